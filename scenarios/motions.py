"""Prescribed time functions f(t) with their first and second derivatives, for drivers."""

from __future__ import annotations

import math
from dataclasses import dataclass

from scenarios.motion_laws import Polynomial, TabulatedLaw


@dataclass(frozen=True)
class ConstantSpeed:
    """f(t) = start + rate * t."""

    start: float
    rate: float

    def f(self, t: float) -> float:
        return self.start + self.rate * t

    def df(self, t: float) -> float:
        return self.rate

    def ddf(self, t: float) -> float:
        return 0.0


@dataclass(frozen=True)
class Harmonic:
    """f(t) = mean + amplitude * cos(omega * t + phase)."""

    mean: float
    amplitude: float
    omega: float
    phase: float = 0.0

    def f(self, t: float) -> float:
        return self.mean + self.amplitude * math.cos(self.omega * t + self.phase)

    def df(self, t: float) -> float:
        return -self.amplitude * self.omega * math.sin(self.omega * t + self.phase)

    def ddf(self, t: float) -> float:
        return -self.amplitude * self.omega**2 * math.cos(self.omega * t + self.phase)


@dataclass(frozen=True)
class Constant:
    """f(t) = value: a driver that holds a coordinate still."""

    value: float

    def f(self, t: float) -> float:
        return self.value

    def df(self, t: float) -> float:
        return 0.0

    def ddf(self, t: float) -> float:
        return 0.0


Motion = ConstantSpeed | Harmonic | Constant | Polynomial | TabulatedLaw
