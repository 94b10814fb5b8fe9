"""Measured errors held two-sided: a value more than FACTOR away from the one measured when the
table was written, either way, fails, so that a change in an engine, an adapter or the truth shows
whether it made things worse or better. A value at round-off is held from above only (its size
is the rounding's, not a property of the method)."""

from __future__ import annotations

from collections.abc import Sequence

FACTOR = 3.0
ROUND_OFF = 1e-12


def held(
    found: Sequence[float],
    measured: Sequence[float],
    names: Sequence[str] = ("position", "velocity", "acceleration"),
    factor: float = FACTOR,
    round_off: float = ROUND_OFF,
) -> None:
    """Assert each found value within `factor` of its measured value (a measured value at or below
    `round_off`: below ten times it), naming the level, the value and the measurement on failure."""
    for name, value, expected in zip(names, found, measured, strict=True):
        if expected <= round_off:
            assert value < 10 * round_off, f"{name}: {value:.2e} is not round-off (< {10 * round_off:g})"
        else:
            low, high = expected / factor, expected * factor
            assert low < value < high, f"{name}: {value:.2e} outside measured {expected:.1e} x/÷ {factor:g}"
