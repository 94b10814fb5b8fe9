"""`mbxval list`, `solve` and `export` as a user meets them: output, exit status, error lines, files."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import adapters
import scenarios
from reports.cli.main import main
from reports.store.results_store import read_trajectories
from scenarios.closed_form import exact
from scenarios.newton_euler import body_forces
from tests.support.engines import ENGINES


def run(capsys, *argv: str) -> tuple[int, str, str]:  # type: ignore[no-untyped-def]
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_writes_the_canonical_csv(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, err = run(capsys, "solve", "slider_crank", "--steps", "10")
    assert code == 0 and err == ""
    frame = pd.read_csv(io.StringIO(out))
    assert len(frame) == 11 and frame["t"].iloc[0] == 0.0
    expected = ["t"] + [
        f"{b}.{c}"
        for b in ("crank", "rod", "slider")
        for c in ("x", "y", "theta", "vx", "vy", "omega", "ax", "ay", "alpha")
    ]
    assert list(frame.columns[: len(expected)]) == expected  # the canonical columns first
    scenario = scenarios.build("slider_crank")
    motion = exact(scenario, frame["t"].to_numpy())
    closed = motion.to_frame()
    np.testing.assert_allclose(frame[expected].to_numpy(), closed[expected].to_numpy(), atol=1e-10)
    # then the inverse dynamics' forces, each the Newton-Euler force on the closed-form motion
    forces = body_forces(scenario, motion)
    extras = [c for c in frame.columns[len(expected) :] if not c.startswith("energy.")]
    assert sorted(extras) == sorted(forces) and forces
    scale = max(float(np.max(np.abs(v))) for v in forces.values())
    for name, truth in forces.items():
        np.testing.assert_allclose(frame[name].to_numpy(), truth, atol=1e-8 * scale, err_msg=name)


def test_solve_with_parameters_dt_and_out(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "cam.csv"
    code, out, _ = run(
        capsys,
        "solve",
        "cam_roller",
        "--set",
        "eccentricity=0.02",
        "--t-end",
        "0.1",
        "--dt",
        "0.025",
        "--out",
        str(target),
    )
    assert code == 0 and out == ""
    frame = pd.read_csv(target)
    np.testing.assert_allclose(frame["t"], [0, 0.025, 0.05, 0.075, 0.1])
    assert "contact.phi" in frame.columns


BAD_INPUTS = {
    "unknown scenario": (
        ["solve", "slider_crnk"],
        "unknown scenario 'slider_crnk' (did you mean 'slider_crank'?)",
    ),
    "unknown variant": (["solve", "four_bar/open"], "unknown variant 'open'"),
    "unknown parameter": (["solve", "four_bar", "--set", "crank=1"], "unknown parameter 'crank'"),
    "not a number": (["solve", "four_bar", "--set", "crank_length=long"], "crank_length must be a number"),
    "bad --set form": (["solve", "four_bar", "--set", "crank_length"], "--set expects NAME=VALUE"),
    "non-physical": (
        ["solve", "spur_gears", "--set", "radius_in=-0.1"],
        "radius_in must be a number in (0, 1e+06] m",
    ),
    "cannot assemble": (["solve", "four_bar", "--set", "crank_length=0.5"], "cannot assemble at t=0"),
    # theta0 = 0.3: the rod stands vertical at t = (pi/2 - 0.3) / 50
    "singular drive": (
        ["solve", "slider_crank", "--set", "rod_length=0.2"],
        "singular configuration at t=0.0254159",
    ),
    "unknown engine": (["solve", "four_bar", "--engine", "adams"], "unknown engine 'adams'"),
    "bad steps": (["solve", "four_bar", "--steps", "0"], "--steps must be at least 1"),
    "argparse error": (["solve", "four_bar", "--steps", "many"], "invalid int value"),
}


@pytest.mark.parametrize("case", list(BAD_INPUTS))
def test_bad_input_one_line_exit_2_no_file(case: str, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    argv, fragment = BAD_INPUTS[case]
    target = tmp_path / "out.csv"
    try:
        code = main([*argv, "--out", str(target)])
    except SystemExit as exit_:  # argparse's own errors
        code = exit_.code  # type: ignore[assignment]
    out, err = capsys.readouterr()
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mbxval: error: ")
    assert fragment in lines[0]
    assert list(tmp_path.iterdir()) == []


def test_output_into_missing_directory_is_a_clean_error(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    code, _, err = run(capsys, "solve", "four_bar", "--out", str(tmp_path / "nowhere" / "x.csv"))
    assert code == 2 and "does not exist" in err and len(err.strip().splitlines()) == 1


def test_existing_output_survives_a_failed_solve(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "keep.csv"
    target.write_text("previous result\n")
    code, _, _ = run(capsys, "solve", "slider_crank", "--set", "rod_length=0.2", "--out", str(target))
    assert code == 2 and target.read_text() == "previous result\n"


def test_list_footnotes_what_an_engine_refuses_with_its_reason(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, _ = run(capsys, "list", "cam_roller[profile=lobed]")
    assert code == 0
    row = next(line.split()[1:] for line in out.splitlines() if line.startswith("cam_roller[profile=lobed]"))
    assert row[1:3] == ["no", "[1]"] and "[1] mujoco on cam_roller[profile=lobed]: " in out
    assert "chatters" in out


def test_list_is_a_table_of_what_each_engine_supports(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, _ = run(capsys, "list")
    assert code == 0
    rows = {
        line.split()[0]: line.split()[1:]
        for line in out.splitlines()
        if line and line.split()[0] in scenarios.catalogue()
    }
    assert set(rows) == set(scenarios.catalogue())
    header = next(line for line in out.splitlines() if line.startswith("scenario"))
    assert header.split()[1:] == list(ENGINES)
    assert rows["slider_crank"] == ["yes"] * len(ENGINES)
    # MuJoCo's knife: a sphere on the offset; an engine without cams says "no" with a note
    cam = scenarios.build("cam_knife_edge/spline")
    with_cams = [e for e in ENGINES if adapters.load(e).supports(cam) is None]
    assert {"reference", "mujoco"} <= set(with_cams)
    assert rows["cam_knife_edge/spline"].count("yes") == len(with_cams)
    assert "    crank_length=0.2  (a number in (0, 1e+06] m)" in out
    assert "stress_" not in out
    # every mode says what it measures: the engine's own solver, or an adapter loop with derived levels
    assert "  mujoco RK4: engine's own solver: MuJoCo's RK4 integrator" in out
    assert "  mujoco kinematic: adapter loop on the engine's kinematics: " in out
    assert (
        "  exudyn STATIC: engine's own solver: " in out and "acceleration (adapter solve with finite" in out
    )


def test_list_stress_adds_the_stress_variants(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, _ = run(capsys, "list", "--stress")
    assert code == 0 and "slider_crank/stress_dead_centre" in out


def test_console_script_exit_status() -> None:
    """The installed entry point, as a user runs it."""
    done = subprocess.run(
        [sys.executable, "-m", "reports.cli", "solve", "nothing"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        "mbxval: error: unknown scenario 'nothing'; known: " + ", ".join(scenarios.all_families())
    ]


@pytest.mark.parametrize(
    ("grid", "expected"),
    [
        (["--t-end", "0.3", "--steps", "7"], [0.3 * k / 7 for k in range(8)]),
        (["--t-end", "0.3", "--dt", "0.1"], [0.0, 0.1, 0.2, 0.30000000000000004]),
        (["--t-end", "0.3", "--dt", "0.08"], [0.0, 0.08, 0.16, 0.24]),
        (["--t-end", "0.3", "--steps", "1"], [0.0, 0.3]),
    ],
)
def test_solve_s_time_column_is_the_grid_the_options_name(
    capsys, grid: list[str], expected: list[float]
) -> None:  # type: ignore[no-untyped-def]
    """The command's own grid builder, end to end: `--steps N` is N + 1 equal steps with both ends,
    `--dt H` the multiples of H up to t_end (0.3 reached when 0.3 / 0.1 rounds below 3)."""
    code, out, _ = run(capsys, "solve", "spur_gears", *grid)
    assert code == 0
    np.testing.assert_allclose(pd.read_csv(io.StringIO(out))["t"], expected, rtol=0, atol=1e-15)


def test_solve_s_default_grid_is_the_scenario_s_and_run_s(capsys, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """Without grid options: the family's declared steps over its t_end, the very times `run`
    stores for the same scenario."""
    code, out, _ = run(capsys, "solve", "four_bar")
    assert code == 0
    times = pd.read_csv(io.StringIO(out))["t"].to_numpy()
    steps = scenarios.all_families()["four_bar"].parameters["steps"].default
    t_end = scenarios.build("four_bar").t_end
    assert len(times) == steps + 1 and times[0] == 0.0 and times[-1] == t_end
    argv = ["run", "--suite", "quick", "--engine", "reference", "--scenario", "four_bar", "--quiet"]
    assert main([*argv, "--out", str(tmp_path), "--repeats", "1", "--warmup", "0"]) == 0
    stored = read_trajectories(tmp_path)
    assert stored  # the truth's and the run's trajectories, each on the scenario's grid
    for trajectory in stored.values():
        np.testing.assert_array_equal(trajectory.times, times)
