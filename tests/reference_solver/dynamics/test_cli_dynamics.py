"""`mbxval solve` on the dynamic scenarios: the canonical columns, then reactions, driver forces,
energy terms and scenario angles; bad input fails like everywhere else (one line, exit 2, no file)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from reports.cli.main import main


def run(capsys, *argv: str) -> tuple[int, str, str]:  # type: ignore[no-untyped-def]
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_writes_reactions_and_energy_columns(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, err = run(capsys, "solve", "compound_pendulum", "--t-end", "0.2", "--steps", "4")
    assert code == 0 and err == ""
    frame = pd.read_csv(io.StringIO(out))
    assert len(frame) == 5
    assert list(frame.columns[:10]) == ["t"] + [
        f"link_1.{c}" for c in ("x", "y", "theta", "vx", "vy", "omega", "ax", "ay", "alpha")
    ]
    for column in ("pin_1.fx", "pin_2.fy", "energy.kinetic", "energy.potential", "energy.balance"):
        assert column in frame.columns
    assert np.max(np.abs(frame["energy.balance"])) < 1e-10


def test_solve_andrews_writes_the_seven_angles(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "andrews.csv"
    code, out, _ = run(
        capsys, "solve", "andrews_squeezer", "--t-end", "0.002", "--steps", "2", "--out", str(target)
    )
    assert code == 0 and out == ""
    frame = pd.read_csv(target)
    angles = ["beta", "theta", "gamma", "phi", "delta", "omega", "epsilon"]
    assert [c for c in frame.columns if c.startswith("andrews.")] == [f"andrews.{a}" for a in angles]
    assert frame["andrews.beta"].iloc[0] == pytest.approx(-0.0617138900142764496358948458001, abs=1e-15)


def test_solve_with_radau_and_inverse_dynamics_columns(capsys) -> None:  # type: ignore[no-untyped-def]
    solved = {}
    for mode in ("Radau", "DOP853"):
        code, out, _ = run(capsys, "solve", "stiff_spring", "--set", "t_end=0.002", "--mode", mode)
        assert code == 0
        solved[mode] = pd.read_csv(io.StringIO(out))["link_1.theta"].to_numpy()
    np.testing.assert_allclose(solved["Radau"], solved["DOP853"], rtol=0, atol=1e-9)
    code, out, _ = run(capsys, "solve", "four_bar", "--steps", "40", "--setting", "inverse_dynamics=1")
    assert code == 0
    assert {"crank_drive.force", "O2.fx", "B.fy"} <= set(pd.read_csv(io.StringIO(out)).columns)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["andrews_squeezer", "--set", "spring_stiffness=-1"], "spring_stiffness must be a number in (0"),
        (["compound_pendulum", "--set", "links=0"], "links must be an integer in [1"),
        (["stiff_spring", "--set", "dt=0"], "dt must be a number in (0"),
        (["andrews_squeezer", "--mode", "RK4"], "unknown mode 'RK4'"),
        (
            ["andrews_squeezer", "--engine", "mujoco", "--mode", "kinematic"],
            "not a MuJoCo integrator of free dynamics",
        ),
        (["four_bar_gravity", "--setting", "rtol=-1"], "option rtol must be a float in (0"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_no_file(
    tmp_path: Path, capsys, argv: list[str], message: str
) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "out.csv"
    code, out, err = run(capsys, "solve", *argv, "--out", str(target))
    assert code == 2 and out == ""
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1 and message in err
    assert not target.exists()
