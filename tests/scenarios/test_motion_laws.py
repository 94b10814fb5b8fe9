"""Every motion law's f' and f'' against central finite differences of f (and of f'), and the
tabulated law's defining properties: it passes through its points and honours its end conditions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from scenarios import Constant, ConstantSpeed, Harmonic, Polynomial, TabulatedLaw
from scenarios.motions import Motion

LAWS: dict[str, Motion] = {
    "constant": Constant(0.7),
    "constant_speed": ConstantSpeed(0.3, -2.5),
    "harmonic": Harmonic(0.1, 0.4, 3.0, 0.2),
    "constant_acceleration": Polynomial((0.5, -1.0, 2.0)),
    "quintic": Polynomial((0.1, 0.2, -0.3, 0.4, -0.5, 0.6)),
    "tabulated_clamped": TabulatedLaw(
        (0.0, 0.4, 0.9, 1.5, 2.0), (0.0, 0.3, 1.1, 0.8, 1.0), "clamped", (0.5, -0.2)
    ),
    "tabulated_periodic": TabulatedLaw((0.0, 0.5, 1.0, 1.5, 2.0), (0.0, 0.6, -0.2, 0.4, 0.0), "periodic"),
}
# Points away from the spline knots (where f''' jumps) and inside, before and after the tables.
TIMES = (-0.63, 0.17, 0.71, 1.23, 1.77, 2.31, 3.49)


@pytest.mark.parametrize("name", LAWS)
def test_derivatives_match_finite_differences(name: str) -> None:
    law, h = LAWS[name], 1e-5
    for t in TIMES:
        df = (law.f(t + h) - law.f(t - h)) / (2 * h)
        ddf = (law.df(t + h) - law.df(t - h)) / (2 * h)
        dd_from_f = (law.f(t + h) - 2 * law.f(t) + law.f(t - h)) / h**2
        assert law.df(t) == pytest.approx(df, rel=1e-9, abs=1e-8), t
        assert law.ddf(t) == pytest.approx(ddf, rel=1e-9, abs=1e-8), t
        assert law.ddf(t) == pytest.approx(dd_from_f, rel=1e-5, abs=1e-4), t


def test_polynomial_values() -> None:
    """Constant acceleration a from x0 at v0: x0 + v0 t + a t^2 / 2."""
    law = Polynomial((1.0, 2.0, 1.5))
    assert law.f(2.0) == 1.0 + 4.0 + 6.0
    assert law.df(2.0) == 2.0 + 6.0
    assert law.ddf(2.0) == 3.0
    assert Polynomial((4.0,)).df(1.0) == 0.0


def test_tabulated_law_interpolates_its_points() -> None:
    for name in ("tabulated_clamped", "tabulated_periodic"):
        law = LAWS[name]
        assert isinstance(law, TabulatedLaw)
        for t, v in zip(law.times, law.values, strict=True):
            assert law.f(t) == pytest.approx(v, abs=1e-14)


def test_clamped_law_has_its_end_slopes_and_continues_straight() -> None:
    law = TabulatedLaw((0.0, 1.0, 2.0, 3.0), (0.0, 1.0, 0.5, 2.0), "clamped", (0.25, -1.0))
    assert law.df(0.0) == pytest.approx(0.25, abs=1e-14)
    assert law.df(3.0) == pytest.approx(-1.0, abs=1e-14)
    assert law.f(5.0) == pytest.approx(2.0 - 2.0, abs=1e-14)
    assert law.f(-2.0) == pytest.approx(-0.5, abs=1e-14)
    assert (law.df(-2.0), law.ddf(-2.0), law.ddf(4.0)) == (0.25, 0.0, 0.0)


def test_periodic_law_repeats() -> None:
    law = LAWS["tabulated_periodic"]
    for t in (0.3, 1.1, 1.9):
        for shift in (-2.0, 2.0, 4.0):
            assert law.f(t + shift) == pytest.approx(law.f(t), abs=1e-13)
            assert law.ddf(t + shift) == pytest.approx(law.ddf(t), abs=1e-10)
    # continuous with continuous slope across the period's end
    assert law.df(2.0 - 1e-9) == pytest.approx(law.df(1e-9), abs=1e-6)


def test_a_tabulated_spline_through_a_smooth_law_converges_to_it() -> None:
    """A cubic spline interpolates with O(h^4) error: a finer table of sin t is far closer."""
    errors = []
    for knots in (9, 17, 33):
        times = tuple(float(t) for t in np.linspace(0.0, 2 * math.pi, knots))
        law = TabulatedLaw(times, tuple(math.sin(t) for t in times), "clamped", (1.0, 1.0))
        probe = np.linspace(0.0, 2 * math.pi, 997)
        errors.append(max(abs(law.f(float(t)) - math.sin(t)) for t in probe))
    assert errors[1] < errors[0] / 10 and errors[2] < errors[1] / 10


def test_a_periodic_table_starting_after_zero_repeats_from_its_own_start() -> None:
    """A table over [0.3, 2.3] (period 2): one period before or after a table time, the law is back at
    that time's value, and inside the table it passes through its points."""
    times = (0.3, 0.8, 1.3, 1.8, 2.3)
    law = TabulatedLaw(times, (0.0, 0.6, -0.2, 0.4, 0.0), "periodic")
    for t, value in zip(times[:-1], law.values, strict=False):
        for shift in (-4.0, -2.0, 0.0, 2.0):
            assert law.f(t + shift) == pytest.approx(value, abs=1e-13), (t, shift)


def test_a_clamped_table_is_its_spline_at_its_first_and_last_times() -> None:
    """Points of p(t) = 1 + t + t^2 - t^3 with p's slopes at the ends: the clamped cubic spline is p
    itself, so at the table's ends f'' is p'' (2 at t = 0, 2 - 6 t = -10 at t = 2), not the straight
    continuation's 0, which starts only beyond them."""
    times = (0.0, 0.5, 1.0, 1.5, 2.0)
    law = TabulatedLaw(times, tuple(1 + t + t * t - t**3 for t in times), "clamped", (1.0, 1.0 + 4.0 - 12.0))
    assert law.ddf(0.0) == pytest.approx(2.0, abs=1e-12)
    assert law.ddf(2.0) == pytest.approx(-10.0, abs=1e-12)
    assert law.f(1.25) == pytest.approx(1 + 1.25 + 1.25**2 - 1.25**3, abs=1e-12)
