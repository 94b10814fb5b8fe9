"""The `mbxval` command line: list, solve and export here; run, report, check and bench in
reports.cli.suite_commands; compare in reports.cli.compare_command.

Every failure the user can cause ends with one line `mbxval: error: ...` on stderr, exit status 2,
and no partial output file.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import textwrap
from collections.abc import Callable, Sequence

import numpy as np

import adapters
import reports.cli.compare_command as compare_command
import reports.cli.draw_command as draw_command
import reports.cli.schema_command as schema_command
import reports.cli.store_command as store_command
import reports.cli.suite_commands as suite_commands
from adapters.base import Adapter, OptionValue, Setting, SettingError
from adapters.step_rule import RULE
from adapters.threads import one_blas_thread
from reports.cli.engine_listing import FORMATS, engine_listing
from reports.cli.usage import Parser, UsageError, Versions, pairs, scenario_argument
from reports.gate import GateError
from reports.run import stop
from reports.scoring import consistent_start, self_check
from reports.store import StoreBusy, StoreDamaged, atomic_output, atomic_path, output_target, write_text
from scenarios import Scenario, ScenarioError, all_families, catalogue, limits, load
from scenarios.files import scenario_toml
from scenarios.names import NameRefused, check_scenario_name
from scenarios.scenario import characteristic_rate
from scenarios.trajectory import Trajectory


def _option_value(text: str) -> OptionValue:
    for kind in (int, float):
        try:
            return kind(text)  # type: ignore[no-any-return]
        except ValueError:
            pass
    return text


def load_engine(name: str) -> Adapter:
    try:
        return adapters.load(name)
    except adapters.EngineUnavailable as error:
        raise UsageError(str(error)) from error


def time_grid(
    scenario: Scenario, t_end: float | None, steps: int | None, dt: float | None, dense: bool = False
) -> np.ndarray:
    """The output grid: `steps` equal steps over [0, t_end] (Scenario.times, the grid `run`
    measures on), or multiples of `dt` up to t_end; refused before it is made if its work (`dense`
    or not, scenarios.limits) is above the limit."""
    t_end = scenario.t_end if t_end is None else t_end
    if not (math.isfinite(t_end) and limits.MIN_T_END <= t_end <= limits.MAX_T_END):
        raise UsageError(f"--t-end must be in [{limits.MIN_T_END:g}, {limits.MAX_T_END:g}] s, got {t_end}")
    bodies = len(scenario.bodies)
    if dt is not None:
        if not (math.isfinite(dt) and 0 < dt <= t_end):
            raise UsageError(f"--dt must be positive and at most --t-end, got {dt}")
        limits.check_grid(scenario.name, t_end / dt + 1, bodies, dense)  # before allocating
        steps = math.floor(t_end / dt + 1e-9)
        return dt * np.arange(steps + 1)
    steps = scenario.steps if steps is None else steps
    if steps < 1:
        raise UsageError(f"--steps must be at least 1, got {steps}")
    limits.check_grid(scenario.name, steps + 1, bodies, dense)
    return np.asarray(scenario.times(t_end, steps))


def engine_setting(adapter: Adapter, scenario: Scenario, mode: str | None, options: list[str]) -> Setting:
    """The engine's default setting for the scenario, with a mode and options overridden."""
    setting = adapter.default_setting(scenario)
    if mode is not None:
        setting = Setting(mode, setting.options)
    overrides = {k: _option_value(v) for k, v in pairs(options, "--setting").items()}
    setting = setting.replace(**overrides) if overrides else setting
    try:
        adapter.check_setting(setting)
    except SettingError as error:
        raise UsageError(str(error)) from None
    return setting


def cmd_list(args: argparse.Namespace) -> int:
    """A scenario x engine table of what each engine supports, the reasons below it, what each
    engine mode measures, then each family's parameters with their defaults; with --engine, that
    engine's modes, options and accuracy knobs alone (reports.cli.engine_listing)."""
    if args.engine is not None:
        if args.scenarios or args.stress:
            raise UsageError("--engine lists one engine's knobs: give it without scenarios or --stress")
        try:
            print(engine_listing(args.engine, args.format), end="")
        except adapters.EngineUnavailable as error:
            raise UsageError(str(error)) from None
        return 0
    if args.format != "text":
        raise UsageError("--format applies to --engine NAME only")
    engines = {}
    for name in adapters.names():
        try:
            engines[name] = adapters.load(name)
        except adapters.EngineUnavailable as error:
            print(f"engine {name}: unavailable ({error})")
    print("engines: " + ", ".join(f"{n} {a._safe_version()}" for n, a in engines.items()))
    names = args.scenarios or catalogue(include_stress=args.stress, include_dynamic=True)
    width = max(len(n) for n in names) + 2
    print("\n" + "scenario".ljust(width) + "".join(e.ljust(12) for e in engines))
    reasons: list[str] = []
    for name in names:
        scenario = load(name)
        cells = []
        for engine, adapter in engines.items():
            try:
                reason = adapter.supports(scenario)
            except Exception as error:  # a broken adapter costs its own cell only
                reason = f"cannot tell: its supports() failed: {type(error).__name__}: {error}"
            if reason is None:
                cells.append("yes")
            else:
                reasons.append(f"[{len(reasons) + 1}] {engine} on {name}: {reason}")
                cells.append(f"no [{len(reasons)}]")
        print(name.ljust(width) + "".join(c.ljust(12) for c in cells))
    if reasons:
        print("\n" + "\n".join(reasons))
    chosen = [
        f"  {engine} on {name}: {why}"
        for name in names
        for engine, adapter in engines.items()
        if (why := _default_reason(adapter, load(name)))
    ]
    if chosen:
        print("\ndefaults chosen for the scene:\n" + "\n".join(chosen))
    if args.scenarios:
        print("\nscales: errors are divided by these (docs/scenario-files.md):")
        for name in names:
            scenario = load(name)
            print(
                f"  {name}: characteristic_length = {scenario.characteristic_length:g} m, "
                f"characteristic_rate = {characteristic_rate(scenario):.6g} rad/s"
            )
        return 0
    print("\nmodes: what each measures (derived levels named):")
    for engine, adapter in engines.items():
        for mode in adapter.measured:
            print(f"  {engine} {mode.name}: {mode.measures}")
    print(f"\nsettings, one rule (docs/settings-rule.md): {RULE}")
    for engine, adapter in engines.items():
        if adapter.rule:
            print(f"  {engine}: {adapter.rule}")
    print("\nparameters: default and range; set them with --set NAME=VALUE:")
    for fam in all_families().values():
        print(f"  {fam.name}:")
        for key, parameter in fam.parameters.items():
            print(f"    {key}={parameter.default}  ({parameter.describe()})")
    return 0


def _default_reason(adapter: Adapter, scenario: Scenario) -> str:
    """The adapter's reason for its default on `scenario`; a broken adapter costs its own line."""
    try:
        return adapter.default_reason(scenario)
    except Exception as error:
        return f"cannot tell: its default_reason() failed: {type(error).__name__}: {error}"


def solve_trajectory(
    scenario: Scenario,
    engine: str,
    mode: str | None = None,
    options: Sequence[str] = (),
    grid: tuple[float | None, int | None, float | None] = (None, None, None),
) -> Trajectory:
    """The trajectory of the scenario's output bodies by one engine, on the grid (t_end, steps, dt)
    gives (each None: the scenario's); UsageError for bad input or a run that is not ok."""
    adapter = load_engine(engine)
    times = time_grid(scenario, *grid, dense=engine != adapters.NATIVE or limits.dense(scenario))
    setting = engine_setting(adapter, scenario, mode, list(options))
    one_blas_thread()
    from reference_solver.compiled import compile_where_it_pays  # on use: --help imports no solver

    compile_where_it_pays()  # one command: the plain path where loading the kernels costs more
    result = adapter.run(scenario, setting, times)
    if result.status != "ok" or result.trajectory is None:
        when = "" if result.failure_time is None else f" at t={result.failure_time:.6g}"
        raise UsageError(f"{engine} {result.status}{when}: {result.message}")
    halving = self_check.step_halving(adapter, scenario, setting, times, result.trajectory)
    drift = self_check.of_trajectory(scenario, result.trajectory, halving)
    if drift:  # ok by the engine, wrong by its own figures: said, the exit status stays 0
        print(f"mbxval: warning: {engine} {drift}", file=sys.stderr)
    return result.trajectory.select(scenario.output_bodies)


def cmd_solve(args: argparse.Namespace) -> int:
    if args.out is not None:
        output_target(args.out)  # a device, FIFO or directory is refused before solving
    scenario = consistent_start(load(args.scenario, pairs(args.set, "--set")))
    grid = (args.t_end, args.steps, args.dt)
    trajectory = solve_trajectory(scenario, args.engine, args.mode, args.setting, grid)
    if args.out is None:
        trajectory.write_csv(sys.stdout)
    else:
        with atomic_output(args.out) as stream:
            trajectory.write_csv(stream)
    return 0


def renamed(scenario: Scenario, name: str | None) -> Scenario:
    """The scenario under the name a file's user gives it (`export --name`): its whole name, so
    that the file runs beside the family it came from; unchanged without a name."""
    if name is None:
        return scenario
    try:
        check_scenario_name(name, "--name")
    except NameRefused as refused:
        raise UsageError(str(refused)) from None
    return dataclasses.replace(scenario, family=name, variant="default", point=())


def cmd_export(args: argparse.Namespace) -> int:
    output_target(args.out)
    scenario = load(args.scenario, pairs(args.set, "--set"))
    if args.name is not None and args.format != "toml":
        raise UsageError("--name names a scenario file: give it with --format toml")
    scenario = renamed(scenario, args.name)
    if args.format == "toml":
        write_text(args.out, scenario_toml(scenario))
        print(f"wrote {args.out}")
        return 0
    engine = args.engine or next(iter(adapters.exporters()), adapters.NATIVE)
    adapter = load_engine(engine)
    setting = engine_setting(adapter, scenario, args.mode, args.setting)
    reason = adapter.supports(scenario)
    if reason is not None:
        raise UsageError(f"{engine} cannot represent {scenario.name}: {reason}")
    try:
        with atomic_path(args.out) as temp:  # the engine's own writer fills a temporary file
            adapter.export(scenario, setting, str(temp))
    except NotImplementedError as error:
        raise UsageError(str(error)) from error
    print(f"wrote {args.out}")
    return 0


def _scenario_arguments(parser: argparse.ArgumentParser, engine_default: str | None) -> None:
    """The scenario and engine arguments; no `engine_default`: the first engine with a model file."""
    scenario_argument(parser)
    said = engine_default or "the first with a model file of its own, such as MJCF"
    parser.add_argument("--engine", default=engine_default, help=f"engine (default: {said})")
    parser.add_argument("--mode", help="engine mode (for example RK4, implicitfast, kinematic)")
    parser.add_argument(
        "--setting",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="engine setting, such as dt=1e-4",
    )


def parser() -> argparse.ArgumentParser:
    top = Parser(
        prog="mbxval",
        description=textwrap.fill(
            "Cross-validate planar multibody kinematics: solve the same mechanism with a "
            "reference solver and several engines, and compare their errors.",
            90,
        ),
        epilog="example: mbxval list; mbxval solve four_bar --out four_bar.csv;\n"
        "  mbxval run --out results; mbxval report results; mbxval --version",
        formatter_class=argparse.RawDescriptionHelpFormatter,  # keeps the epilog's lines
    )
    top.add_argument("-V", "--version", action=Versions, help="print the versions")
    sub = top.add_subparsers(dest="command", required=True, parser_class=Parser)

    listing = sub.add_parser("list", help="scenarios, variants, engines and what each supports")
    listing.add_argument("--stress", action="store_true", help="include the stress variants")
    listing.add_argument("scenarios", nargs="*", help="only these scenarios or scenario files (.toml)")
    listing.add_argument("--engine", help="only this engine: its modes, options and accuracy knobs")
    listing.add_argument(
        "--format", choices=FORMATS, default="text", help="with --engine: one line each, or Markdown tables"
    )

    solve = sub.add_parser("solve", help="one trajectory as CSV")
    _scenario_arguments(solve, adapters.NATIVE)
    solve.add_argument("--t-end", type=float, help="end time (default: the scenario's)")
    grid = solve.add_mutually_exclusive_group()
    grid.add_argument("--steps", type=int, help="number of equal steps (rows = steps + 1)")
    grid.add_argument("--dt", type=float, help="output step")
    solve.add_argument("--out", help="CSV file (default: stdout)")

    export = sub.add_parser("export", help="write the engine's own model file")
    _scenario_arguments(export, None)
    export.add_argument("--out", required=True, help="model file to write")
    export.add_argument(
        "--format",
        choices=("engine", "toml"),
        default="engine",
        help="engine: the engine's own model file; toml: an mbxval scenario file",
    )
    export.add_argument("--name", help="the scenario file's name (default: the scenario's; --format toml)")

    suite_commands.add_parsers(sub)
    compare_command.add_parser(sub)
    draw_command.add_parser(sub)
    schema_command.add_parser(sub)
    store_command.add_parser(sub)
    for name, subparser in sub.choices.items():
        what, example = GUIDE[name]
        subparser.description, subparser.epilog = textwrap.fill(what, 90), "example:\n  " + example
        subparser.formatter_class = argparse.RawDescriptionHelpFormatter
    return top


GUIDE: dict[str, tuple[str, str]] = {
    "list": (
        "Which scenarios exist, which engine can represent each (and why not), and every scenario "
        "parameter with its default and allowed range; with --engine NAME, that engine's modes, options "
        "and accuracy knobs (swept, fixed or not applicable, and why).",
        "mbxval list --stress; mbxval list --engine mujoco",
    ),
    "solve": (
        "Solve one scenario with one engine and write its trajectory as CSV: t, then x, y, theta and "
        "their first and second derivatives for every moving body.",
        "mbxval solve slider_crank --engine mujoco --set offset=0.05 --steps 100 --out sc.csv",
    ),
    "export": (
        "Write the engine's own model of a scenario, to open in that engine's tools.",
        "mbxval export four_bar --engine mujoco --out four_bar.xml\n"
        "  python -m mujoco.viewer --mjcf four_bar.xml",
    ),
    "run": (
        "The main job: run a suite of scenarios on every engine over its settings, store one row per "
        "run, and write an HTML and a Markdown report. Runs already stored are skipped.",
        "mbxval run --out mbxval-report --scenario four_bar --engine exudyn",
    ),
    "report": (
        "Render the report again from stored results alone, without running anything.",
        "mbxval report mbxval-report",
    ),
    "check": (
        "Regression gate for CI: compare results with a committed baseline; exit 1 with one line per "
        "cell whose status got worse or whose error grew past the factor.",
        "mbxval check --baseline default --junit check.xml",
    ),
    "compare": (
        "Score a trajectory made by any tool (the CSV `mbxval solve` writes: t, then BODY.x BODY.y "
        "BODY.theta, BODY.vx ... BODY.alpha; missing bodies and levels are allowed) against the same "
        "truth and with the same metrics as a run; with --out, add it to a results store so the "
        "report shows it beside the engines.",
        "mbxval compare slider_crank my_tool.csv --label my_tool --out mbxval-report",
    ),
    "draw": (
        "Draw the mechanism as one self-contained SVG: bodies, joints, gears, cams and drivers, "
        "labelled, posed by the native solver at time t; with --frames N, one cycle animated in a "
        "browser. Hover a body or joint for its name and position.",
        "mbxval draw examples/watt_six_bar.toml --t 0.3 --out six_bar.svg\n"
        "  mbxval draw cam_roller --set profile=lobed --frames 48 --out cam.svg",
    ),
    "schema": (
        "Print the JSON Schema of the scenario file format, so that editors complete and check "
        "scenario files (TOML editors such as Taplo read a `#:schema FILE` first line).",
        "mbxval schema --out scenario.schema.json",
    ),
    "store": (
        "Repair a results store that mbxval refuses because its `current` link is missing or odd "
        "(a copy made with cp -rL, a deleted link) or a generation does not verify: every generation "
        "that verifies is kept, one that does not is moved aside, never deleted.",
        "mbxval store repair mbxval-report",
    ),
    "bench": (
        "Measure the native solver's speed beside the engines (benchmarks, run on demand).",
        "mbxval bench speed",
    ),
}


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "list": cmd_list,
    "solve": cmd_solve,
    "export": cmd_export,
    **suite_commands.COMMANDS,
    **compare_command.COMMANDS,
    **draw_command.COMMANDS,
    **schema_command.COMMANDS,
    **store_command.COMMANDS,
}


def main(argv: Sequence[str] | None = None) -> int:
    """Run one command; bad input is one line and exit 2, Ctrl-C one line and exit 130, a closed
    pipe (`mbxval solve ... | head`) ends quietly with 141 (128 + SIGPIPE, as a shell reports it)."""
    stop.catch_sigterm()
    try:
        args = parser().parse_args(argv)
        status = COMMANDS[args.command](args)
        stop.raise_if_terminated()  # a SIGTERM whose exception was swallowed still ends as one
        return status
    except BrokenPipeError:
        return stop.closed_pipe()
    except KeyboardInterrupt as error:
        return stop.interrupted(f"interrupted ({' '.join(sys.argv[1:2]) or 'mbxval'})", error)
    except (UsageError, ScenarioError, StoreDamaged, StoreBusy, GateError, OSError) as error:
        return stop.usage_error(str(error))
