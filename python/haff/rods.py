"""Giese's vibrating rods: the coefficient of restitution of two rods with internal modes.

The collision equation, Eq. (3) of Giese, of two rods of length ratio gamma with
contact stiffness kappa: deterministic (a cold bath, the modes start at rest) and
stochastic (the modes thermalized, the noise of Eq. (5)).
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _haff

__all__ = ["deterministic", "closed_form", "collide"]


def deterministic(gamma, kappa, step: float = 0.02):
    """eps of Eq. (3) at T_bath = 0, solved numerically (as ``haff rods deterministic``).

    Parameters
    ----------
    gamma : float or array-like
        Length ratio of the two rods, 1e-3 <= gamma <= 1e3.
    kappa : float or array-like
        Contact stiffness, 1 <= kappa <= 1e5.
    step : float
        Integration step h kappa, 0 < step < 1 (default 0.02, the command's).

    Returns a float for scalars, else an array of the broadcast shape. The work of one
    value is bounded (about 50 s; the work grows as kappa / step and as 1/gamma^2 or
    gamma^2 away from 1).
    """
    g, k = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(kappa, float))
    out = np.array([_haff.rods_deterministic(float(a), float(b), float(step))
                    for a, b in zip(g.ravel(), k.ravel())]).reshape(g.shape)
    return float(out) if out.ndim == 0 else out


def closed_form(gamma, kappa, general: bool = False):
    """Giese's closed form eps = min(gamma, 1/gamma) + ln(kappa |Gamma2 - Gamma1|) / kappa.

    Asymptotic in kappa |Gamma2 - Gamma1| >> 1 (Gamma1 = 1 + gamma, Gamma2 = 1 + 1/gamma);
    ``general=True`` takes the generalized span min(Gamma1, Gamma2, |Gamma2 - Gamma1|).
    NaN where undefined (gamma = 1).
    """
    g, k = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(kappa, float))
    out = np.array([_haff.rods_closed_form(float(a), float(b), bool(general))
                    for a, b in zip(g.ravel(), k.ravel())]).reshape(g.shape)
    return float(out) if out.ndim == 0 else out


def collide(gamma: float, kappa: float, bath_ratio: Optional[float] = None,
            realizations: int = 8000, seed: int = 1) -> np.ndarray:
    """eps of `realizations` collisions with thermal noise (as ``haff rods collide``).

    Parameters
    ----------
    bath_ratio : float or None
        E_tr / T_bath, the translational energy over the bath temperature,
        1e-4..1e6; None (or inf): a cold bath.
    realizations : int
        1..1e7; they share the machine's cores (GIL released).
    seed : int
        The random streams, one per realization: the same seed gives the same array.
    """
    ratio = float("inf") if bath_ratio is None else float(bath_ratio)
    if isinstance(realizations, bool) or not isinstance(realizations, (int, np.integer)):
        raise _haff.ConfigError(f"realizations: {realizations!r} is not an integer")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise _haff.ConfigError(f"seed: {seed!r} is not an integer >= 0")
    return _haff.rods_collide(float(gamma), float(kappa), ratio, int(realizations), int(seed))
