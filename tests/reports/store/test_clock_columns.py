"""The run-time columns say their clock (issue #40): run_time is declared as process CPU time
counting every thread, with the wall clock's figure declared beside it, and a report states the
clock it shows, a store from before CPU time as wall."""

from __future__ import annotations

import math

import pandas as pd

from reports.render.clock import CPU, MIXED, OLD_WALL, clock_label
from reports.render.engine_reach import markdown_lines
from reports.store.columns import COLUMNS, DECLARED, WALL_COLUMNS

MEANING = {column.name: column.meaning for column in DECLARED}


def test_run_time_is_declared_as_process_cpu_time_counting_every_thread() -> None:
    meaning = MEANING["run_time"]
    assert "CPU" in meaning and "process_time" in meaning and "every thread" in meaning
    assert "run_time_wall" in meaning


def test_every_cpu_column_has_its_wall_column_declared_once() -> None:
    for name in ("build_time", "run_time", "warmup_time", "repeats_time"):
        assert "CPU" in MEANING[name]
        assert COLUMNS.count(f"{name}_wall") == 1
    assert {c.name for c in WALL_COLUMNS} <= set(COLUMNS)
    assert "wall" in MEANING["run_time_wall"] and "perf_counter" in MEANING["run_time_wall"]


def _rows(wall: list[float]) -> pd.DataFrame:
    return pd.DataFrame(
        {
            "engine": ["e"] * len(wall),
            "scenario": [f"s{k}" for k in range(len(wall))],
            "status": ["ok"] * len(wall),
            "run_time": [0.01] * len(wall),
            "build_time": [0.001] * len(wall),
            "run_time_wall": wall,
            "error_position": [1e-9] * len(wall),
            "error_velocity": [1e-9] * len(wall),
            "error_acceleration": [1e-9] * len(wall),
            "is_default": [True] * len(wall),
        }
    )


def test_a_report_names_the_clock_it_shows() -> None:
    assert clock_label(_rows([0.02, 0.03])) == CPU
    assert clock_label(_rows([math.nan, math.nan])) == OLD_WALL  # a store from before CPU time
    assert clock_label(_rows([0.02, math.nan])) == MIXED  # a resume that kept old rows
    old = _rows([math.nan]).drop(columns=["run_time_wall"])
    assert clock_label(old) == OLD_WALL == "wall (recorded before CPU time)"


def test_the_engine_reach_table_states_its_clock() -> None:
    assert "(CPU)" in "\n".join(markdown_lines(_rows([0.02]), str))
    assert f"({OLD_WALL})" in "\n".join(markdown_lines(_rows([math.nan]), str))
