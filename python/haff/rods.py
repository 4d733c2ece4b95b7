"""Giese's vibrating rods: the coefficient of restitution of two rods with internal modes.

The collision equation, Eq. (3) of Giese, of two rods of length ratio gamma with
contact stiffness kappa: deterministic (a cold bath, the modes start at rest) and
stochastic (the modes thermalized, the noise of Eq. (5)). Dimensionless throughout: kappa
is the contact stiffness in units of the rods' own, eps a ratio of speeds.
"""

from __future__ import annotations

from typing import Callable, Optional, Union

import numpy as np
import numpy.typing as npt

from . import _haff

__all__ = ["deterministic", "closed_form", "collide"]

FloatOrArray = Union[float, npt.NDArray[np.float64]]


def _broadcast(gamma: npt.ArrayLike, kappa: npt.ArrayLike,
               f: Callable[[float, float], float]) -> FloatOrArray:
    """`f` at every pair of the broadcast arguments: a float for scalars, else an array."""
    g, k = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(kappa, float))
    out = np.array([f(float(a), float(b))
                    for a, b in zip(g.ravel(), k.ravel())]).reshape(g.shape)
    return float(out) if out.ndim == 0 else out


def deterministic(gamma: npt.ArrayLike, kappa: npt.ArrayLike,
                  step: float = 0.02) -> FloatOrArray:
    """eps of Eq. (3) at T_bath = 0, solved numerically (as ``haff rods deterministic``).

    Parameters
    ----------
    gamma : float or array_like
        Length ratio of the two rods, 1e-3 <= gamma <= 1e3.
    kappa : float or array_like
        Contact stiffness (dimensionless), 1 <= kappa <= 1e5; broadcast with `gamma`.
    step : float, default 0.02
        Integration step h kappa, 0 < step < 1 (the command's default).

    Returns
    -------
    float or numpy.ndarray of float64
        eps: a float for scalar arguments, else an array of the broadcast shape.

    Raises
    ------
    ConfigError
        An argument out of range, or one value needing more than about 50 s (the work
        grows as kappa / step and as 1/gamma^2 or gamma^2 away from 1).

    See Also
    --------
    closed_form : Giese's asymptotic formula for the same eps.

    Examples
    --------
    >>> import haff
    >>> round(haff.rods.deterministic(0.5, 100.0), 6)
    0.550068
    >>> haff.rods.deterministic([0.5, 2.0], 100.0).round(6)   # the same pair of rods
    array([0.550068, 0.550068])
    """
    return _broadcast(gamma, kappa,
                      lambda a, b: _haff.rods_deterministic(a, b, float(step)))


def closed_form(gamma: npt.ArrayLike, kappa: npt.ArrayLike,
                general: bool = False) -> FloatOrArray:
    """Giese's closed form eps = min(gamma, 1/gamma) + ln(kappa |Gamma2 - Gamma1|) / kappa.

    Asymptotic in kappa |Gamma2 - Gamma1| >> 1 (Gamma1 = 1 + gamma, Gamma2 = 1 + 1/gamma);
    the closed-form columns of ``haff rods deterministic``.

    Parameters
    ----------
    gamma : float or array_like
        Length ratio of the two rods, 1e-3 <= gamma <= 1e3.
    kappa : float or array_like
        Contact stiffness, 1 <= kappa <= 1e5; broadcast with `gamma`.
    general : bool, default False
        Take the generalized span min(Gamma1, Gamma2, |Gamma2 - Gamma1|) instead of
        |Gamma2 - Gamma1|.

    Returns
    -------
    float or numpy.ndarray of float64
        eps (NaN where undefined: gamma = 1), a float for scalar arguments.

    Raises
    ------
    ConfigError
        An argument out of range.

    Examples
    --------
    >>> import haff
    >>> haff.rods.closed_form([0.5, 0.8, 1.0], 100.0).round(6)
    array([0.550106, 0.838067,      nan])
    """
    return _broadcast(gamma, kappa,
                      lambda a, b: _haff.rods_closed_form(a, b, bool(general)))


def collide(gamma: float, kappa: float, bath_ratio: Optional[float] = None,
            realizations: int = 8000, seed: int = 1) -> npt.NDArray[np.float64]:
    """eps of `realizations` collisions with thermal noise (as ``haff rods collide``).

    Parameters
    ----------
    gamma : float
        Length ratio of the two rods, 1e-3 <= gamma <= 1e3.
    kappa : float
        Contact stiffness, 1 <= kappa <= 1e5.
    bath_ratio : float or None
        E_tr / T_bath, the translational energy of the collision over the temperature of
        the rods' modes, 1e-4..1e6; None (or inf): a cold bath.
    realizations : int, default 8000
        1..1e7 collisions; they share the machine's cores (GIL released).
    seed : int, default 1
        The random streams, one per realization: the same seed gives the same array.

    Returns
    -------
    numpy.ndarray of float64
        eps of each realization, shape (realizations,).

    Raises
    ------
    ConfigError
        An argument out of range or not an integer.

    Examples
    --------
    A hot bath (E_tr = 10 T_bath) scatters eps around, and above, the cold value 0.55:

    >>> import haff
    >>> e = haff.rods.collide(0.5, 100.0, bath_ratio=10.0, realizations=200, seed=1)
    >>> e.shape, round(float(e.mean()), 3)
    ((200,), 0.745)
    """
    ratio = float("inf") if bath_ratio is None else float(bath_ratio)
    if isinstance(realizations, bool) or not isinstance(realizations, (int, np.integer)):
        raise _haff.ConfigError(f"realizations: {realizations!r} is not an integer")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise _haff.ConfigError(f"seed: {seed!r} is not an integer >= 0")
    return _haff.rods_collide(float(gamma), float(kappa), ratio, int(realizations), int(seed))
