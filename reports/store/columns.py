"""The result table's columns, declared once: name, the value a row holds before a run fills it, and
what the column means. The store orders its table by them and the row builder starts from them."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from reports.scoring import (
    CLOSED_FORM,
    DRIFT_DEFINITION,
    FORCE_DEFINITION,
    LEVEL_COLUMNS,
    METRIC_COLUMNS,
    SCALE_DEFINITION,
    STARTUP_DEFINITION,
)

__all__ = [
    "CLOSED_FORM",
    "COLUMNS",
    "DECLARED",
    "DRIFT_DEFINITION",
    "DRIFT_SERIES",
    "ERROR_SERIES",
    "FORCE_DEFINITION",
    "LEVEL_COLUMNS",
    "LOST",
    "NOT_RECORDED",
    "NOT_RUN",
    "RECORDED_COLUMNS",
    "SCALE_DEFINITION",
    "STARTUP_DEFINITION",
    "WALL_COLUMNS",
    "Column",
    "empty_row",
]
"""The definitions of what the measured columns mean are declared beside the measures (and
re-exported here, so that a report needs this module alone)."""

NOT_RUN = "-"
"""The setting label of a row that stands for an engine that never ran on the scenario."""


@dataclass(frozen=True)
class Column:
    name: str
    empty: Any
    meaning: str


DRIFT_SERIES = {"energy drift": "drift.energy", "constraint residual": "drift.residual"}
"""Extras stored with a dynamic scenario's default runs (reports.dynamics.recording): the energy
drift and the scaled constraint residual at each time, by what the report calls them."""
ERROR_SERIES = {level: f"error.{level}" for level in LEVEL_COLUMNS}
"""Extras stored with each default run (reports.run.recording): its dimensionless error against
the truth at every grid time, per level."""
LOST = 0.1
"""A verdict says `drifted` where the run is farther than this from the truth and from every closure
(lengths in characteristic lengths, angles in radians; reports.stress.branch_check)."""
NOT_RECORDED = "not recorded"
"""What a report shows for a column its store does not hold (written before the column existed)."""


@dataclass(frozen=True)
class Judgement:
    """One row's verdict, with when it happened, its error and the run's worst residual: what
    reports.stress.stability_map decides and stores in the verdict columns below, and what the
    report reads back from them (reports.render.stored_verdicts)."""

    scenario: str
    engine: str
    setting: str
    is_default: bool
    verdict: str
    time: float
    error: float
    residual: float
    detail: str


RECORDED_COLUMNS: tuple[Column, ...] = (
    Column(
        "verdict",
        "",
        "what became of the run, decided when the run was made: the stability verdict of a stress "
        "case's row or a swept point's default (reports.stress.stability_map, with its branch check), "
        "of a dynamics map cell (reports.dynamics.stability); '' where none is made or not recorded",
    ),
    Column("verdict_time", math.nan, "when the verdict's event happened (a failure, leaving the branch), s"),
    Column("verdict_error", math.nan, "the largest headline error where the truth exists, as judged"),
    Column("verdict_detail", "", "how the verdict was reached (the closure found, a false alarm, ...)"),
    Column("case_rank", -1, "stress suite: the case's place in reports.stress.cases; -1 off a case"),
    Column("case_probes", "", "stress suite: what the case probes"),
    Column(
        "case_singular_time", math.nan, "stress suite: closed-form time of the first singular configuration"
    ),
    Column("case_nominal", "", "stress suite: the nominal scenario the case is a similarity of"),
    *(
        Column(
            f"{quantity}_{turn}_rev",
            math.nan,
            f"long-horizon case: largest {what} over the {turn} revolution",
        )
        for quantity, what in (("error", "headline error"), ("residual", "constraint residual"))
        for turn in ("first", "last")
    ),
    Column(
        "angle_error_end", math.nan, "long-horizon case: the largest body angle error at the last time, rad"
    ),
    Column("map_stiffness", math.nan, "dynamics map cell: the spring stiffness, N/m"),
    Column("map_dt", math.nan, "dynamics map cell: the output step, s"),
    Column(
        "is_untuned",
        False,
        "the engine's own defaults as a new user's model gets them, at the rule's step "
        "(Adapter.untuned_setting): the report's untuned point",
    ),
    Column("scenario_rank", -1, "the scenario's place in the catalogue (the report's order); -1 not listed"),
    Column(
        "engine_rank", -1, "the engine's place in the engine registry (the report's order); -1 not listed"
    ),
    Column(
        "agreement",
        "",
        "the scenario's engines' default runs: the widest difference per level and its pair, as JSON "
        "(run.recording); '' with fewer than two runs",
    ),
)
"""Columns a report shows as stored, decided when the run was made (appended: older stores lack them)."""


WALL_COLUMNS: tuple[Column, ...] = (
    Column(
        "run_time_wall",
        math.nan,
        "wall-clock seconds to simulate, minimum of the same repeats as run_time (time.perf_counter): "
        "what the run took on the machine as loaded then; NaN in stores recorded before CPU time, "
        "whose run_time is this wall time",
    ),
    Column("build_time_wall", math.nan, "build_time on the wall clock"),
    Column("warmup_time_wall", math.nan, "warmup_time on the wall clock"),
    Column("repeats_time_wall", math.nan, "repeats_time on the wall clock (a timeout's: the limit it hit)"),
)
"""The wall clock beside the CPU-time columns (appended: older stores lack them, and their run_time is
wall time; reports.render.report_data.clock_label says which a report shows)."""


DECLARED: tuple[Column, ...] = (
    Column("scenario", "", "scenario name, family/variant"),
    Column("family", "", "mechanism family"),
    Column("variant", "", "variant of the family"),
    Column("sweep", "", "a swept point's parameter values as JSON (run.sweep); '' off a sweep"),
    Column(
        "scenario_digest",
        "",
        "the mechanism measured: digest of its canonical file (store.scenario_identity)",
    ),
    Column("engine", "", "engine name"),
    Column("engine_version", "", "installed engine version"),
    Column("mode", "", "engine mode (integrator, solver)"),
    Column(
        "measures", "", "what the mode measures: the engine's own solver or an adapter loop, derived levels"
    ),
    Column("setting", NOT_RUN, "setting label: mode and options"),
    Column("options", "{}", "setting options as JSON"),
    Column("is_default", False, "the engine's default setting for the scenario"),
    Column("status", "failed", "ok, failed, diverged, singular, timeout or unsupported"),
    Column("message", "", "why the run is not ok"),
    Column("failure_time", math.nan, "simulated time of the failure"),
    Column("warnings", "", "engine and Python warnings"),
    Column("levels", "", "levels compared"),
    Column("error", math.nan, "headline error (metrics.HEADLINE_DEFINITION), = error_position"),
    Column("truth", "", "which truth the row was measured against (scoring.truth)"),
    *(
        Column(name, math.nan, f"dimensionless {level} error, NaN where not produced (scoring.level_error)")
        for level, name in LEVEL_COLUMNS.items()
    ),
    *(Column(name, math.nan, "error statistic: level_quantity_statistic") for name in METRIC_COLUMNS),
    Column(
        "startup_excess",
        math.nan,
        "start-up transient: the first half's largest error over the second half's, at the level where "
        "it is largest (scoring.startup)",
    ),
    Column(
        "startup_time",
        math.nan,
        "start-up transient: how long after the start the error settles, s (scoring.startup)",
    ),
    Column("constraint_residual", math.nan, "largest scaled constraint residual"),
    Column(
        "constraint_residual_final", math.nan, "scaled constraint residual at the last grid time (its drift)"
    ),
    Column("energy_drift", math.nan, "dynamic runs: scaled energy drift (scoring.energy_drift)"),
    Column(
        "energy_change",
        math.nan,
        "the run's own energy balance: the change of T + V less the work of its loads and drivers "
        "(scoring.work), over its energy scale, no truth used; NaN where a driven run reports no "
        "driving force",
    ),
    Column(
        "step_halving",
        math.nan,
        "a run with no truth: the largest position difference from the same setting at half its step "
        "dt (scoring.self_check), characteristic lengths and radians; NaN where not made",
    ),
    Column(
        "self_check", "", "'' or what drifted by the run's own figures, no truth used (scoring.self_check)"
    ),
    Column(
        "benchmark_error",
        math.nan,
        "scenarios of a published benchmark: its own error figure (IFToMM A02: B0's position and "
        "velocity, m and m/s, against the one-degree-of-freedom solution), NaN elsewhere",
    ),
    Column("benchmark_limit", math.nan, "the benchmark's high-precision limit on benchmark_error"),
    Column(
        "invariant_error",
        math.nan,
        "published benchmarks: the largest departure from the motion's invariant (A02: a rocker's "
        "angle to the crank, rad)",
    ),
    Column(
        "error_force",
        math.nan,
        "runs reporting forces: the larger of driver_force_error and reaction_error (scoring.forces)",
    ),
    Column(
        "force_truth",
        "",
        "which force truth the row's forces were measured against (scoring.forces.FORCE_TRUTHS); '' "
        "where none was",
    ),
    Column(
        "driver_force_error",
        math.nan,
        "runs reporting driver forces: error against the force truth (scoring.forces)",
    ),
    Column(
        "reaction_error",
        math.nan,
        "runs reporting joint reactions: error against the force truth (scoring.forces)",
    ),
    Column(
        "build_time",
        math.nan,
        "CPU seconds to build the engine's model (a failed build: up to its failure); wall: build_time_wall",
    ),
    Column(
        "run_time",
        math.nan,
        "CPU seconds to simulate, minimum of repeats after a warm-up: the process CPU time of the run's "
        "worker (time.process_time), the same clock for every engine, counting every thread the "
        "process runs (an engine's own threads included; BLAS held to one thread per worker); "
        "wall clock: run_time_wall",
    ),
    Column("steps", 0, "engine steps taken"),
    Column("repeats", 0, "timed repeats"),
    Column(
        "warmup",
        0,
        "untimed warm-up runs before the timed ones, each over the grid's first interval (its first two "
        "times: every first call paid, not the horizon)",
    ),
    Column(
        "warmup_time",
        math.nan,
        "CPU seconds spent in the untimed warm-up runs, summed (0 without one); a run that failed in its "
        "engine records what it spent up to the failure; NaN where not recorded (a timeout, a "
        "crash, a run not made)",
    ),
    Column(
        "repeats_time",
        math.nan,
        "CPU seconds spent in the timed repeats, summed (run_time is their minimum): with build_time and "
        "warmup_time, the work the run's timing did, a failed run's up to its failure, a timeout's the "
        "limit it hit (a wall-clock limit: at most that much CPU); NaN where not recorded (a crash, a "
        "run not made)",
    ),
    Column("grid_points", 0, "time points compared"),
    Column("t_end", math.nan, "end of the time grid, s"),
    Column("characteristic_length", math.nan, "the scenario's length scale, m"),
    Column("characteristic_rate", math.nan, "the scenario's rate scale |omega|, rad/s (scoring.level_error)"),
    Column("host", "", "machine the run was made on (timings compare only within one host)"),
    Column("workers", 0, "runs made at the same time as this one: 1 serial, N on N Dask workers"),
    Column("recorded_at", "", "when the row was made (UTC)"),
    Column("revision", "", "git revision the row was made under (run.resume)"),
    Column("stale", False, "kept by a resume under another revision or engine version (--keep-stale)"),
    *RECORDED_COLUMNS,
    *WALL_COLUMNS,
)
COLUMNS: tuple[str, ...] = tuple(c.name for c in DECLARED)


def empty_row() -> dict[str, Any]:
    """A row with every declared column at its empty value."""
    return {c.name: c.empty for c in DECLARED}
