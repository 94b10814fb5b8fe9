"""The runner: scenario x engine x setting, each run isolated, every outcome stored as a row.

For each scenario the truth (reports.scoring.truth: the closed form where there is one, else the
native solver refined; or the suite's own hook) is computed once on the scenario's grid, in
this process (with a time limit), so that the solver's JIT-compiled kernels are compiled once and
inherited by the forked runs;
each scenario-engine group's runs are then made by reports.run.group_runs.run_group (build
timed apart, simulation timed as the minimum of repeats after a warm-up by the adapter's base class,
errors against the truth computed beside it, in a warm forked worker per engine, kept from group
to group, with a time limit per run): a crash, a hang or a divergence costs that row only. Rows
already stored are skipped unless `rerun`; the store is saved after a group when
`RunConfig.save_interval` has passed since the last save, and at the end. A Dask task
(reports.run.dask_backend) runs a group with the same `run_group`.
"""

from __future__ import annotations

import functools
import math
import sys
import threading
import time
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import tqdm

import adapters
import reports.run.stop as stop
from adapters.base import Adapter, Setting
from adapters.threads import one_blas_thread
from reports.run.engine_facts import colours, engine_packages
from reports.run.group_runs import RunConfig, Workers, run_group
from reports.run.isolation import Outcome, run_here, run_isolated
from reports.run.planning import NOT_INSTALLED, Group, SettingsHook, plan_engine
from reports.run.resume import ResumePolicy, StoredRuns
from reports.scoring import (
    HEADLINE_DEFINITION,
    SCALE_DEFINITION,
    TRUTH_TOLERANCE,
    NamedTruth,
    Residual,
    consistent_start,
    independent_truth,
    named,
)
from reports.store import ResultsStore, provenance
from scenarios import Scenario, ScenarioError
from scenarios import load as build_scenario
from scenarios.trajectory import Trajectory

Truth = Callable[[Scenario, np.ndarray], Trajectory | NamedTruth]
"""A truth hook: the truth of a scenario on a grid; a bare trajectory is named HOOK_TRUTH."""
HOOK_TRUTH = f"native, tolerance {TRUTH_TOLERANCE:g}"
Loader = Callable[[str], Adapter]


def reference_residual() -> Residual | None:
    """The lead's `reference_solver.constraint_residual`, when it exists."""
    import reference_solver

    return getattr(reference_solver, "constraint_residual", None)


OURS = ("adapters", "scenarios", "reports", "reference_solver", "mbxval", "benchmarks", "tests")
"""Our own packages: a module of ours that is missing is a broken install, not an absent engine."""


def not_installed(error: BaseException) -> str:
    """The missing third-party module behind a loader's error (an engine whose package is not
    installed, such as an optional extra), or "" for any other failure."""
    seen: BaseException | None = error
    while seen is not None:
        if isinstance(seen, ModuleNotFoundError) and seen.name and seen.name.split(".")[0] not in OURS:
            return f"no module named {seen.name}"
        seen = seen.__cause__
    return ""


class Runner:
    """Runs scenarios on engines into a ResultsStore."""

    def __init__(
        self,
        store: ResultsStore,
        engines: Sequence[str],
        config: RunConfig,
        loader: Loader = adapters.load,
        truth: Truth | None = None,  # None: independent_truth (closed form, else refined native)
        residual: Residual | None = None,  # None: reference_solver.constraint_residual
        progress: bool = True,
        suite: str = "",
        settings: SettingsHook | None = None,
    ) -> None:
        self.store, self.engines, self.config = store, list(engines), config
        self.truth, self.progress, self.suite = truth or independent_truth, progress, suite
        self.settings, self.loader = settings, loader
        self.residual = residual if residual is not None else reference_residual()
        self.adapters: dict[str, Adapter | str] = {}
        self.made: Counter[str] = Counter()
        """The rows this runner made, by status: what one run did, apart from the store's total."""
        self.planned: dict[str, Scenario] = {}
        """The scenarios of the last `run`, by name (as built for it: a file's, with its sets)."""
        self.revision = provenance.git_revision()
        self.provenance = provenance.describe(
            engine_packages()
        )  # machine, packages, revision: once, not per save
        self.saved_at = -math.inf
        """When the store was last saved (time.monotonic); a run counts its interval from its start."""
        self.policy = ResumePolicy(config.rerun, config.keep_failures, config.keep_stale)
        self.stored = StoredRuns(store, self.revision, self.policy)
        for name in self.engines:
            try:
                self.adapters[name] = loader(name)
            except Exception as error:  # not installed, or its module is broken
                missing = not_installed(error)
                if missing:
                    print(
                        f"mbxval: engine {name} is not installed ({missing}): no runs of it", file=sys.stderr
                    )
                    self.adapters[name] = NOT_INSTALLED
                else:
                    self.adapters[name] = f"engine unavailable: {type(error).__name__}: {error}"

    workers = 1
    """Runs made at the same time (the `workers` column): one by one here."""

    def run(self, scenario_names: Sequence[str]) -> None:
        """Plan every group, then run what is not stored yet, saving as RunConfig.save_interval says
        and at the end."""
        self.saved_at = time.monotonic()
        one_blas_thread()  # the truths solved here, and every worker forked from here
        groups = [g for name in scenario_names for g in self._plan(name)]
        self.planned = {g.scenario.name: g.scenario for g in groups}
        stored = self.stored = StoredRuns(self.store, self.revision, self.policy)
        kept = {id(g) for g in groups if g.adapter is None and stored.keeps_unavailable(*_pair(g))}
        pending = {
            id(g): [j for j in g.jobs if not stored.keeps(*_pair(g), g.version, j[0].label)] for g in groups
        }
        for line in self.stored.log.lines():
            print(f"mbxval: {line}", file=sys.stderr)
        try:
            self._execute([(g, pending[id(g)]) for g in groups if id(g) not in kept])
        finally:
            self._save(clean=True)

    def _execute(self, groups: list[tuple[Group, list[tuple[Setting, bool]]]]) -> None:
        """Run each group's pending jobs here, one after another (unavailable groups left out)."""
        total = sum(made_rows(group, jobs) for group, jobs in groups)
        truths: dict[str, NamedTruth | str] = {}
        workers = Workers(self.config, self.residual)  # one per engine, kept from group to group
        with progress_bar(total, self.progress, "run") as bar, workers:
            for group, jobs in groups:
                name = group.scenario.name
                self._reconcile(group)
                if group.reason_row is not None:
                    self._add(group.reason_row)
                    tick(bar, f"{name} {group.engine}", str(group.reason_row["status"]))
                    continue
                if jobs and name not in truths:
                    bar.set_description(f"{name} truth", refresh=False)
                    truths[name] = solve_truth(self.truth, group.scenario, self.config.truth_timeout)
                    self._put_truth(group.scenario, truths[name])
                done = functools.partial(tick, bar, f"{name} {group.engine}")
                truth = truths.get(name, "")
                made = run_group(group, jobs, truth, self.config, self.residual, done, workers)
                for row, trajectory in made:
                    self._add(row, trajectory)
                self._save()
                stop.raise_if_terminated()

    # --- planning ---------------------------------------------------------------------------
    def _plan(self, name: str) -> list[Group]:
        try:
            scenario = consistent_start(build_scenario(name))
        except ScenarioError as error:
            raise ScenarioError(f"suite scenario {name} cannot be built: {error}") from error
        return [
            plan_engine(scenario, e, self.adapters[e], self.config.ladder, self.settings)
            for e in self.engines
        ]

    def _reconcile(self, group: Group) -> None:
        planned = None if group.reason_row is not None else {s.label for s, _ in group.jobs}
        self.stored.reconcile(group.scenario.name, group.engine, planned)

    # --- storing ----------------------------------------------------------------------------
    def _put_truth(self, scenario: Scenario, truth: NamedTruth | str) -> None:
        if isinstance(truth, NamedTruth):
            self.store.put_truth(scenario.name, truth.name, truth.trajectory.select(scenario.output_bodies))

    def _add(self, row: dict[str, Any], trajectory: Trajectory | None = None) -> None:
        """Store a row made now: stamped with the revision, not stale."""
        row.update(revision=self.revision, stale=False, workers=self.workers)
        self.store.add(row, trajectory)
        self.made[str(row["status"])] += 1

    def _save(self, clean: bool = False) -> None:
        """Save the store when it is due (RunConfig.save_interval), or now when `clean`."""
        if not clean and time.monotonic() - self.saved_at < self.config.save_interval:
            return
        versions = {
            name: (a if isinstance(a, str) else a._safe_version()) for name, a in self.adapters.items()
        }
        meta = {
            **self.provenance,
            "date": provenance.now(),
            "suite": self.suite,
            "engines": versions,
            "engine_colours": colours(self.engines),
            "native_engine": adapters.NATIVE,
            "repeats": self.config.repeats,
            "warmup": self.config.warmup,
            "timeout": self.config.timeout,
            "revisions": sorted({str(r.get("revision") or "unknown") for r in self.store.rows.values()}),
            "resume": self.stored.log.lines(),
            "truth": (
                "each row's `truth` column: the closed form where the scenario has one, else the "
                "native solver on a refined grid at tight tolerance; for dynamic scenarios the native "
                "forward dynamics at tight tolerance"
            ),
            "headline": HEADLINE_DEFINITION,
            "scales": SCALE_DEFINITION,
        }
        self.store.save(meta, clean)
        self.saved_at = time.monotonic()


def _pair(group: Group) -> tuple[str, str]:
    return group.scenario.name, group.engine


def progress_bar(total: int, shown: bool, unit: str) -> tqdm.tqdm:
    """The progress bar on stderr: in a log rather than a terminal (a CI job), a line every 10 s."""
    tqdm.tqdm.monitor_interval = 0  # no monitor thread: the runs are forked
    interval = 0.1 if sys.stderr.isatty() else 10.0
    return tqdm.tqdm(total=total, file=sys.stderr, disable=not shown, unit=unit, mininterval=interval)


def made_rows(group: Group, jobs: list[tuple[Setting, bool]]) -> int:
    """The rows a group makes, which the bar counts as the run's last line does: one per run, or
    its one row saying why the engine does not run the scenario (a truth is not a row)."""
    return 1 if group.reason_row is not None else len(jobs)


def tick(bar: tqdm.tqdm, what: str, label: str) -> None:
    """One more done on the bar, naming what was done last."""
    bar.set_description(f"{what} {label}", refresh=False)
    bar.update()


def solve_truth(truth: Truth, scenario: Scenario, timeout: float) -> NamedTruth | str:
    """The scenario's truth on its grid, or why there is none. Solved in this process when it is
    the main thread (the solver's compiled kernels are then inherited by the forked runs), else (a
    Dask worker's task thread, where no alarm can be set) in a forked child with the time limit."""
    times = np.asarray(scenario.times())
    here = threading.current_thread() is threading.main_thread()
    return truth_named((run_here if here else run_isolated)(lambda: truth(scenario, times), timeout))


def truth_named(outcome: Outcome[Trajectory | NamedTruth]) -> NamedTruth | str:
    """What a truth hook's call came to: its truth named (a bare trajectory is HOOK_TRUTH), or why
    there is none."""
    if outcome.kind != "ok" or outcome.value is None:
        return f"no reference truth ({outcome.kind}: {outcome.message})"
    return named(outcome.value, HOOK_TRUTH)
