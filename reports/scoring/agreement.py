"""Cross-engine agreement: how far the engines' default runs of one scenario lie from each other.

No truth enters here: for every pair of engines, the dimensionless difference of their default
trajectories at each level (reports.scoring.level_error's scales), over the bodies both carry. This
is the evidence where no closed form exists, and a second witness where one does. A level either
engine of a pair does not produce is NaN for that pair.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping

from reports.scoring.level_error import largest, level_series
from scenarios.scenario import LEVELS, Level
from scenarios.trajectory import Trajectory

Pair = tuple[str, str]


def pair_differences(
    runs: Mapping[str, Trajectory], length: float, rate: float
) -> dict[Pair, dict[Level, float]]:
    """{(engine a, engine b): {level: largest dimensionless difference}} for every unordered pair."""
    out: dict[Pair, dict[Level, float]] = {}
    for a, b in itertools.combinations(sorted(runs), 2):
        shared = tuple(body for body in runs[a].bodies if body in runs[b].bodies)
        first, second = runs[a].select(shared), runs[b].select(shared)
        same_grid = len(first.times) == len(second.times)
        out[(a, b)] = {
            level: largest(level_series(first, second, level, length, rate)) if same_grid else math.nan
            for level in LEVELS
        }
    return out


def widest(pairs: Mapping[Pair, Mapping[Level, float]], level: Level) -> tuple[Pair | None, float]:
    """The pair that differs most at `level` and by how much ((None, NaN) when no pair compares)."""
    found = [(pair, values[level]) for pair, values in pairs.items() if math.isfinite(values[level])]
    if not found:
        return None, math.nan
    return max(found, key=lambda item: item[1])
