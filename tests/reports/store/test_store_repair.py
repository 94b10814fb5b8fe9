"""Issue 22: the store never deletes what it cannot account for. A missing or odd `current`, a
copy made with `cp -rL`, or a generation its sidecar does not account for is refused in one line
naming `mbxval store repair DIR`, with every generation left in place; the repair keeps every
generation that verifies and gives back the rows stored before; a save keeps the newest three."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from reports.cli.main import main
from reports.store import files as store_files
from reports.store.files import GENERATIONS, KEEP, StoreDamaged
from reports.store.results_store import RESULTS, ResultsStore
from tests.support.store_runs import copy, fake_run, one_line_error, rows, stored_run
from tests.support.stores import copy_entry, table_files


@pytest.fixture(scope="module")
def saved_often(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A store saved more often than KEEP (the fake run saves once per scenario-engine group, and
    each save here adds one generation)."""
    directory = stored_run(tmp_path_factory, "often")
    store = ResultsStore(directory)
    for _ in range(KEEP + 1):
        store.save(dict(store.meta))
    return directory


def generations(directory: Path) -> list[str]:
    return sorted(p.name for p in (directory / GENERATIONS).iterdir())


def break_current(directory: Path, how: str) -> None:
    link = directory / "current"
    link.unlink()
    if how == "regular file":
        link.write_text("not a link\n")
    elif how == "dangling":
        link.symlink_to(Path(GENERATIONS) / "g999999")
    elif how == "outside":
        link.symlink_to(Path("..") / "elsewhere")
    elif how == "directory":
        link.mkdir()


BROKEN = ["missing", "regular file", "dangling", "outside", "directory"]


@pytest.mark.parametrize("how", BROKEN)
def test_an_odd_current_is_refused_then_repaired_without_losing_a_row(
    saved_often: Path, tmp_path: Path, how: str, capsys: pytest.CaptureFixture[str]
) -> None:
    out = copy(saved_often, tmp_path / "out")
    before, kept = rows(out), generations(out)
    break_current(out, how)
    assert main(["report", str(out), "--out", str(tmp_path / "page")]) == 2
    one_line_error(capsys, "not in a state mbxval understands", f"mbxval store repair {out}")
    with pytest.raises(StoreDamaged, match="store repair"):
        ResultsStore(out, fresh=True).save({})  # a save (and its collection) never starts
    assert generations(out) == kept
    assert main(["store", "repair", str(out)]) == 0
    said = capsys.readouterr().out.splitlines()
    assert 1 <= len(said) <= 4 and said[-1].startswith(f"{out}: current -> {kept[-1]}"), said
    assert rows(out).equals(before)
    assert [g for g in generations(out) if g.startswith("g")] == kept  # nothing deleted
    assert (out / "current").is_symlink() and (out / RESULTS).is_symlink()


def test_a_regular_file_current_is_moved_aside_not_deleted(saved_often: Path, tmp_path: Path) -> None:
    out = copy(saved_often, tmp_path / "out")
    break_current(out, "regular file")
    assert main(["store", "repair", str(out)]) == 0
    aside = [p for p in (out / GENERATIONS).iterdir() if p.name.startswith("quarantine-current")]
    assert [p.read_text() for p in aside] == ["not a link\n"]


def test_a_copy_made_with_cp_rL_is_refused_then_adopted(saved_often: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "copy"
    subprocess.run(["cp", "-rL", str(saved_often), str(out)], check=True)
    assert (out / "current").is_dir() and not (out / "current").is_symlink()
    before = rows(saved_often)
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, "current is a directory, not a link", "cp -rL", "store repair")
    assert main(["store", "repair", str(out)]) == 0
    assert "same checksums" in capsys.readouterr().out
    assert rows(out).equals(before)
    ResultsStore(out).save({})  # and it saves again


def test_copied_files_that_are_a_newer_generation_are_adopted(saved_often: Path, tmp_path: Path) -> None:
    """A store whose directory holds plain files newer than any generation (the links followed by
    a copy, the generations lost): they verify, so they become the newest generation."""
    out = copy(saved_often, tmp_path / "out")
    before = rows(out)
    newest = out / GENERATIONS / generations(out)[-1]
    for name in ("results.parquet", "results.json", "trajectories.parquet"):
        (out / name).unlink()
        copy_entry(newest / name, out / name)
    shutil.rmtree(newest)
    (out / "current").unlink()
    assert main(["store", "repair", str(out)]) == 0
    assert rows(out).equals(before)


def test_a_generation_that_does_not_verify_is_moved_aside_and_the_newest_good_one_used(
    saved_often: Path, tmp_path: Path, capsys
) -> None:
    out = copy(saved_often, tmp_path / "out")
    good = generations(out)
    newest = table_files(out / GENERATIONS / good[-1], RESULTS)[-1]
    newest.unlink()  # a part shared with the older generations by a hard link: truncate a copy
    newest.write_bytes((out / GENERATIONS / good[-2] / RESULTS / newest.name).read_bytes()[:-10])
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, f"generation {good[-1]}", "store repair")
    (out / "current").unlink()
    assert main(["store", "repair", str(out)]) == 0
    said = capsys.readouterr().out
    assert f"generation {good[-1]} does not verify" in said and "not deleted" in said
    assert os.readlink(out / "current") == f"{GENERATIONS}/{good[-2]}"
    aside = [p.name for p in (out / GENERATIONS).iterdir() if p.name.startswith("quarantine-")]
    assert aside and aside[0].startswith(f"quarantine-{good[-1]}")
    assert len(rows(out)) > 0


def test_repair_with_nothing_that_verifies_deletes_nothing(saved_often: Path, tmp_path: Path, capsys) -> None:
    out = copy(saved_often, tmp_path / "out")
    for name in generations(out):
        for part in table_files(out / GENERATIONS / name, RESULTS):
            part.write_bytes(b"PAR1")
    assert main(["store", "repair", str(out)]) == 2
    one_line_error(capsys, "no generation", "verifies", "nothing was deleted")
    assert len([p for p in (out / GENERATIONS).iterdir() if p.name.startswith("quarantine-")]) == KEEP


def test_a_save_keeps_the_newest_generations_not_all_nor_one(saved_often: Path, tmp_path: Path) -> None:
    out = copy(saved_often, tmp_path / "out")
    store = ResultsStore(out)
    for _ in range(2):
        store.save({})
    names = generations(out)
    assert len(names) == KEEP and os.readlink(out / "current") == f"{GENERATIONS}/{names[-1]}"


def test_a_healthy_store_needs_no_repair(saved_often: Path, tmp_path: Path, capsys) -> None:
    out = copy(saved_often, tmp_path / "out")
    before = generations(out)
    assert main(["store", "repair", str(out)]) == 0
    assert capsys.readouterr().out.startswith(f"{out}: nothing to repair: current -> {before[-1]}")
    assert generations(out) == before


def test_a_first_save_stopped_before_its_switch_is_read(tmp_path: Path) -> None:
    """Killed between the rename of its generation and the switch of `current`: the one complete
    generation is the store (nothing to refuse, nothing lost)."""
    out = tmp_path / "out"
    pid = os.fork()
    if pid == 0:  # the child dies where the first save would switch `current`
        store_files.switch = lambda root, generation: os._exit(9)  # type: ignore[assignment]
        try:
            fake_run(out)
        finally:
            os._exit(0)
    _, status = os.waitpid(pid, 0)
    assert os.WEXITSTATUS(status) == 9 and generations(out) == ["g000001"]
    assert not (out / "current").exists()
    assert store_files.committed(out) == out / GENERATIONS / "g000001"
    assert len(ResultsStore(out).rows) > 0


def test_repair_of_a_folder_without_a_store_changes_nothing(tmp_path: Path, capsys) -> None:
    (tmp_path / "notes.txt").write_text("mine\n")
    assert main(["store", "repair", str(tmp_path)]) == 2
    one_line_error(capsys, "no results store at")
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]
