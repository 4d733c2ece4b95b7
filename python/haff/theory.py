"""Kinetic theory of the homogeneous cooling state, as haff's own checks use it.

Brilliantov & Pöschel, *Kinetic Theory of Granular Gases* (2004): the Enskog collision
frequency, Haff's law T(t) = T0 / (1 + t/tau)^2 and the Sonine coefficient a2.
"""

from __future__ import annotations

import numpy as np

from . import _haff
from ._haff import ConfigError

__all__ = ["collision_frequency", "haff_time", "haff_temperature", "a2", "sonine",
           "cooling_per_collision"]


def collision_frequency(dimension: int, packing_fraction: float, temperature: float = 1.0,
                        diameter: float = 1.0, mass: float = 1.0) -> float:
    """The Enskog collision frequency of one sphere in a Maxwellian gas,
    omega = g2(phi) n sigma^(D-1) S_D sqrt(T / (pi m)) with n = phi / V_ball(sigma / 2) and
    g2 the contact value of the pair correlation (Carnahan-Starling in 3D, Henderson in 2D,
    exact in 1D)."""
    return _haff.theory_collision_frequency(int(dimension), float(packing_fraction),
                                            float(temperature), float(diameter), float(mass))


def haff_time(dimension: int, restitution: float, omega0: float) -> float:
    """Haff's time tau = 2 D / ((1 - eps^2) omega0) of a gas of constant restitution eps
    with collision frequency omega0 at t = 0 (Maxwellian cooling rate)."""
    return _haff.theory_haff_time(int(dimension), float(restitution), float(omega0))


def haff_temperature(t, t0: float, tau: float):
    """Haff's law T(t) = T0 / (1 + t/tau)^2."""
    return t0 / (1.0 + np.asarray(t, float) / tau) ** 2


def a2(dimension: int, restitution: float) -> float:
    """a2 of the homogeneous cooling state, first Sonine approximation linearized in a2
    (van Noije & Ernst 1998)."""
    return _haff.theory_a2(int(dimension), float(restitution))


def sonine(dimension: int, restitution: float, order: int = 3, linear: bool = True):
    """[a2, ..., aK] of the homogeneous cooling state from the Sonine hierarchy truncated at
    order K = ``order`` (2 to 10): linearized in the a_k (K = 2: van Noije & Ernst, equal
    to :func:`a2`; K = 3: the second Sonine approximation of Brilliantov & Pöschel, EPL 74,
    424 (2006)), or with all its quadratic terms (``linear=False``; None where it has no
    solution, below eps of about 0.3). 2D and 3D."""
    result = _haff.theory_sonine(int(dimension), float(restitution), int(order), bool(linear))
    return None if result is None else list(result)


def cooling_per_collision(restitution: float, a2: float = 0.0) -> float:
    """-d ln T / d(collisions per particle) of a 3D gas of constant restitution eps in the
    homogeneous cooling state: (1 - eps^2)/3 * (1 + 3 a2/16) / (1 - a2/16), first order in
    a2. A collision of a Maxwellian gas loses (1 - eps^2) T on average (the
    collision-weighted <(g.n)^2> is 4T/m); with the Sonine correction the cooling rate
    grows by (1 + 3 a2/16) and the collision frequency by (1 - a2/16) (Brilliantov &
    Pöschel, *Kinetic Theory of Granular Gases*, Ch. 7; the latter derived in
    docs/studies.md)."""
    eps, a2 = float(restitution), float(a2)
    if not 0.0 <= eps <= 1.0:
        raise ConfigError(f"restitution: {eps} is out of range; allowed: 0 <= eps <= 1")
    if not -1.0 <= a2 <= 1.0:
        raise ConfigError(f"a2: {a2} is out of range; allowed: -1 <= a2 <= 1 (first order "
                          f"in a small a2)")
    return (1.0 - eps * eps) / 3.0 * (1.0 + 3.0 * a2 / 16.0) / (1.0 - a2 / 16.0)
