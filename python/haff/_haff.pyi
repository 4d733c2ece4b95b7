"""Type stubs of the extension module haff._haff (the Rust side of the haff package).

The public API is in haff/__init__.py (haff.eps, haff.Simulation, ...), which wraps these.
"""

from pathlib import Path
from typing import Any, Callable, Optional, final

import numpy as np
import numpy.typing as npt

# The runtime's __all__ (PyO3 lists every name a module adds, in registration order).
__all__ = [
    "ConfigError", "__version__", "eps", "eps_v", "beta", "dashpot_eps", "law_validity",
    "coefficients_decimal", "pade_decimal", "rods_deterministic", "rods_closed_form",
    "rods_collide", "_Simulation", "study_plan", "study_open", "study_run", "study_aggregate",
    "read_configuration", "write_configuration", "theory_collision_frequency",
    "theory_haff_time", "theory_a2", "theory_sonine",
]

__version__: str

class ConfigError(ValueError):
    """Bad input: the message names the key or argument and what is allowed.

    Declared in the module ``haff`` (its ``__module__``), which re-exports it.
    """

_Float1D = npt.NDArray[np.float64]
_Callback = Optional[Callable[[int, int, str], Any]]

def eps(vstar: _Float1D, law: str) -> tuple[_Float1D, int, str]: ...
def eps_v(v: _Float1D, beta: float, law: str) -> tuple[_Float1D, int, str]: ...
def beta(
    material: Optional[str],
    radius: float,
    dissipative_constant: float,
    units: str,
    young: Optional[float],
    poisson: Optional[float],
    density: Optional[float],
) -> float: ...
def dashpot_eps(damping_ratio: _Float1D, criterion: str) -> _Float1D: ...
def law_validity(law: str) -> tuple[float, float, str]: ...
def coefficients_decimal(kind: str, order: int, digits: int) -> list[str]: ...
def pade_decimal(m: int, n: int, digits: int) -> tuple[list[str], list[str], list[float]]: ...
def rods_deterministic(gamma: float, kappa: float, step: float) -> float: ...
def rods_closed_form(gamma: float, kappa: float, general: bool) -> float: ...
def rods_collide(
    gamma: float, kappa: float, bath_ratio: float, realizations: int, seed: int
) -> _Float1D: ...

def theory_collision_frequency(
    dimension: int, packing_fraction: float, temperature: float, diameter: float, mass: float
) -> float: ...
def theory_haff_time(dimension: int, restitution: float, omega0: float) -> float: ...
def theory_a2(dimension: int, restitution: float) -> float: ...
def theory_sonine(
    dimension: int, restitution: float, order: int = 3, linear: bool = True
) -> Optional[list[float]]: ...
def study_plan(
    text: str, origin: str, keep_going: bool = False
) -> tuple[list[str], list[str], list[tuple[int, int, int]], list[tuple[int, str]]]: ...
def study_open(text: str, origin: str, dir: str, force: bool = False) -> None: ...
def study_run(
    text: str,
    origin: str,
    dir: str,
    point: int,
    replica: int,
    threads: int = 1,
    checkpoint_every: Optional[int] = None,
) -> str: ...
def study_aggregate(
    text: str, origin: str, dir: str, outcomes: list[str], invalid: list[tuple[int, str]]
) -> str: ...

def read_configuration(
    path: str,
    format: str,
    dimension: int = 3,
    frame: int = ...,  # -1: the last frame
    check: bool = True,
    sides: Optional[list[float]] = None,
) -> dict[str, Any]: ...
def write_configuration(
    path: str,
    format: str,
    box: list[float],
    positions: npt.NDArray[np.float64],
    velocities: Optional[npt.NDArray[np.float64]] = None,
    diameters: Optional[npt.NDArray[np.float64]] = None,
    masses: Optional[npt.NDArray[np.float64]] = None,
    species: Optional[list[int]] = None,
    spins: Optional[npt.NDArray[np.float64]] = None,
    time: Optional[float] = None,
) -> None: ...

@final  # PyO3 classes cannot be subclassed
class _Simulation:
    @staticmethod
    def from_toml(text: str, origin: str) -> _Simulation: ...
    @staticmethod
    def with_initial(text: str, origin: str, box: list[float], positions: npt.NDArray[np.float64],
                     velocities: Optional[npt.NDArray[np.float64]] = ..., diameters: Optional[_Float1D] = ...,
                     masses: Optional[_Float1D] = ..., species: Optional[list[int]] = ...,
                     spins: Optional[npt.NDArray[np.float64]] = ...) -> _Simulation: ...
    @staticmethod
    def from_path(path: str) -> _Simulation: ...
    @staticmethod
    def load(path: str) -> _Simulation: ...
    def run(self, callback: _Callback = None, stop_after: Optional[int] = None) -> bool: ...
    def advance(
        self,
        time: Optional[float] = None,
        collisions_per_particle: Optional[float] = None,
        callback: _Callback = None,
    ) -> bool: ...
    def timeseries(self) -> dict[str, np.ndarray]: ...
    def species_timeseries(self) -> dict[str, np.ndarray] | None: ...
    def walls(self) -> dict[str, Any] | None:
        """The columns of walls.csv: time, collisions_per_particle, axis, side, collisions,
        momentum, energy (one row per wall and sample)."""
    def pressure(self) -> dict[str, _Float1D] | None:
        """The columns of pressure.csv: time, collisions_per_particle, pxx, pyy, pzz, pxy,
        pxz, pyz, kinetic_xy."""
    def rheology(self) -> str | None:
        """summary.json's rheology as JSON text (None without [shear])."""
    def green_kubo(self) -> str | None:
        """summary.json's green_kubo as JSON text (None without output.pressure or under
        [shear])."""
    def profiles(self) -> dict[str, _Float1D] | None:
        """The columns of profiles.csv (one row per slab and sample; NaN for empty cells)."""
    def velocity_histograms(self) -> list[tuple[float, float, float, _Float1D, _Float1D]]: ...
    def modes(self) -> dict[str, _Float1D]:
        """The columns of modes.csv: time, collisions_per_particle, k, transverse_energy,
        longitudinal_energy, density_power (one row per sample and shell)."""
    def structure(self) -> tuple[_Float1D, _Float1D, list[str], _Float1D, _Float1D]:
        """The columns of structure.csv: (time, collisions_per_particle, function ("S" or
        "g"), x, value), per sample S(k) rows then g(r) rows."""
    def field_files(self) -> list[tuple[float, str]]:
        """(time, file name in the output directory) of the fields_NNNNNN.vti written."""
    def snapshot_files(self) -> list[tuple[float, str]]:
        """(time, file name in the output directory) of the snapshot_NNNNNN.vtu written."""
    def set_output_dir(self, dir: str, force: bool) -> None:
        """Claims dir as haff run --out does; field and snapshot files go there."""
    def particles(
        self,
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], _Float1D, _Float1D]: ...
    def temperature(self) -> float: ...
    def counters(self) -> tuple[int, int, float, int]:
        """(collisions, events, energy_lost, tc_elastic_collisions) so far."""
    def initial_state_json(self) -> str | None:
        """How a dense start was grown (summary.json's initial_state) as JSON, or None."""
    def contact_statistics(self) -> dict[str, float] | None: ...
    def description_json(self) -> str: ...
    def save(self, path: str) -> None: ...
    def write(self, dir: str, force: bool) -> None: ...
    @property
    def time(self) -> float: ...
    @property
    def output_dir(self) -> Optional[Path]:
        """The output directory, None until set."""
    @property
    def complete(self) -> bool: ...
    @property
    def particle_count(self) -> int: ...
    @property
    def dimension(self) -> int: ...
    @property
    def wall_seconds(self) -> float: ...
