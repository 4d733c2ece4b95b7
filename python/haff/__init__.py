"""haff — the physics of granular gases, exactly.

Coefficients of restitution (viscoelastic exact / series / Padé / fast, dash-pot),
the computer algebra behind them, Giese's vibrating rods, and granular-gas runs
(event-driven MD, DSMC) — the same Rust code as the ``haff`` command, giving the
same numbers bit for bit.

Quick start::

    import haff
    haff.eps([0.1, 1.0, 10.0], law="exact")          # eps(v*), scaled speeds
    sim = haff.Simulation({"system": {"particles": 1000, "packing_fraction": 0.1},
                           "collision": {"law": "constant", "restitution": 0.9},
                           "run": {"collisions_per_particle": 20, "samples": 21}})
    sim.run()
    sim.timeseries["temperature"]

Many runs over a grid of parameters and seeds, on threads, processes or a dask cluster::

    result = haff.study({"system": {...}, "collision": {...}, "run": {...}},
                        vary={"collision.restitution": [0.6, 0.8]}, seeds=8,
                        output_dir="eps-study")
    result.ensemble          # mean and standard error over the seeds (pandas)

Bad input raises :class:`haff.ConfigError` (a ``ValueError``) whose message names the
key or argument and what is allowed.

Every public function and class documents its parameters, units, results and an example
(``help(haff.Simulation)``, ``help(haff.eps)``, ``help(haff.theory)``, ...). The task-by-task
guide is the Python page of the user guide, docs/guide/python.md; python/examples/ holds
two notebooks (a first tour, and a study with error bars against kinetic theory).
"""

from ._haff import ConfigError, __version__
from ._cor import beta, coefficients, dashpot_eps, eps, eps_v, pade
from ._simulation import Simulation
from ._study import StudyResult, study
from ._particles import read_configuration, write_configuration
from . import rods, theory

__all__ = [
    "ConfigError",
    "Simulation",
    "StudyResult",
    "beta",
    "coefficients",
    "dashpot_eps",
    "eps",
    "eps_v",
    "pade",
    "read_configuration",
    "rods",
    "study",
    "theory",
    "write_configuration",
    "__version__",
]
