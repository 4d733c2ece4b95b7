"""The coefficient of restitution and the computer algebra behind it."""

from __future__ import annotations

import warnings
from decimal import Decimal
from typing import List, Optional, Tuple, Union

import numpy as np

from . import _haff
from ._haff import ConfigError

ArrayLike = Union[float, "np.typing.ArrayLike"]


def _floats(values, name: str) -> np.ndarray:
    """`values` as a float64 array (any shape), or ConfigError naming `name`."""
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ConfigError(f"{name}: not numbers ({error})") from None
    return array


def _each(values, name: str, evaluate) -> np.ndarray:
    """Applies the Rust loop `evaluate` to the flattened values, keeping their shape."""
    array = _floats(values, name)
    flat = np.ascontiguousarray(array.ravel())
    return evaluate(flat).reshape(array.shape)


def _warn_beyond(beyond: int, total: int, law: str, validity: str) -> None:
    if beyond:
        warnings.warn(
            f"law {law!r} is {validity}: {beyond} of the {total} values are the "
            "approximation's, not the viscoelastic law's",
            RuntimeWarning,
            stacklevel=3,
        )


def eps(vstar, law: str = "fast") -> np.ndarray:
    """The coefficient of restitution eps(v*) of viscoelastic spheres.

    Parameters
    ----------
    vstar : float or array-like
        Scaled impact speeds v* = beta^(1/2) v^(1/10), 0 <= v* <= 1e6
        (Eq. (9) of Müller & Pöschel 2011; beta from :func:`beta`).
    law : str
        Every name ``haff cor eps --law`` takes: ``exact`` (integration of the
        collision equation, Eq. (3) of Schwager & Pöschel 2008, with the
        force-vanishes criterion), ``exact-naive`` (overlap-vanishes criterion),
        ``fast`` (the exact law tabulated to ~1e-13), ``fast-naive``,
        ``pade:M/N`` and ``series:K`` (any order, from the coefficients this
        package computes), ``pade-paper:M/N`` (Table I of MP2011) and
        ``series-paper:K`` (Table V of SP2008).

    Returns
    -------
    numpy.ndarray of float64, the shape of `vstar` (0-d for a scalar).

    A series or Padé form evaluated beyond its range of validity (past a pole,
    eps outside [0, 1], beyond the radius of convergence 1.06) returns its values
    with a ``RuntimeWarning``. The loop runs in Rust with the GIL released.
    """
    counts = {}

    def evaluate(flat):
        values, beyond, validity = _haff.eps(flat, law)
        counts.update(beyond=beyond, validity=validity, total=flat.size)
        return values

    out = _each(vstar, "vstar", evaluate)
    _warn_beyond(counts["beyond"], counts["total"], law, counts["validity"])
    return out


def eps_v(v, beta: float, law: str = "fast", units: str = "si") -> np.ndarray:
    """eps at physical impact speeds v, with v* = beta^(1/2) v^(1/10).

    Parameters
    ----------
    v : float or array-like
        Normal impact speeds (m/s with ``units="si"``, cm/s with ``"cgs"``), >= 0.
    beta : float
        The material constant of Eq. (8) of MP2011 in the same unit system,
        (s/m)^(1/5) or (s/cm)^(1/5); 1e-30 <= beta <= 1e30. See :func:`beta`.
    law : str
        As for :func:`eps`.
    units : str
        ``"si"`` or ``"cgs"``: the unit system of `v` and `beta` (as
        ``haff cor eps --units``).
    """
    if units not in ("si", "cgs"):
        raise ConfigError(f"units: '{units}' is not a unit system; allowed: si, cgs")
    counts = {}

    def evaluate(flat):
        values, beyond, validity = _haff.eps_v(flat, float(beta), law)
        counts.update(beyond=beyond, validity=validity, total=flat.size)
        return values

    out = _each(v, "v", evaluate)
    _warn_beyond(counts["beyond"], counts["total"], law, counts["validity"])
    return out


def beta(
    material: Optional[str] = None,
    radius: Optional[float] = None,
    dissipative_constant: Optional[float] = None,
    units: str = "si",
    young: Optional[float] = None,
    poisson: Optional[float] = None,
    density: Optional[float] = None,
) -> float:
    """The material constant beta of two equal spheres (Eq. (8) of MP2011).

    beta = (3/2) A (rho / m_eff)^(2/5) with rho = 2 Y sqrt(R_eff) / (3 (1 - nu^2)), in
    (s/m)^(1/5) (``units="si"``) or (s/cm)^(1/5) (``"cgs"``), from the sphere `radius` (m) and the dissipative constant `dissipative_constant`
    A (s) of the material: a built-in `material` (``steel``, ``soda-lime-glass``,
    ``aluminium``, ``ice``; Young's modulus, Poisson ratio and density from
    handbooks) or `young` (Pa), `poisson` and `density` (kg/m^3), which also
    override the built-in values. No material carries A: give it.
    """
    if radius is None:
        raise ConfigError("radius: missing (the sphere radius in m)")
    if dissipative_constant is None:
        raise ConfigError("dissipative_constant: missing (A in s; no material carries one)")
    return _haff.beta(
        material,
        float(radius),
        float(dissipative_constant),
        units,
        None if young is None else float(young),
        None if poisson is None else float(poisson),
        None if density is None else float(density),
    )


def dashpot_eps(damping_ratio, criterion: str = "improved") -> np.ndarray:
    """eps of the linear dash-pot, F = -k x - gamma x' (Sec. 4 of Schwager & Pöschel 2008).

    Parameters
    ----------
    damping_ratio : float or array-like
        R = gamma / (2 sqrt(m_eff k)) >= 0 (R >= 1: overdamped).
    criterion : str
        ``"improved"`` (the collision ends when the force vanishes: eps by the
        corrected Eqs. (10), (12), see docs/errata.md) or ``"naive"`` (when the
        overlap vanishes: eps = exp(-pi R / sqrt(1 - R^2)), no separation for R >= 1,
        eps = 0 there).
    """
    return _each(damping_ratio, "damping_ratio", lambda flat: _haff.dashpot_eps(flat, criterion))


def _check_digits(digits) -> None:
    if isinstance(digits, bool) or not isinstance(digits, (int, np.integer)):
        raise ConfigError(f"digits: {digits!r} is not an integer; allowed: 1 <= digits <= 60")


def coefficients(kind: str, order: int, digits: int = 20, as_string: bool = False) -> List:
    """The series coefficients of Schwager & Pöschel 2008, k = 0..order, to full precision.

    Parameters
    ----------
    kind : str
        ``"h"`` (eps = sum h_k v*^k, Table V / Eq. (36)), ``"c"`` (the
        coefficients of the time of the collision), ``"a"`` (tau_max = sum a_n A^n,
        Eq. (B3)) or ``"b"`` (x_max, Eq. (B5)); computed exactly / in high
        precision by the computer algebra of ``haff-series`` (order <= 100).
    digits : int
        Significant digits, 1..60.
    as_string : bool
        Decimal strings instead of :class:`decimal.Decimal`.

    Returns a list of ``decimal.Decimal`` (full precision); ``numpy.asarray(x, float)``
    gives floats.
    """
    _check_digits(digits)
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)):
        raise ConfigError(f"order: {order!r} is not an integer")
    values = _haff.coefficients_decimal(kind, int(order), int(digits))
    return values if as_string else [Decimal(x) for x in values]


def pade(m: int, n: int, digits: Optional[int] = None) -> Tuple:
    """The Padé approximant [m/n] of eps(v*) (Müller & Pöschel 2011, Eq. (20)).

    eps = (a_0 + a_1 v* + ... + a_m v*^m) / (1 + b_1 v* + ... + b_n v*^n), from the
    coefficients h_0..h_{m+n} that :func:`coefficients` computes. Returns ``(a, b)``
    as float64 arrays (b[0] = 1), or as lists of ``decimal.Decimal`` with `digits`
    significant digits (1..60) when `digits` is given.
    """
    for name, value in (("m", m), ("n", n)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise ConfigError(f"{name}: {value!r} is not an integer; allowed: 0 <= {name} <= 60")
    if digits is not None:
        _check_digits(digits)
    a, b, _poles = _haff.pade_decimal(int(m), int(n), 40 if digits is None else int(digits))
    if digits is not None:
        return [Decimal(x) for x in a], [Decimal(x) for x in b]
    return np.array([float(x) for x in a]), np.array([float(x) for x in b])
