"""The adapter contract: the small base class every engine adapter derives from.

A subclass provides exactly:
    name: str                                  the engine's name on the command line
    measured: tuple[Mode, ...]                 its modes (integrators, solvers), each with what it
                                               measures (adapters.modes), the first the default;
                                               `modes`, their names, is derived from it (an engine
                                               without `measured` declares `modes` alone)
    options: tuple[Option, ...]                every option a setting may carry, typed and ranged
    knobs: tuple[Knob, ...]                    every accuracy knob (each option, and each engine
                                               setting that changes the error), swept, fixed or not
                                               applicable, with why (adapters.knobs): what
                                               `mbxval list --engine NAME` and docs/engine-knobs.md show
    version() -> str                           the installed engine's version
    supports(scenario) -> str | None           None, or why the engine cannot represent it faithfully
    default_setting(scenario) -> Setting       the setting used by `mbxval solve` and the status matrix
                                               (and may say why it departs from the engine's usual
                                               one: default_reason(scenario) -> str)
    ladder(scenario) -> list[Setting]          the settings ladder: settings for the work-precision
                                               curves; a mode named UNTUNED in it is the engine's own
                                               defaults (`untuned_setting` finds it)
    build(scenario, setting) -> model          the engine's own model (not timed)
    simulate(model, times) -> Trajectory       the timed part; must not depend on earlier calls.
It may also provide export(scenario, setting, path) in the engine's own file format,
untuned_setting(scenario) (the engine's own defaults as a new user's model gets them, at the rule's
step: the report's "untuned" point beside the default and the best; by default the ladder's setting
in the mode UNTUNED, None where there is none), and call `self.count_steps(n)` inside `simulate`
to report the engine steps taken. Its other facts are data here too, so that nothing outside its
subpackage names it: `colour` (its colour in the report's figures), `packages` (the distributions
whose versions a run records) and `probe_settings` (its settings for a stress case that probes
what it has knobs for, adapters.probes).

Every setting is checked against `modes` and `options` where it enters (`check_setting`): an unknown
mode or key, a value of the wrong type or outside its range is a SettingError naming the known ones or
the limit, raised before anything is built. A step `dt` that would take more than MAX_STEPS steps
over the grid is refused too (a failed run saying so).

simulate raises an EngineFailure subclass (Diverged, Singular, Unsupported) or lets any other
exception escape: the base's `run` turns every outcome into a RunResult with a status and a message,
times the parts, records Python warnings, and rejects non-finite trajectories. A failing engine never
raises out of `run`. Its untimed warm-up runs simulate the grid's first interval only (WARMUP_POINTS),
which pays every first call's cost without paying the whole horizon again.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any, ClassVar

import numpy as np

from adapters.failures import STATUSES, Diverged, EngineFailure, SettingError, Singular, Status, Unsupported
from adapters.knobs import Knob
from adapters.modes import Mode, measures_of
from adapters.probes import Probe
from adapters.run_result import RunResult, failure_fields, first_nonfinite_time, warning_texts
from adapters.setting import Option, OptionValue, Setting
from adapters.spent import Stopwatch
from adapters.timing import timed
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory

__all__ = [  # the contract a plug-in engine imports from here; failures and settings are their own modules
    "MAX_STEPS",
    "STATUSES",
    "UNTUNED",
    "Adapter",
    "Diverged",
    "EngineFailure",
    "Knob",
    "Option",
    "OptionValue",
    "RunResult",
    "Setting",
    "SettingError",
    "Singular",
    "Status",
    "Unsupported",
]


class Adapter:
    """Base class of engine adapters; see the module docstring for what a subclass provides."""

    name: ClassVar[str] = ""
    measured: ClassVar[tuple[Mode, ...]] = ()
    """The engine's modes, each with what it measures (adapters.modes): the one declaration of them."""
    modes: ClassVar[tuple[str, ...]] = ()
    """The names of `measured` in its order, derived (__init_subclass__); declared only by an engine
    that declares no `measured`."""
    options: ClassVar[tuple[Option, ...]] = ()
    knobs: ClassVar[tuple[Knob, ...]] = ()
    """The engine's accuracy knobs (adapters.knobs): every option is one, beside the engine's own
    settings that change the error."""
    rule: ClassVar[str] = ""
    """How the engine applies the settings rule (adapters.step_rule): its constants, one line."""
    dynamics: ClassVar[bool] = False
    """Whether the engine runs forward dynamics (scenarios whose `analysis` is "dynamic")."""
    colour: ClassVar[str] = ""
    """The engine's colour in the report's figures, `#rrggbb` or `#rgb`, stored with its runs ('' for
    one from a shared palette; anything else is warned about and given one: reports.run.engine_facts)."""
    packages: ClassVar[tuple[str, ...]] = ()
    """The distributions (as pip names them) whose installed versions a run records beside ours."""

    def __init__(self) -> None:
        self._steps = 0

    # --- what a subclass provides -------------------------------------------------------------
    def version(self) -> str:
        raise NotImplementedError

    def supports(self, scenario: Scenario) -> str | None:
        return None

    def default_setting(self, scenario: Scenario) -> Setting:
        raise NotImplementedError

    def default_reason(self, scenario: Scenario) -> str:
        """Why the default setting for `scenario` is not the engine's usual one ('' where it is):
        `mbxval list` prints it beside the scenario."""
        return ""

    def ladder(self, scenario: Scenario) -> list[Setting]:
        """The settings ladder: the settings the work-precision curves run over (by default the
        default setting alone). Not the parameter sweep of `mbxval run --sweep`."""
        return [self.default_setting(scenario)]

    def untuned_setting(self, scenario: Scenario) -> Setting | None:
        """The engine as a new user's model has it (its own defaults at the rule's step): the
        ladder's first setting in the mode named UNTUNED, or None for an engine without one."""
        return next((s for s in self.ladder(scenario) if s.mode == UNTUNED), None)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """A subclass's `modes` from its `measured`."""
        super().__init_subclass__(**kwargs)
        if "measured" in cls.__dict__ and "modes" not in cls.__dict__:
            cls.modes = tuple(mode.name for mode in cls.measured)

    def build(self, scenario: Scenario, setting: Setting) -> Any:
        raise NotImplementedError

    def simulate(self, model: Any, times: np.ndarray) -> Trajectory:
        raise NotImplementedError

    def export(self, scenario: Scenario, setting: Setting, path: str) -> None:
        raise NotImplementedError(f"engine '{self.name}' has no model file format to export")

    def probe_settings(self, probe: Probe, scenario: Scenario) -> list[Setting] | None:
        """The settings to run a stress case that probes `probe` with (the first its default), or
        None for the engine's own default: an engine without knobs for what is probed keeps it."""
        return None

    # --- owned by the base ---------------------------------------------------------------------
    def check_setting(self, setting: Setting) -> Setting:
        """`setting` with every value typed, or SettingError naming what is unknown or out of range."""
        if setting.mode not in self.modes:
            raise SettingError(f"{self.name}: unknown mode '{setting.mode}'; known: {', '.join(self.modes)}")
        declared = {option.name: option for option in self.options}
        typed: dict[str, OptionValue] = {}
        for key, value in setting.options:
            if key not in declared:
                known = ", ".join(declared) or "none"
                raise SettingError(f"{self.name}: unknown option '{key}'; known: {known}")
            typed[key] = declared[key].check(self.name, value)
        return Setting.of(setting.mode, **typed)

    def count_steps(self, n: int) -> None:
        """Called by `simulate` to report engine steps taken."""
        self._steps += n

    def run(
        self,
        scenario: Scenario,
        setting: Setting | None = None,
        times: Sequence[float] | np.ndarray | None = None,
        repeats: int = 1,
        warmup: int = 0,
        once_above: float = math.inf,
        agree: float = 0.0,
        budget: float = math.inf,
    ) -> RunResult:
        """Build once and simulate, timing the build apart and the simulation as the minimum over
        `repeats` after `warmup` untimed runs over the grid's first interval (_warm_up), or once
        where the first timed run takes longer than `once_above` seconds, or fewer where a repeat
        agrees with the best before it to a relative `agree`, or where one more would take the
        repeats past `budget` CPU seconds (adapters.timing.timed); the warm-up's
        and the repeats' seconds are measured too (what the run's timing cost), for a run that fails
        up to its failure (adapters.spent). Times are the process's CPU seconds, the wall clock's
        beside them (adapters.timing). Never raises for an engine's failure."""
        setting = setting or self.default_setting(scenario)
        base: Mapping[str, Any] = {
            "engine": self.name,
            "version": self._safe_version(),
            "setting": setting,
            "measures": measures_of(self.measured, setting.mode),
        }
        grid = np.asarray(scenario.times() if times is None else times, dtype=float)
        try:
            setting = self.check_setting(setting)
        except SettingError as error:
            return RunResult(**base, status="failed", message=str(error))
        refused = self._refusal(scenario, setting, grid)
        if refused is not None:
            return RunResult(**base, status=refused[0], message=refused[1])
        caught: list[warnings.WarningMessage] = []
        watch = Stopwatch()
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                built = timed(lambda: self.build(scenario, setting))
                model = built.result
                watch.built()

                def simulate() -> Trajectory:
                    self._steps = 0
                    return self.simulate(model, grid)

                warm = self._warm_up(model, grid, watch)
                timing = timed(
                    simulate, repeats, warmup, once_above=once_above, warm=warm, agree=agree, budget=budget
                )
        except Exception as error:  # an engine's failure, or its own exception: recorded, never raised
            build, warmed, repeated = watch.spent(warmup)
            build_wall, warmed_wall, repeated_wall = watch.spent_wall(warmup)
            return RunResult(
                **base,
                **failure_fields(error),
                build_time=build,
                warmup_time=warmed,
                repeats_time=repeated,
                build_time_wall=build_wall,
                warmup_time_wall=warmed_wall,
                repeats_time_wall=repeated_wall,
                warnings=warning_texts(caught),
            )
        spent: dict[str, Any] = {
            "build_time": built.best,
            "warmup_time": timing.warmup_time,
            "repeats_time": timing.repeats_time,
            "build_time_wall": built.best_wall,
            "warmup_time_wall": timing.warmup_time_wall,
            "repeats_time_wall": timing.repeats_time_wall,
        }
        trajectory = timing.result
        if not trajectory.is_finite():
            return RunResult(
                **base,
                status="diverged",
                message="the trajectory has non-finite values",
                failure_time=first_nonfinite_time(trajectory),
                **spent,
                warnings=warning_texts(caught),
            )
        return RunResult(
            **base,
            status="ok",
            trajectory=trajectory,
            run_time=timing.best,
            run_time_wall=timing.best_wall,
            **spent,
            repeats=timing.repeats,
            steps=self._steps,
            warnings=warning_texts(caught),
        )

    def _warm_up(self, model: Any, grid: np.ndarray, watch: Stopwatch | None = None) -> Callable[[], object]:
        """One untimed warm-up run: the simulation over the grid's first WARMUP_POINTS times, which
        makes every first call a timed run would (imports, compiled kernels, the engine's programs
        and allocations for this model). Where that short run raises, the warm-up is the whole grid
        instead: a run that fails then fails as it did, with the whole run's message and time, and
        an engine that cannot take a short grid is warmed as before."""
        prefix = grid[:WARMUP_POINTS]

        def warm() -> Trajectory:
            try:
                result = self.simulate(model, prefix)
            except Exception:
                result = self.simulate(model, grid)
            if watch is not None:
                watch.warmed()
            return result

        return warm

    def _refusal(self, scenario: Scenario, setting: Setting, grid: np.ndarray) -> tuple[Status, str] | None:
        """Why a checked setting is not run on `scenario` (status and message), or None: more steps
        than MAX_STEPS, a scenario the engine cannot represent, forward dynamics it does not do."""
        too_many = _too_many_steps(setting, grid)
        if too_many:
            return "failed", too_many
        reason = self.supports(scenario)
        if reason is None and scenario.analysis == "dynamic" and not self.dynamics:
            reason = f"{self.name} is not yet compared on forward dynamics"
        return ("unsupported", reason) if reason is not None else None

    def _safe_version(self) -> str:
        """The engine's version, asked once per adapter (importlib.metadata reads files each time)."""
        known: str | None = self.__dict__.get("_known_version")
        if known is None:
            try:
                known = self.version()
            except Exception:
                known = "unknown"
            self.__dict__["_known_version"] = known
        return known


UNTUNED = "untuned"
"""The mode name of an engine's own defaults as a new user's model has them, at the rule's step:
the report's 'untuned' point beside the rule's default and the ladder's best."""

WARMUP_POINTS = 2
"""A warm-up run simulates the grid's first this many times: its first interval, the shortest grid
on which every engine takes a step (and records a point on each side of it), so that it pays each
first call (kernels, programs, the step, the output) and not the horizon."""

MAX_STEPS = 1e7
"""A setting whose step `dt` would take more engine steps than this over the grid is refused: such
a run takes hours or forever, whatever the engine."""


def _too_many_steps(setting: Setting, grid: np.ndarray) -> str:
    """Why the setting's step is too small for the grid, or ""."""
    dt = setting.get("dt")
    if dt is None or len(grid) < 2:
        return ""
    planned = float(grid[-1] - grid[0]) / float(dt)
    if planned <= MAX_STEPS:
        return ""
    return f"dt = {float(dt):.3g} s would take {planned:.3g} steps over the grid (at most {MAX_STEPS:.0e})"
