"""`mbxval bench startup` and `bench threads`: a child's CPU time is read from the child itself
(wait4), its own work and its reaped children's, not from the clock on the wall; every case is put
beside one start-up measured in the same run; the BLAS benchmark's runs are real native runs."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from benchmarks import blas_threads, startup

BUSY = "import time\nend = time.process_time() + {0}\nwhile time.process_time() < end: pass"
FORKED = "import os, time\nif os.fork() == 0:\n    exec({0!r})\n    os._exit(0)\nos.wait()"


def test_a_childs_cpu_is_its_work_and_a_sleep_is_none() -> None:
    worked = startup.cost([sys.executable, "-c", BUSY.format(0.3)], {})
    slept = startup.cost([sys.executable, "-c", "import time; time.sleep(0.3)"], {})
    assert worked.cpu >= 0.3 and worked.wall >= 0.3
    assert slept.wall >= 0.3 and slept.cpu < 0.2  # the interpreter's start alone


def test_a_reaped_grandchild_counts() -> None:
    spent = startup.cost([sys.executable, "-c", FORKED.format(BUSY.format(0.3))], {})
    assert spent.cpu >= 0.3


def test_a_failing_command_is_said(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit, match="failed"):
        startup.cost([sys.executable, "-c", "raise SystemExit(3)"], {})


def test_each_case_is_put_beside_the_start_up_of_the_same_run(capsys: pytest.CaptureFixture[str]) -> None:
    best = startup.main(["--repeats", "1", "--case=--help"])
    cases = {case for case, _ in best}
    assert cases == {startup.NUMPY, "--help", startup.START_UP}
    printed = capsys.readouterr().out
    assert "OPENBLAS_NUM_THREADS=1" in printed and "/start-up" in printed and "load after" in printed
    for variant in startup.VARIANTS:
        assert best[(startup.NUMPY, variant)].cpu < best[(startup.START_UP, variant)].cpu


def test_the_blas_benchmark_times_a_real_native_run() -> None:
    _, chain, setting = blas_threads.cases(2)[-1]
    spent = blas_threads.spent(chain, setting)
    assert spent.cpu > 0 and spent.wall > 0


FIGURES = {
    (case, variant): startup.Cost(cpu, 10 * cpu, 50.0)
    for case, cpu in ((startup.NUMPY, 0.1), (startup.START_UP, 0.5), ("--help", 0.3))
    for variant in startup.VARIANTS
}


def test_the_table_puts_each_case_beside_the_start_up_and_numpy() -> None:
    table = startup.markdown(FIGURES, 3, ("1.00", "2.00"))
    assert "load average 1.00 before and 2.00 after; best of 3 by CPU" in table
    assert "| `mbxval --help` | 0.30 | 3 | 50 | 0.60 | 3.0 | 1.00 |" in table  # 0.3 / 0.5, 0.3 / 0.1


def test_the_page_is_written_between_its_markers_only(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(f"intro\n{startup.BEGIN}\nold table\n{startup.END}\noutro\n")
    startup.write_between_markers(page, "new table\n")
    assert page.read_text() == f"intro\n{startup.BEGIN}\nnew table\n{startup.END}\noutro\n"


def test_a_page_without_markers_is_refused_and_left_alone(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text("no markers\n")
    with pytest.raises(SystemExit, match="markers"):
        startup.write_between_markers(page, "new table\n")
    assert page.read_text() == "no markers\n"
