"""The coefficient of restitution and the computer algebra behind it."""

from __future__ import annotations

import warnings
from decimal import Decimal
from typing import Any, Callable, Dict, List, Literal, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import _haff
from ._haff import ConfigError

ArrayLike = npt.ArrayLike
Floats = npt.NDArray[np.float64]


def _floats(values: ArrayLike, name: str) -> Floats:
    """`values` as a float64 array (any shape), or ConfigError naming `name`."""
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ConfigError(f"{name}: not numbers ({error})") from None
    return array


def _each(values: ArrayLike, name: str, evaluate: Callable[[Floats], Floats]) -> Floats:
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


def eps(vstar: ArrayLike, law: str = "fast") -> Floats:
    """The coefficient of restitution eps(v*) of viscoelastic spheres.

    The same numbers as ``haff cor eps --law LAW --vstar ...``. The loop runs in Rust
    with the GIL released.

    Parameters
    ----------
    vstar : float or array_like
        Scaled impact speeds v* = beta^(1/2) v^(1/10), dimensionless, 0 <= v* <= 1e6
        (Eq. (9) of Müller & Pöschel 2011; beta from :func:`beta`, or use :func:`eps_v`
        for speeds in m/s).
    law : str, default "fast"
        Every name ``haff cor eps --law`` takes: ``exact`` (integration of the
        collision equation, Eq. (3) of Schwager & Pöschel 2008, with the
        force-vanishes criterion), ``exact-naive`` (overlap-vanishes criterion),
        ``fast`` (the exact law tabulated to ~1e-13), ``fast-naive``,
        ``pade:M/N`` and ``series:K`` (any order, from the coefficients this
        package computes), ``pade-paper:M/N`` (Table I of MP2011) and
        ``series-paper:K`` (Table V of SP2008).

    Returns
    -------
    numpy.ndarray of float64
        eps in [0, 1] for the exact laws, of the shape of `vstar` (0-d for a scalar).

    Raises
    ------
    ConfigError
        An unknown `law`, or a v* outside [0, 1e6] or NaN (the message names the index).

    Warns
    -----
    RuntimeWarning
        A series or Padé form evaluated beyond its range of validity (past a pole, eps
        outside [0, 1], beyond the radius of convergence 1.06 of the series): the values
        are returned, the warning says how many are the approximation's only.

    See Also
    --------
    eps_v : eps at physical impact speeds.

    Examples
    --------
    >>> import haff
    >>> haff.eps([0.1, 1.0, 3.0], law="exact").round(6)
    array([0.988547, 0.393931, 0.02944 ])
    >>> round(float(haff.eps(0.5, law="pade-paper:3/6")), 6)
    0.760038
    """
    counts: Dict[str, Union[int, str]] = {}

    def evaluate(flat: Floats) -> Floats:
        values, beyond, validity = _haff.eps(flat, law)
        counts.update(beyond=beyond, validity=validity, total=flat.size)
        return values

    out = _each(vstar, "vstar", evaluate)
    _warn_beyond(int(counts["beyond"]), int(counts["total"]), law, str(counts["validity"]))
    return out


def eps_v(v: ArrayLike, beta: float, law: str = "fast", units: str = "si") -> Floats:
    """eps at physical impact speeds v, with v* = beta^(1/2) v^(1/10).

    The same numbers as ``haff cor eps --law LAW --v ... --beta B --units U``.

    Parameters
    ----------
    v : float or array_like
        Normal impact speeds, m/s with ``units="si"`` or cm/s with ``"cgs"``, >= 0 (up to
        the speed where v* reaches 1e6).
    beta : float
        The material constant of Eq. (8) of MP2011 in the same unit system,
        (s/m)^(1/5) or (s/cm)^(1/5); 1e-30 <= beta <= 1e30. See :func:`beta`.
    law : str, default "fast"
        As for :func:`eps`.
    units : {"si", "cgs"}
        The unit system of `v` and `beta` (as ``haff cor eps --units``).

    Returns
    -------
    numpy.ndarray of float64
        eps, of the shape of `v`.

    Raises
    ------
    ConfigError
        An unknown `law` or `units`, `beta` or a speed out of range.

    Warns
    -----
    RuntimeWarning
        As :func:`eps`, for speeds beyond the validity of a series or Padé form.

    Examples
    --------
    Steel spheres of radius 5 mm with a dissipative constant A = 1e-7 s:

    >>> import haff
    >>> b = haff.beta(material="steel", radius=0.005, dissipative_constant=1e-7)
    >>> haff.eps_v([0.1, 1.0, 10.0], b).round(4)     # at 0.1, 1 and 10 m/s
    array([0.9886, 0.9821, 0.9717])
    """
    if units not in ("si", "cgs"):
        raise ConfigError(f"units: '{units}' is not a unit system; allowed: si, cgs")
    counts: Dict[str, Union[int, str]] = {}

    def evaluate(flat: Floats) -> Floats:
        values, beyond, validity = _haff.eps_v(flat, float(beta), law)
        counts.update(beyond=beyond, validity=validity, total=flat.size)
        return values

    out = _each(v, "v", evaluate)
    _warn_beyond(int(counts["beyond"]), int(counts["total"]), law, str(counts["validity"]))
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

    beta = (3/2) A (rho / m_eff)^(2/5) with rho = 2 Y sqrt(R_eff) / (3 (1 - nu^2)): the
    scale of the impact speed in v* = beta^(1/2) v^(1/10). The same number as the
    ``--material``/``--radius``/``--dissipative-constant`` options of ``haff cor eps``.

    Parameters
    ----------
    material : str, optional
        A built-in material: ``steel``, ``soda-lime-glass``, ``aluminium``, ``ice``
        (Young's modulus, Poisson ratio and density from handbooks). No material carries
        A: give `dissipative_constant`.
    radius : float
        The sphere radius in m (whatever `units`).
    dissipative_constant : float
        The dissipative constant A of the material in s, > 0.
    units : {"si", "cgs"}
        The unit system of the result: (s/m)^(1/5) or (s/cm)^(1/5).
    young, poisson, density : float, optional
        Young's modulus Y (Pa), the Poisson ratio nu and the density (kg/m^3): all three
        without `material`, or any of them to override the material's.

    Returns
    -------
    float
        beta in (s/m)^(1/5) (``units="si"``) or (s/cm)^(1/5) (``"cgs"``).

    Raises
    ------
    ConfigError
        A missing `radius` or `dissipative_constant`, an unknown material, a property
        missing or out of range.

    Examples
    --------
    >>> import haff
    >>> round(haff.beta(material="steel", radius=0.005, dissipative_constant=1e-7), 6)
    0.015736
    >>> round(haff.beta(young=2e11, poisson=0.3, density=7800.0, radius=0.005,
    ...                 dissipative_constant=1e-7), 6)
    0.015777
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


def dashpot_eps(damping_ratio: ArrayLike, criterion: str = "improved") -> Floats:
    """eps of the linear dash-pot, F = -k x - gamma x' (Sec. 4 of Schwager & Pöschel 2008).

    The same numbers as ``haff cor dashpot``.

    Parameters
    ----------
    damping_ratio : float or array_like
        R = gamma / (2 sqrt(m_eff k)), dimensionless, >= 0 (R >= 1: overdamped).
    criterion : {"improved", "naive"}
        ``"improved"``: the collision ends when the force vanishes (eps by the corrected
        Eqs. (10), (12), see docs/errata.md); ``"naive"``: when the overlap vanishes
        (eps = exp(-pi R / sqrt(1 - R^2)); no separation for R >= 1, eps = 0 there).

    Returns
    -------
    numpy.ndarray of float64
        eps, of the shape of `damping_ratio`.

    Raises
    ------
    ConfigError
        A negative or non-finite ratio, an unknown criterion.

    Examples
    --------
    >>> import haff
    >>> haff.dashpot_eps([0.0, 0.1, 0.5]).round(4)
    array([1.    , 0.7441, 0.2984])
    >>> haff.dashpot_eps([0.0, 0.1, 0.5], criterion="naive").round(4)
    array([1.    , 0.7292, 0.163 ])
    """
    return _each(damping_ratio, "damping_ratio",
                 lambda flat: _haff.dashpot_eps(flat, criterion))


def _check_digits(digits: object) -> None:
    if isinstance(digits, bool) or not isinstance(digits, (int, np.integer)):
        raise ConfigError(f"digits: {digits!r} is not an integer; allowed: 1 <= digits <= 60")


@overload
def coefficients(kind: str, order: int, digits: int = ...,
                 *, as_string: Literal[False] = ...) -> List[Decimal]: ...
@overload
def coefficients(kind: str, order: int, digits: int = ...,
                 *, as_string: Literal[True]) -> List[str]: ...
@overload
def coefficients(kind: str, order: int, digits: int, as_string: bool) -> List[Any]: ...
def coefficients(kind: str, order: int, digits: int = 20,
                 as_string: bool = False) -> Union[List[Decimal], List[str], List[Any]]:
    """The series coefficients of Schwager & Pöschel 2008, k = 0..order, to full precision.

    Computed exactly / in high precision by the computer algebra of ``haff-series``, as
    ``haff cor coefficients`` prints them.

    Parameters
    ----------
    kind : {"h", "c", "a", "b"}
        ``"h"``: eps = sum h_k v*^k (Table V / Eq. (36)); ``"c"``: the coefficients of the
        time of the collision; ``"a"``: tau_max = sum a_n A^n (Eq. (B3)); ``"b"``: x_max
        (Eq. (B5)).
    order : int
        The highest k, 0 <= order <= 100 (the work is bounded to about a minute).
    digits : int, default 20
        Significant digits, 1..60.
    as_string : bool, default False
        Decimal strings instead of :class:`decimal.Decimal`.

    Returns
    -------
    list of decimal.Decimal (or str)
        order + 1 coefficients; ``numpy.asarray(x, float)`` gives floats.

    Raises
    ------
    ConfigError
        An unknown `kind`, `order` or `digits` not an integer or out of range.

    Examples
    --------
    >>> import haff
    >>> haff.coefficients("h", 4, digits=10)
    [Decimal('1.000000000'), Decimal('0'), Decimal('-1.153448858'), Decimal('0'), Decimal('0.7982665609')]
    >>> haff.coefficients("h", 2, digits=6, as_string=True)
    ['1.00000', '0', '-1.15345']
    """
    _check_digits(digits)
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)):
        raise ConfigError(f"order: {order!r} is not an integer")
    values = _haff.coefficients_decimal(kind, int(order), int(digits))
    return values if as_string else [Decimal(x) for x in values]


@overload
def pade(m: int, n: int, digits: None = ...) -> Tuple[Floats, Floats]: ...
@overload
def pade(m: int, n: int, digits: int) -> Tuple[List[Decimal], List[Decimal]]: ...
def pade(m: int, n: int, digits: Optional[int] = None
         ) -> Union[Tuple[Floats, Floats], Tuple[List[Decimal], List[Decimal]]]:
    """The Padé approximant [m/n] of eps(v*) (Müller & Pöschel 2011, Eq. (20)).

    eps = (a_0 + a_1 v* + ... + a_m v*^m) / (1 + b_1 v* + ... + b_n v*^n), from the
    coefficients h_0..h_{m+n} that :func:`coefficients` computes; ``haff cor pade``.

    Parameters
    ----------
    m, n : int
        The degrees of the numerator and the denominator, 0..60.
    digits : int, optional
        Significant digits (1..60) of the coefficients as ``decimal.Decimal``; None:
        float64 arrays.

    Returns
    -------
    (a, b) : tuple of numpy.ndarray of float64, or of lists of decimal.Decimal
        The numerator's m + 1 and the denominator's n + 1 coefficients (b[0] = 1).

    Raises
    ------
    ConfigError
        Degrees out of range, or an approximant that does not exist (a singular linear
        system, e.g. [1/1]: h_1 = 0).

    Examples
    --------
    >>> import haff
    >>> a, b = haff.pade(2, 2, digits=8)
    >>> a
    [Decimal('1.0000000'), Decimal('0'), Decimal('-0.46137954')]
    >>> b
    [Decimal('1.0000000'), Decimal('0'), Decimal('0.69206931')]
    >>> a, b = haff.pade(3, 6)
    >>> a.shape, b.shape
    ((4,), (7,))
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
