"""Motion laws beyond the constant ones: a polynomial in t and a smooth tabulated law.

Like the laws in `scenarios.motions`, each gives f(t), f'(t) and f''(t) exactly (the tabulated law
is exact for its own spline), so that a driver's velocity and acceleration right-hand sides are not
approximations.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Literal

if TYPE_CHECKING:  # scipy.interpolate is imported by the first tabulated law's spline only
    from scipy.interpolate import CubicSpline

Ends = Literal["periodic", "clamped"]


@dataclass(frozen=True)
class Polynomial:
    """f(t) = c0 + c1 t + c2 t^2 + ...: constant acceleration is three coefficients."""

    coefficients: tuple[float, ...]

    def _horner(self, coefficients: tuple[float, ...], t: float) -> float:
        value = 0.0
        for c in reversed(coefficients):
            value = value * t + c
        return value

    def f(self, t: float) -> float:
        return self._horner(self.coefficients, t)

    def df(self, t: float) -> float:
        return self._horner(tuple(k * c for k, c in enumerate(self.coefficients))[1:], t)

    def ddf(self, t: float) -> float:
        return self._horner(tuple(k * (k - 1) * c for k, c in enumerate(self.coefficients))[2:], t)


@dataclass(frozen=True)
class TabulatedLaw:
    """A cubic spline through (times, values), twice continuously differentiable.

    `ends = "periodic"`: the values repeat with period times[-1] - times[0] (the first and last
    values must be equal), for a cyclic motion. `ends = "clamped"`: the spline has the first
    derivatives `slopes` at its two ends, and outside the table it continues as a straight line
    with the end value and slope (so a clamped law with zero slopes holds still before and after).
    """

    times: tuple[float, ...]
    values: tuple[float, ...]
    ends: Ends = "clamped"
    slopes: tuple[float, float] = (0.0, 0.0)

    @cached_property
    def spline(self) -> CubicSpline:
        """The scipy spline through the table with the chosen end conditions."""
        from scipy.interpolate import CubicSpline

        if self.ends == "periodic":
            return CubicSpline(self.times, self.values, bc_type="periodic")
        return CubicSpline(self.times, self.values, bc_type=((1, self.slopes[0]), (1, self.slopes[1])))

    def _evaluate(self, t: float, order: int) -> float:
        start, end = self.times[0], self.times[-1]
        if self.ends == "periodic":
            return float(self.spline(start + (t - start) % (end - start), order))
        if start <= t <= end:
            return float(self.spline(t, order))
        edge, slope, value = (start, self.slopes[0], self.values[0])
        if t > end:
            edge, slope, value = (end, self.slopes[1], self.values[-1])
        return (value + slope * (t - edge), slope, 0.0)[order]

    def f(self, t: float) -> float:
        return self._evaluate(t, 0)

    def df(self, t: float) -> float:
        return self._evaluate(t, 1)

    def ddf(self, t: float) -> float:
        return self._evaluate(t, 2)
