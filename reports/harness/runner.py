"""The runner: scenario x engine x setting, each run isolated, every outcome stored as a row.

For each scenario the truth (reports.harness.truth: the closed form where there is one, else the
native solver refined; or the suite's own hook) is computed once on the scenario's grid, in
this process (with a time limit), so that the solver's JIT-compiled kernels are compiled once and
inherited by the forked runs;
each engine run (build timed apart, simulation timed as the minimum of repeats after a warm-up, by
the adapter's base class) happens in a forked child with a time limit, and its errors against the
truth are computed there too. A crash, a hang or a divergence costs that row only. Rows already
stored are skipped unless `rerun`; the store is saved after each scenario-engine group.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import tqdm

import adapters
from adapters.base import Adapter, RunResult, Setting
from reports.harness import provenance
from reports.harness.columns import NOT_RUN
from reports.harness.energy_drift import energy_drift
from reports.harness.isolation import run_here, run_isolated
from reports.harness.level_error import SCALE_DEFINITION, level_errors
from reports.harness.metrics import (
    HEADLINE_DEFINITION,
    Residual,
    compared_levels,
    error_metrics,
    residual_metrics,
)
from reports.harness.results_store import ResultsStore
from reports.harness.resume import STALE, ResumeLog, ResumePolicy, rerun_reason, staleness
from reports.harness.rows import failure_row, result_row
from reports.harness.truth import NamedTruth, independent_truth, named
from scenarios import Scenario, ScenarioError
from scenarios import load as build_scenario
from scenarios.trajectory import Trajectory

TRUTH_TOLERANCE = 1e-12
LONG_RUN = 0.25  # seconds: a simulation this long is timed once after the warm-up
Truth = Callable[[Scenario, np.ndarray], Trajectory | NamedTruth]
"""A truth hook: the truth of a scenario on a grid; a bare trajectory is named HOOK_TRUTH."""
HOOK_TRUTH = f"native, tolerance {TRUTH_TOLERANCE:g}"
Loader = Callable[[str], Adapter]
SettingsHook = Callable[[Scenario, Adapter], list[Setting] | None]
"""A suite's own settings for a scenario and engine (the first is the default), or None: the engine's."""


@dataclass(frozen=True)
class RunOptions:
    """How each engine run is made: `sweep` False runs only each engine's default setting."""

    sweep: bool = True
    repeats: int = 3
    warmup: int = 1
    timeout: float = 60.0
    rerun: bool = False
    keep_failures: bool = False  # keep stored failed/timeout rows instead of retrying them
    keep_stale: bool = False  # keep rows of another revision or engine version, marked stale
    truth_timeout: float = 600.0  # our own solver; its first call may compile its kernels


@dataclass
class Group:
    """The planned runs of one engine on one scenario, or the row that says why there are none."""

    scenario: Scenario
    engine: str
    adapter: Adapter | None
    version: str
    jobs: list[tuple[Setting, bool]] = field(default_factory=list)
    reason_row: dict[str, Any] | None = None


def reference_residual() -> Residual | None:
    """The lead's `reference_solver.constraint_residual`, when it exists."""
    import reference_solver

    return getattr(reference_solver, "constraint_residual", None)


class Runner:
    """Runs scenarios on engines into a ResultsStore."""

    def __init__(
        self,
        store: ResultsStore,
        engines: Sequence[str],
        options: RunOptions,
        loader: Loader = adapters.load,
        truth: Truth | None = None,  # None: independent_truth (closed form, else refined native)
        residual: Residual | None = None,  # None: reference_solver.constraint_residual
        progress: bool = True,
        suite: str = "",
        settings: SettingsHook | None = None,
    ) -> None:
        self.store, self.engines, self.options = store, list(engines), options
        self.truth, self.progress, self.suite = truth or independent_truth, progress, suite
        self.settings = settings
        self.residual = residual if residual is not None else reference_residual()
        self.adapters: dict[str, Adapter | str] = {}
        self.revision = provenance.git_revision()
        self.policy = ResumePolicy(options.rerun, options.keep_failures, options.keep_stale)
        self.resume_log = ResumeLog()
        for name in self.engines:
            try:
                self.adapters[name] = loader(name)
            except Exception as error:  # not installed, or its module is broken
                self.adapters[name] = f"engine unavailable: {type(error).__name__}: {error}"

    def run(self, scenario_names: Sequence[str]) -> None:
        """Plan every group, then run what is not stored yet, saving after each group."""
        groups = [g for name in scenario_names for g in self._plan(name)]
        kept = {id(g) for g in groups if g.adapter is None and self._stored_results(g)}
        pending = {id(g): [j for j in g.jobs if not self._stored(g, j[0])] for g in groups}
        for line in self.resume_log.lines():
            print(f"mbxval: {line}", file=sys.stderr)
        truths_needed = {g.scenario.name for g in groups if pending[id(g)]}
        total = sum(len(p) for p in pending.values()) + len(truths_needed)
        tqdm.tqdm.monitor_interval = 0  # no monitor thread: the runs are forked
        truths: dict[str, NamedTruth | str] = {}
        # In a log rather than a terminal (a CI job), a line every 10 s instead of one per update.
        interval = 0.1 if sys.stderr.isatty() else 10.0
        with tqdm.tqdm(
            total=total, file=sys.stderr, disable=not self.progress, unit="run", mininterval=interval
        ) as bar:
            try:
                for group in groups:
                    name = group.scenario.name
                    if id(group) in kept:
                        continue  # unavailable now: its stored rows stay as they are
                    self._reconcile(group)
                    if group.reason_row is not None:
                        self._add(group.reason_row)
                        continue
                    if pending[id(group)] and name not in truths:
                        bar.set_description(f"{name} truth", refresh=False)
                        truths[name] = self._solve_truth(group.scenario)
                        bar.update()
                    self._run_group(group, pending[id(group)], truths.get(name, ""), bar)
                    self._save()
            finally:
                self._save()

    # --- planning ---------------------------------------------------------------------------
    def _plan(self, name: str) -> list[Group]:
        try:
            scenario = build_scenario(name)
        except ScenarioError as error:
            raise ScenarioError(f"suite scenario {name} cannot be built: {error}") from error
        return [self._plan_engine(scenario, engine) for engine in self.engines]

    def _plan_engine(self, scenario: Scenario, engine: str) -> Group:
        adapter = self.adapters[engine]
        if isinstance(adapter, str):
            row = failure_row(scenario, engine, "unavailable", None, True, "failed", adapter)
            return Group(scenario, engine, None, "unavailable", reason_row=row)
        version = adapter._safe_version()
        group = Group(scenario, engine, adapter, version)
        try:
            reason = adapter.supports(scenario)
            if reason is not None:
                group.reason_row = failure_row(scenario, engine, version, None, True, "unsupported", reason)
                return group
            default = adapter.default_setting(scenario)
            settings = adapter.sweep(scenario) if self.options.sweep else []
            chosen = self.settings(scenario, adapter) if self.settings else None
            if chosen:
                default, settings = chosen[0], chosen
        except Exception as error:  # a broken adapter costs its own rows only
            message = f"cannot plan the runs: {type(error).__name__}: {error}"
            group.reason_row = failure_row(scenario, engine, version, None, True, "failed", message)
            return group
        group.jobs = [(s, s == default) for s in dict.fromkeys([*settings, default])]
        return group

    def _stored(self, group: Group, setting: Setting) -> bool:
        """Whether the stored row of this run is kept (see reports.harness.resume)."""
        key = (group.scenario.name, group.engine, setting.label)
        row = self.store.rows.get(key)
        if row is None:
            return False
        reason = rerun_reason(row, self.revision, group.version, key in self.store.trajectories, self.policy)
        log = self.resume_log
        if reason is not None:
            log.reasons[reason] += 1
        stale = staleness(row, self.revision, group.version)
        if stale and reason in (STALE, None):
            log.stale_from[stale] += 1
        if reason is None and stale:
            log.kept_stale += 1
            row["stale"] = True
        return reason is None

    def _stored_results(self, group: Group) -> bool:
        """Whether the store has rows of an engine that cannot be loaded now (counted in the log)."""
        pair = (group.scenario.name, group.engine)
        count = sum(1 for k in self.store.rows if k[:2] == pair and k[2] != NOT_RUN)
        if count:
            log = self.resume_log.kept_unavailable
            log[group.engine] = log.get(group.engine, 0) + count
        return count > 0

    def _reconcile(self, group: Group) -> None:
        """Make the stored rows of this scenario-engine pair agree with the plan: a pair that no
        longer runs keeps only its reason row; one that runs loses its old reason row; stored
        settings outside the plan (another suite's sweep) stay, but are no longer the default."""
        planned = {s.label for s, _ in group.jobs}
        for key in [k for k in self.store.rows if k[:2] == (group.scenario.name, group.engine)]:
            if (group.reason_row is None) == (key[2] == NOT_RUN):
                del self.store.rows[key]
                self.store.trajectories.pop(key, None)
            elif group.reason_row is None and key[2] not in planned:
                self.store.rows[key]["is_default"] = False
                self.store.trajectories.pop(key, None)

    # --- running ----------------------------------------------------------------------------
    def _solve_truth(self, scenario: Scenario) -> NamedTruth | str:
        times = np.asarray(scenario.times())
        outcome = run_here(lambda: self.truth(scenario, times), self.options.truth_timeout)
        if outcome.kind != "ok" or outcome.value is None:
            return f"no reference truth ({outcome.kind}: {outcome.message})"
        found = named(outcome.value, HOOK_TRUTH)
        self.store.put_truth(scenario.name, found.name, found.trajectory.select(scenario.output_bodies))
        return found

    def _run_group(
        self, group: Group, jobs: list[tuple[Setting, bool]], truth: NamedTruth | str, bar: tqdm.tqdm
    ) -> None:
        timed_out: set[str] = set()
        for setting, is_default in jobs:
            bar.set_description(f"{group.scenario.name} {group.engine} {setting.label}", refresh=False)
            if setting.mode in timed_out:
                message = "not run: a cheaper setting of this mode hit the time limit"
                self._fail(group, setting, is_default, "timeout", message)
            else:
                self._run_one(group, setting, is_default, truth, timed_out)
            bar.update()

    def _run_one(
        self, group: Group, setting: Setting, is_default: bool, truth: NamedTruth | str, timed_out: set[str]
    ) -> None:
        scenario, adapter, opts = group.scenario, group.adapter, self.options
        assert adapter is not None
        times = np.asarray(scenario.times())
        residual = self.residual

        def execute() -> tuple[RunResult, int, dict[str, float], tuple[str, ...], str]:
            result, repeats = timed_run(adapter, scenario, setting, times, opts)
            against = truth.trajectory if isinstance(truth, NamedTruth) else truth
            return (result, repeats, *compare(scenario, result, against, residual))

        outcome = run_isolated(execute, opts.timeout)
        if outcome.kind == "timeout":
            timed_out.add(setting.mode)
            self._fail(group, setting, is_default, "timeout", outcome.message)
        elif outcome.kind != "ok" or outcome.value is None:
            self._fail(group, setting, is_default, "failed", outcome.message)
        else:
            result, repeats, metrics, levels, note = outcome.value
            row = result_row(scenario, result, is_default, repeats, opts.warmup, metrics, levels, note)
            row["engine"] = group.engine  # the name it was asked by, whatever the adapter calls itself
            row["truth"] = truth.name if isinstance(truth, NamedTruth) else ""
            keep = result.trajectory if is_default and result.status == "ok" else None
            keep = keep.select(scenario.output_bodies) if keep is not None else None
            self._add(row, keep)

    def _fail(self, group: Group, setting: Setting, is_default: bool, status: Any, message: str) -> None:
        row = failure_row(group.scenario, group.engine, group.version, setting, is_default, status, message)
        self._add(row)

    def _add(self, row: dict[str, Any], trajectory: Trajectory | None = None) -> None:
        """Store a row made now: stamped with the revision, not stale."""
        row.update(revision=self.revision, stale=False)
        self.store.add(row, trajectory)

    def _save(self) -> None:
        versions = {
            name: (a if isinstance(a, str) else a._safe_version()) for name, a in self.adapters.items()
        }
        meta = {
            **provenance.describe(),
            "suite": self.suite,
            "engines": versions,
            "repeats": self.options.repeats,
            "warmup": self.options.warmup,
            "timeout": self.options.timeout,
            "revisions": sorted({str(r.get("revision") or "unknown") for r in self.store.rows.values()}),
            "resume": self.resume_log.lines(),
            "truth": (
                "each row's `truth` column: the closed form where the scenario has one, else the "
                "native solver on a refined grid at tight tolerance; for dynamic scenarios the native "
                "forward dynamics at tight tolerance"
            ),
            "headline": HEADLINE_DEFINITION,
            "scales": SCALE_DEFINITION,
        }
        self.store.save(meta)


def timed_run(
    adapter: Adapter, scenario: Scenario, setting: Setting, times: np.ndarray, opts: RunOptions
) -> tuple[RunResult, int]:
    """The adapter's run, timed as the minimum of `opts.repeats` after the warm-up, except that a
    run longer than LONG_RUN is timed once (its timing noise is small against its length). Returns
    the result and the number of timed repeats."""
    first = adapter.run(scenario, setting, times, repeats=1, warmup=opts.warmup)
    if first.status != "ok" or opts.repeats <= 1 or first.run_time > LONG_RUN:
        return first, 1
    more = adapter.run(scenario, setting, times, repeats=opts.repeats - 1, warmup=0)
    if more.status != "ok":  # an engine that fails on a repeat of the same run: that is its result
        return more, opts.repeats
    best = dataclasses.replace(
        first, run_time=min(first.run_time, more.run_time), build_time=min(first.build_time, more.build_time)
    )
    return best, opts.repeats


class ComparisonError(Exception):
    """An engine's trajectory that cannot be set against the truth (wrong grid or bodies)."""


def compare(
    scenario: Scenario, result: RunResult, truth: Trajectory | str, residual: Residual | None
) -> tuple[dict[str, float], tuple[str, ...], str]:
    """Error metrics, compared levels and a note (why something is missing) for one run."""
    if result.status != "ok" or result.trajectory is None:
        return {}, (), ""
    if isinstance(truth, str):
        return {}, (), truth
    notes = []
    try:
        metrics = error_metrics(scenario, result.trajectory, truth)
        metrics.update(level_errors(scenario, result.trajectory, truth))
        metrics["error"] = metrics["error_position"]  # one headline: the position level
        levels = compared_levels(scenario, result.trajectory, truth)
    except (ValueError, KeyError) as error:  # the engine's trajectory is not what it should be
        raise ComparisonError(f"cannot compare with the truth: {error}") from error
    if residual is None:
        notes.append("constraint residual not measured (reference_solver.constraint_residual missing)")
    else:
        try:
            metrics.update(residual_metrics(scenario, result.trajectory, residual))
        except Exception as error:
            notes.append(f"constraint residual failed: {type(error).__name__}: {error}")
            metrics["constraint_residual"] = math.nan
    if scenario.analysis == "dynamic":
        try:
            metrics["energy_drift"] = energy_drift(scenario, result.trajectory, truth)
        except (ValueError, KeyError) as error:
            notes.append(f"energy drift not measured: {error}")
    return metrics, levels, "; ".join(notes)
