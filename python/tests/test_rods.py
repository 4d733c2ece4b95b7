"""haff.rods: equal to `haff rods deterministic | collide`."""

import numpy as np
import pytest

import haff
from conftest import column


def test_deterministic_equals_the_command(cli):
    out = cli("rods", "deterministic", "--gamma", "0.6173,0.5", "--kappa", "100,1000")
    gammas, kappas = column(out, "gamma"), column(out, "kappa")
    eps = haff.rods.deterministic(gammas, kappas)
    np.testing.assert_array_equal(eps, column(out, "eps"))
    np.testing.assert_array_equal(haff.rods.closed_form(gammas, kappas), column(out, "closed_form"))
    np.testing.assert_array_equal(haff.rods.closed_form(gammas, kappas, general=True),
                                  column(out, "closed_form_general"))
    assert isinstance(haff.rods.deterministic(0.6173, 100.0), float)
    # The closed form is asymptotic in kappa: at kappa = 1000 it is within ~1/kappa.
    assert haff.rods.deterministic(0.5, 1000.0) == pytest.approx(
        haff.rods.closed_form(0.5, 1000.0), abs=2e-3)
    assert np.isnan(haff.rods.closed_form(1.0, 100.0))


def test_collide_equals_the_command(cli):
    out = cli("rods", "collide", "--gamma", "0.6173", "--kappa", "100", "--bath-ratio", "10",
              "--realizations", "200", "--seed", "4")
    eps = haff.rods.collide(0.6173, 100.0, bath_ratio=10.0, realizations=200, seed=4)
    assert eps.shape == (200,) and eps.dtype == np.float64
    np.testing.assert_array_equal(eps, column(out, "eps"))
    cold = haff.rods.collide(0.6173, 100.0, realizations=16)
    # A cold bath is the deterministic limit: every realization alike.
    np.testing.assert_allclose(cold, haff.rods.deterministic(0.6173, 100.0), rtol=1e-3)


@pytest.mark.parametrize(
    "call, key",
    [
        (lambda: haff.rods.deterministic(0.0, 100.0), "gamma"),
        (lambda: haff.rods.deterministic(0.5, 1e6), "kappa"),
        (lambda: haff.rods.deterministic(0.5, 100.0, step=1.5), "step"),
        (lambda: haff.rods.deterministic(1e-3, 1e5), "gamma"),  # about 10 hours of work
        (lambda: haff.rods.collide(0.5, 100.0, bath_ratio=-1.0), "bath_ratio"),
        (lambda: haff.rods.collide(0.5, 100.0, realizations=0), "realizations"),
        (lambda: haff.rods.collide(0.5, 100.0, seed=-1), "seed"),
    ],
)
def test_bad_arguments(call, key):
    with pytest.raises(haff.ConfigError) as error:
        call()
    assert str(error.value).startswith(key), str(error.value)
