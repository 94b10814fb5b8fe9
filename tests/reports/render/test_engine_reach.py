"""What each engine gives and reaches, from a hand-made results table whose answers are known."""

from __future__ import annotations

import math

import pandas as pd

from reports.render.engine_reach import reach, sentences

NAN = math.nan


def row(
    engine: str,
    scenario: str,
    errors: tuple[float, float, float],
    time: float,
    default: bool = False,
    status: str = "ok",
    untuned: bool = False,
) -> dict[str, object]:
    p, v, a = errors
    return {
        "engine": engine,
        "scenario": scenario,
        "status": status,
        "is_default": default,
        "is_untuned": untuned,
        "run_time": time,
        "error_position": p,
        "error_velocity": v,
        "error_acceleration": a,
    }


ROWS = [
    # engine A: default 1e-4 on s1; a finer setting meets 1e-6 at 2 ms, a finer one at 5 ms
    row("A", "s1", (1e-5, 1e-4, 1e-3), 0.001, default=True),
    row("A", "s1", (1e-8, 1e-7, 1e-7), 0.005),
    row("A", "s1", (1e-7, 1e-7, 9e-7), 0.002),
    # on s2 it never meets 1e-6 (acceleration 2e-6 at best); a failed row does not count
    row("A", "s2", (1e-9, 1e-9, 2e-6), 0.010, default=True),
    row("A", "s2", (0.0, 0.0, 0.0), 0.0, status="failed"),
    # its own defaults, untuned: worse than the rule's default on s1
    row("A", "s1", (1e-3, 1e-2, 1e-1), 0.0005, untuned=True),
    # engine B gives no accelerations: the levels it produces decide
    row("B", "s1", (1e-7, 1e-7, NAN), 0.004, default=True),
    row("B", "s2", (1e-3, 1e-2, NAN), 0.001, default=True),
]


def test_reach_reads_the_front_by_hand() -> None:
    table = reach(pd.DataFrame(ROWS)).set_index("engine")
    a, b = table.loc["A"], table.loc["B"]
    assert (a["default_error_position"], a["default_error_velocity"], a["default_error_acceleration"]) == (
        1e-5,
        1e-4,
        1e-3,
    )
    assert a["best_worst"] == 2e-6  # s1's best is 1e-7, s2's 2e-6: the worst scenario's best
    assert (a["reached"], a["scenarios"], a["median_cost"]) == (1, 2, 0.002)
    assert (a["untuned_error_position"], a["untuned_error_velocity"], a["untuned_error_acceleration"]) == (
        1e-3,
        1e-2,
        1e-1,
    )
    # the best settings: s1's at 5 ms (worst 1e-7), s2's default at 10 ms (worst 2e-6)
    assert a["best_cost"] == 0.0075
    assert math.isnan(b["untuned_error_position"])
    assert math.isnan(b["default_error_acceleration"]) and b["best_worst"] == 1e-2
    assert (b["reached"], b["median_cost"]) == (1, 0.004)


def test_the_sentences_say_not_reached() -> None:
    rows = [row("C", "s1", (1e-3, 1e-3, 1e-3), 0.001, default=True)]
    ((engine, untuned, default, best, cost),) = sentences(reach(pd.DataFrame(rows)))
    assert engine == "C" and default == "1.0e-03 / 1.0e-03 / 1.0e-03" and untuned == "none declared"
    assert best.startswith("1.0e-03") and cost == "not reached on any of 1 scenarios"


def test_a_store_from_before_the_untuned_column_has_no_untuned_point() -> None:
    rows = [{k: v for k, v in r.items() if k != "is_untuned"} for r in ROWS]
    table = reach(pd.DataFrame(rows)).set_index("engine")
    assert math.isnan(table.loc["A", "untuned_error_position"])
    assert table.loc["A", "best_worst"] == 2e-6
