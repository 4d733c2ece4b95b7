"""Kinetic theory of the homogeneous cooling state, as haff's own checks use it.

Brilliantov & Pöschel, *Kinetic Theory of Granular Gases* (2004): the Enskog collision
frequency, Haff's law T(t) = T0 / (1 + t/tau)^2 and the Sonine coefficients a2, a3, ...
Quantities are in the run's units (haff's reduced units: lengths in the particle diameter,
masses in the particle mass, temperature as an energy with k_B = 1, all 1 by default; time
then in sigma sqrt(m / T)), or in any consistent units.
"""

from __future__ import annotations

from typing import List, Optional, Union

import numpy as np
import numpy.typing as npt

from . import _haff
from ._haff import ConfigError

__all__ = ["collision_frequency", "haff_time", "haff_temperature", "a2", "sonine",
           "cooling_per_collision"]


def collision_frequency(dimension: int, packing_fraction: float, temperature: float = 1.0,
                        diameter: float = 1.0, mass: float = 1.0) -> float:
    """The Enskog collision frequency of one sphere in a Maxwellian gas.

    omega = g2(phi) n sigma^(D-1) S_D sqrt(T / (pi m)) with n = phi / V_ball(sigma / 2) and
    g2 the contact value of the pair correlation (Carnahan-Starling in 3D, Henderson in 2D,
    exact in 1D); S_D the surface of the unit sphere.

    Parameters
    ----------
    dimension : {1, 2, 3}
        The dimension D.
    packing_fraction : float
        phi, 0 < phi < close packing.
    temperature : float, default 1
        The granular temperature T (an energy, k_B = 1), > 0.
    diameter : float, default 1
        The sphere diameter sigma, > 0.
    mass : float, default 1
        The particle mass m, > 0.

    Returns
    -------
    float
        Collisions per particle per unit time (the unit of time of `temperature`,
        `diameter` and `mass`: sigma sqrt(m / T) in reduced units).

    Raises
    ------
    ConfigError
        An argument out of range.

    Examples
    --------
    >>> import haff
    >>> round(haff.theory.collision_frequency(3, 0.1), 6)
    1.764544
    >>> round(haff.theory.collision_frequency(3, 0.1, temperature=4.0), 6)   # ~ sqrt(T)
    3.529087
    """
    return _haff.theory_collision_frequency(int(dimension), float(packing_fraction),
                                            float(temperature), float(diameter), float(mass))


def haff_time(dimension: int, restitution: float, omega0: float) -> float:
    """Haff's time tau = 2 D / ((1 - eps^2) omega0) of a gas of constant restitution.

    The time scale of Haff's law T(t) = T0 / (1 + t/tau)^2 for a gas of constant
    coefficient of restitution eps and collision frequency omega0 at t = 0 (the
    Maxwellian cooling rate, a2 = 0).

    Parameters
    ----------
    dimension : {1, 2, 3}
        The dimension D.
    restitution : float
        eps, 0 <= eps < 1.
    omega0 : float
        The collision frequency at t = 0 (e.g. :func:`collision_frequency`), > 0.

    Returns
    -------
    float
        tau, in the unit of time of `omega0`.

    Raises
    ------
    ConfigError
        An argument out of range.

    Examples
    --------
    >>> import haff
    >>> omega0 = haff.theory.collision_frequency(3, 0.1)
    >>> round(haff.theory.haff_time(3, 0.9, omega0), 4)
    17.8964
    """
    return _haff.theory_haff_time(int(dimension), float(restitution), float(omega0))


def haff_temperature(t: npt.ArrayLike, t0: float, tau: float
                     ) -> Union[float, npt.NDArray[np.float64]]:
    """Haff's law T(t) = T0 / (1 + t/tau)^2.

    Parameters
    ----------
    t : float or array_like
        Times, in the unit of `tau`.
    t0 : float
        The temperature T0 at t = 0.
    tau : float
        Haff's time (:func:`haff_time`).

    Returns
    -------
    float or numpy.ndarray of float64
        T at the times `t`, in the unit of `t0` (an array of the shape of `t`; a numpy
        float for a scalar `t`).

    Examples
    --------
    >>> import haff
    >>> haff.theory.haff_temperature([0.0, 10.0, 30.0], 1.0, 10.0)
    array([1.    , 0.25  , 0.0625])
    """
    return t0 / (1.0 + np.asarray(t, float) / tau) ** 2


def a2(dimension: int, restitution: float) -> float:
    """a2 of the homogeneous cooling state, van Noije & Ernst's first Sonine approximation.

    The Sonine coefficient a2 = <c^4> / <c^4>_Maxwell - 1 of the scaled velocity
    distribution of a gas of constant restitution eps, from the first Sonine approximation
    linearized in a2 (van Noije & Ernst 1998; Brilliantov & Pöschel 2004, Ch. 7). The
    ``a2`` column of ``timeseries.csv`` measures the same coefficient.

    Parameters
    ----------
    dimension : {1, 2, 3}
        The dimension D.
    restitution : float
        eps, 0 <= eps <= 1.

    Returns
    -------
    float
        a2 (dimensionless; 0 at eps = 1).

    Raises
    ------
    ConfigError
        An argument out of range.

    See Also
    --------
    sonine : higher Sonine approximations, better below eps of about 0.8.

    Examples
    --------
    >>> import haff
    >>> round(haff.theory.a2(3, 0.9), 6)
    -0.01456
    >>> round(haff.theory.a2(3, 0.5), 6)
    0.052459
    """
    return _haff.theory_a2(int(dimension), float(restitution))


def sonine(dimension: int, restitution: float, order: int = 3,
           linear: bool = True) -> Optional[List[float]]:
    """[a2, ..., aK] of the homogeneous cooling state from the truncated Sonine hierarchy.

    The hierarchy of the moments of the Boltzmann equation truncated at order
    K = `order`, its collisional moments computed by an exact quadrature, solved either
    linearized in the a_k (K = 2: van Noije & Ernst, equal to :func:`a2`; K = 3: the
    second Sonine approximation of Brilliantov & Pöschel, EPL 74, 424 (2006)) or with all
    its quadratic terms (``linear=False``).

    Parameters
    ----------
    dimension : {2, 3}
        The dimension D.
    restitution : float
        eps, 0 <= eps <= 1.
    order : int, default 3
        K, 2 to 10 (K = 6 takes about 6 s; the GIL is released).
    linear : bool, default True
        Linearize in the a_k; False keeps every term.

    Returns
    -------
    list of float or None
        [a2, a3, ..., aK]; None where the full hierarchy has no solution (Newton's method
        does not converge: e.g. at K = 6 for eps = 0.1; it does at eps = 0.2).

    Raises
    ------
    ConfigError
        An argument out of range.

    Examples
    --------
    >>> import haff
    >>> [round(a, 5) for a in haff.theory.sonine(3, 0.9)]             # a2, a3
    [-0.01566, -0.00387]
    >>> [round(a, 5) for a in haff.theory.sonine(3, 0.9, linear=False)]
    [-0.01567, -0.00391]
    """
    result = _haff.theory_sonine(int(dimension), float(restitution), int(order), bool(linear))
    return None if result is None else list(result)


def cooling_per_collision(restitution: float, a2: float = 0.0) -> float:
    """-d ln T / d(collisions per particle) of a 3D gas in the homogeneous cooling state.

    (1 - eps^2)/3 * (1 + 3 a2/16) / (1 - a2/16), first order in a2, for a gas of constant
    restitution eps. A collision of a Maxwellian gas loses (1 - eps^2) T on average (the
    collision-weighted <(g.n)^2> is 4T/m); with the Sonine correction the cooling rate
    grows by (1 + 3 a2/16) and the collision frequency by (1 - a2/16) (Brilliantov &
    Pöschel, *Kinetic Theory of Granular Gases*, Ch. 7; the latter derived in
    docs/studies.md). It compares with the slope of ln(temperature) against
    collisions_per_particle of ``timeseries.csv``.

    Parameters
    ----------
    restitution : float
        eps, 0 <= eps <= 1.
    a2 : float, default 0
        The Sonine coefficient a2 (measured, or :func:`a2`), -1 <= a2 <= 1.

    Returns
    -------
    float
        The decay of ln T per collision per particle (dimensionless).

    Raises
    ------
    ConfigError
        An argument out of range.

    Examples
    --------
    >>> import haff
    >>> round(haff.theory.cooling_per_collision(0.9), 5)                # Maxwellian
    0.06333
    >>> round(haff.theory.cooling_per_collision(0.9, haff.theory.a2(3, 0.9)), 5)
    0.0631
    """
    eps, a2 = float(restitution), float(a2)
    if not 0.0 <= eps <= 1.0:
        raise ConfigError(f"restitution: {eps} is out of range; allowed: 0 <= eps <= 1")
    if not -1.0 <= a2 <= 1.0:
        raise ConfigError(f"a2: {a2} is out of range; allowed: -1 <= a2 <= 1 (first order "
                          f"in a small a2)")
    return (1.0 - eps * eps) / 3.0 * (1.0 + 3.0 * a2 / 16.0) / (1.0 - a2 / 16.0)
