"""Work bounded in time as well as in memory: a problem whose estimated work (scenarios.limits) is
above the limit is refused in one line before any work, and a long solve ends within a couple of
seconds of a SIGTERM or Ctrl-C, with no output file."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

import scenarios
from reference_solver import analyse
from reference_solver.dynamics import inverse_dynamics
from reports.cli.main import main
from scenarios import limits

ROOT = Path(__file__).resolve().parents[3]


def refused(capsys: pytest.CaptureFixture[str], argv: list[str], words: str) -> None:
    started = time.process_time()
    assert main(argv) == 2
    assert time.process_time() - started < 5  # before any work
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err[:300]
    assert words in err, err[:300]


def test_a_grid_of_more_work_than_the_limit_is_refused_naming_it(capsys, tmp_path: Path) -> None:
    out = tmp_path / "big.csv"
    limit = f"above the limit of {limits.MAX_WORK_SECONDS:g} s"
    refused(capsys, ["solve", "slider_crank", "--steps", "2000000", "--out", str(out)], limit)
    refused(capsys, ["solve", "four_bar_chain", "--set", "loops=1000", "--steps", "2000"], limit)
    assert not out.exists()


def test_the_refusal_names_the_most_steps_admitted(capsys) -> None:
    bodies = len(scenarios.build("slider_crank").bodies)
    most = int(limits.MAX_WORK_SECONDS / limits.work_seconds(1, bodies, dense=False)) - 1
    refused(capsys, ["solve", "slider_crank", "--steps", str(most + 2)], f"use at most {most} steps")
    limits.check_grid("slider_crank", most + 1, bodies)  # the number named is admitted


def test_dense_work_on_a_long_chain_is_refused_and_the_kinematic_solve_admitted(
    capsys, tmp_path: Path
) -> None:
    """A 2001-body chain: the reference kinematics is banded and admitted; an engine, a run (the
    native forces) and free dynamics solve densely and are refused up front."""
    words = f"above the limit of {limits.MAX_DENSE_ROWS} rows"
    chain = ["four_bar_chain", "--set", "loops=1000"]
    refused(capsys, ["solve", *chain, "--engine", "mujoco"], words)
    out = tmp_path / "o"
    refused(
        capsys, ["run", "--scenario", chain[0], *chain[1:], "--engine", "reference", "--out", str(out)], words
    )
    assert not out.exists()
    limits.check_grid("four_bar_chain", 201, 2001, dense=False)


def test_the_costs_per_row_step_bound_what_they_estimate() -> None:
    """The measured costs the estimate uses are not below what the solves cost here: the banded
    kinematic loop on a 201-body chain and the dense inverse dynamics on a 101-body one (process
    CPU time on one BLAS thread, as the runner solves), within a factor 3."""
    with threadpool_limits(limits=1):
        _costs_within_their_estimates()


def _costs_within_their_estimates() -> None:
    chain = scenarios.build("four_bar_chain", overrides={"loops": 100})
    grid = np.asarray(chain.times(steps=400))
    analyse(chain, grid[:3])  # compiled and cached
    started = time.process_time()
    analyse(chain, grid)
    spent = time.process_time() - started
    assert spent < 3 * limits.work_seconds(grid.size, len(chain.bodies), dense=False)
    chain = scenarios.build("four_bar_chain", overrides={"loops": 50})
    few = analyse(chain, np.asarray(chain.times(steps=4)))
    inverse_dynamics(chain, analyse(chain, few.times[:2]))  # its Jacobian compiled
    started = time.process_time()
    inverse_dynamics(chain, few)
    spent = time.process_time() - started
    assert spent < 3 * limits.work_seconds(few.times.size, len(chain.bodies), dense=True)


def _cpu_seconds(pid: int) -> float:
    """The CPU time a running process has used (Linux's /proc: its user and system ticks)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _default_interrupt() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _most_steps(name: str, overrides: dict[str, int], share: float) -> int:
    """The steps of `share` of the largest kinematic solve of `name` admitted (scenarios.limits)."""
    bodies = len(scenarios.build(name, overrides=overrides).bodies)
    return int(share * limits.MAX_WORK_SECONDS / limits.work_seconds(1, bodies, dense=False)) - 1


LATE_CPU = 1.0
"""CPU seconds the command may spend after the signal: its compiled loops return between chunks of
about 0.1 s (reference_solver.compiled.chunks), its CSV is written in blocks, and the process ends
without the interpreter's teardown (stop.end); a few hundredths of a second are measured."""
LATE_WALL = 5.0
"""Wall seconds it may take, for a machine shared by a whole test suite (under a second measured
beside a load of 14 on 2 cores): the CPU bound is the test's measure, this one only its backstop."""

LONG_SOLVES = [
    # the half-minute slider-crank: its dense inverse dynamics by 6 CPU seconds, its CSV by 12
    ("slider_crank", {}, 0.5, signal.SIGTERM, 143, 6.0),
    ("slider_crank", {}, 0.5, signal.SIGINT, 130, 12.0),
    # the longest chain a kinematic solve admits, at its most steps: the banded loop by 6 s
    ("four_bar_chain", {"loops": 1000}, 1.0, signal.SIGTERM, 143, 6.0),
]


@pytest.mark.slow
@pytest.mark.parametrize(("name", "overrides", "share", "sent", "status", "after"), LONG_SOLVES)
def test_a_long_solve_ends_soon_after_a_signal(
    tmp_path: Path, name: str, overrides: dict[str, int], share: float, sent: int, status: int, after: float
) -> None:
    """A long admitted solve, signalled `after` CPU seconds in: it ends within LATE_CPU seconds of
    its own CPU time (and LATE_WALL of wall time) with the documented status, one line, and no
    output file."""
    out = tmp_path / "long.csv"
    steps = _most_steps(name, overrides, share)
    command = [sys.executable, "-m", "reports.cli", "solve", name, "--steps", str(steps)]
    command += [f"--set={key}={value}" for key, value in overrides.items()]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen(
        [*command, "--out", str(out)],
        env=env,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_default_interrupt,  # as from a terminal, even where this test's SIGINT is ignored
    )
    while _cpu_seconds(process.pid) < after:  # past its imports, well into the solve
        assert process.poll() is None, process.stderr.read() if process.stderr else ""
        time.sleep(0.05)
    spent = _cpu_seconds(process.pid)
    process.send_signal(sent)
    signalled = time.monotonic()
    try:
        _, waited, usage = os.wait4(process.pid, 0)
    finally:
        process.kill()
    late_wall = time.monotonic() - signalled
    late_cpu = usage.ru_utime + usage.ru_stime - spent
    process.returncode = os.waitstatus_to_exitcode(waited)
    err = process.stderr.read() if process.stderr else ""
    assert process.returncode == status and err.count("\n") == 1, err
    assert late_cpu < LATE_CPU, f"{late_cpu:.2f} CPU s after the signal"
    assert late_wall < LATE_WALL, f"{late_wall:.1f} s after the signal"
    assert not out.exists() and not list(tmp_path.iterdir())


def test_a_stopped_command_ends_without_the_interpreter_s_teardown(tmp_path: Path) -> None:
    """After a Ctrl-C the command line's exit handlers run and its output is flushed, then the
    process ends at once (stop.end): a module's finalizer, which teardown would run, never does."""
    code = (
        "import atexit, sys, signal, os\n"
        "class Finalized:\n"
        "    def __del__(self):\n"
        "        os.write(2, b'teardown\\n')\n"
        "sys.modules['__main__'].kept = Finalized()\n"
        "atexit.register(lambda: print('exit handler', flush=True))\n"
        "print('flushed at exit', end='')\n"
        "from reports.run.stop import end\n"
        "end(130)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert (done.returncode, done.stdout, done.stderr) == (130, "flushed at exitexit handler\n", "")


def test_compare_refuses_dense_work_before_its_truth(capsys, tmp_path: Path) -> None:
    """A trajectory of a 2001-body chain, solved kinematically (admitted): scoring it needs the
    native forces, a dense solve of 6003 rows a grid point, refused before any."""
    csv = tmp_path / "chain.csv"
    chain = ["four_bar_chain", "--set", "loops=1000"]
    assert main(["solve", *chain, "--out", str(csv)]) == 0
    capsys.readouterr()
    refused(capsys, ["compare", *chain, str(csv)], f"above the limit of {limits.MAX_DENSE_ROWS} rows")


def test_a_long_chain_the_compiled_path_cannot_do_is_not_handed_to_the_dense_plain_path(capsys) -> None:
    """Two steps over a 2001-body chain's swing are too long for the compiled loop; the plain path
    it would hand them to factors 6003 rows densely (minutes in one uninterruptible call): refused."""
    started = time.process_time()
    assert main(["solve", "four_bar_chain", "--set", "loops=1000", "--steps", "2"]) == 2
    assert time.process_time() - started < 20
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"above the limit of {limits.MAX_DENSE_ROWS}" in err, err


def test_inverse_dynamics_is_left_out_where_its_dense_solves_are_not_admitted(capsys) -> None:
    """The native solve's forces are a dense least-squares solve a grid point: on a chain past
    MAX_DENSE_ROWS rows the default solves the motion alone, and asking for the forces there, or
    on a grid whose dense work is above the limit, is refused before the analysis, naming it."""
    from adapters.reference import ReferenceAdapter

    adapter = ReferenceAdapter()
    rows_admitted = limits.MAX_DENSE_ROWS // 3
    small = scenarios.build("four_bar_chain", overrides={"loops": (rows_admitted - 1) // 2})
    large = scenarios.build("four_bar_chain", overrides={"loops": (rows_admitted + 1) // 2})
    assert 3 * len(small.bodies) <= limits.MAX_DENSE_ROWS < 3 * len(large.bodies)
    assert adapter.default_setting(small).get("inverse_dynamics") == 1
    assert adapter.default_setting(large).get("inverse_dynamics") is None
    chain = ["four_bar_chain", "--set", f"loops={(rows_admitted + 1) // 2}", "--steps", "4"]
    refused(capsys, ["solve", *chain, "--setting", "inverse_dynamics=1"], f"{limits.MAX_DENSE_ROWS} rows")
    most = int(limits.MAX_WORK_SECONDS / limits.work_seconds(1, len(small.bodies), dense=True))
    loops = f"loops={(rows_admitted - 1) // 2}"
    refused(
        capsys, ["solve", "four_bar_chain", "--set", loops, "--steps", str(most + 1)], "inverse_dynamics=0"
    )
