"""haff.coefficients and haff.pade: equal to `haff cor coefficients | pade`."""

from decimal import Decimal

import numpy as np
import pytest

import haff
from conftest import column, read_csv


def test_coefficients_equal_the_command(cli):
    for kind, order in [("h", 8), ("a", 4), ("b", 3), ("c", 5)]:
        ours = haff.coefficients(kind, order, digits=30, as_string=True)
        theirs = column(cli("cor", "coefficients", "--kind", kind, "--order", str(order),
                            "--digits", "30"), "value", str)
        assert ours == theirs
    values = haff.coefficients("h", 4)
    assert all(isinstance(x, Decimal) for x in values) and len(values) == 5
    # eps(v*) = 1 + h_1 v* + ...: h_0 = 1 exactly.
    assert values[0] == 1
    floats = np.asarray(values, float)
    assert floats.dtype == np.float64
    # The series sums to the exact law at small v* (its error ~ h_5 v*^5).
    v = 0.05
    assert float(np.polyval(floats[::-1], v)) == pytest.approx(float(haff.eps(v, "exact")),
                                                               abs=1e-6)


def test_pade_equals_the_command(cli):
    header, rows = read_csv(cli("cor", "pade", "--m", "3", "--n", "6", "--digits", "40"))
    a = [float(r[1]) for r in rows if r[1]]
    b = [float(r[2]) for r in rows if r[2]]
    ours_a, ours_b = haff.pade(3, 6)
    np.testing.assert_array_equal(ours_a, a)
    np.testing.assert_array_equal(ours_b, b)
    assert ours_b[0] == 1.0
    # The approximant evaluated from these coefficients is the law `pade:3/6`.
    v = np.linspace(0, 3, 31)
    value = np.polyval(ours_a[::-1], v) / np.polyval(ours_b[::-1], v)
    np.testing.assert_allclose(value, haff.eps(v, "pade:3/6"), rtol=1e-14)
    exact_a, exact_b = haff.pade(1, 4, digits=25)
    assert all(isinstance(x, Decimal) for x in exact_a + exact_b)


@pytest.mark.parametrize(
    "call, key",
    [
        (lambda: haff.coefficients("z", 3), "kind"),
        (lambda: haff.coefficients("h", -1), "order"),
        (lambda: haff.coefficients("h", 101), "order"),
        (lambda: haff.coefficients("h", 3, digits=0), "digits"),
        (lambda: haff.coefficients("h", 3, digits=2.5), "digits"),
        (lambda: haff.pade(61, 1), "m"),
        (lambda: haff.pade(1, "2"), "n"),
        (lambda: haff.pade(60, 60), "m + n"),  # about 100 s: refused
    ],
)
def test_bad_arguments(call, key):
    with pytest.raises(haff.ConfigError) as error:
        call()
    assert str(error.value).startswith(key), str(error.value)
