"""Issue 27: a store that appends. A save writes its batch as a new part and lists the older parts
unchanged (the same files: inode and mtime); a load gives the table a single file gave (columns,
dtypes, row order), the newest entry of a key winning; a part the sidecar does not list is never
read and a repair moves it aside; a torn or altered part is refused in one line naming it; a store
written by the mbxval before parts loads, and its first save converts it, keeping its generation."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from benchmarks.store_append import realistic_rows
from reports.cli.main import main
from reports.store import files as store_files
from reports.store.files import GENERATIONS, StoreDamaged
from reports.store.lock import StoreBusy, WriterLock
from reports.store.repair import Repair
from reports.store.results_store import (
    RESULTS,
    TRAJECTORIES,
    ResultsStore,
    key_of,
    read_results,
    rows_frame,
)
from scenarios.trajectory import Trajectory
from tests.support.store_runs import one_line_error, rows
from tests.support.stores import table_files, write_schema_1

META = {"suite": "test"}


def single_file_frame(table: dict, tmp: Path) -> pd.DataFrame:
    """The table as the mbxval before parts stored and read it: one file, read back whole."""
    rows_frame(table.values()).to_parquet(tmp, index=False)
    from reports.store.columns import COLUMNS

    frame = pd.read_parquet(tmp)
    return frame[[c for c in COLUMNS if c in frame.columns]]


def trajectory(seed: int) -> Trajectory:
    generator = np.random.default_rng(seed)
    times = np.linspace(0.0, 1.0, 11)
    return Trajectory(
        times, ("crank", "rod"), generator.normal(size=(11, 2, 3)), generator.normal(size=(11, 2, 3))
    )


@pytest.fixture()
def store(tmp_path: Path) -> ResultsStore:
    made = ResultsStore(tmp_path / "out")
    for index, row in enumerate(realistic_rows(300)):
        made.add(row, trajectory(index) if index % 50 == 0 else None)
    made.put_truth(str(made.rows[min(made.rows)]["scenario"]), "closed form", trajectory(1000))
    made.save(dict(META))
    return made


def same_rows(a: dict, b: dict) -> bool:
    """The same rows (NaN equal to NaN, as in a table)."""
    return set(a) == set(b) and rows_frame(a.values()).equals(rows_frame(b.values()))


def parts(directory: Path, table: str = RESULTS) -> dict[str, os.stat_result]:
    return {p.name: p.stat() for p in table_files(directory / "current", table)}


def test_an_append_writes_one_part_and_leaves_the_others_untouched(store: ResultsStore) -> None:
    out = store.directory
    before = parts(out)
    for row in realistic_rows(5, start=300):
        store.add(row)
    store.save(dict(META))
    after = parts(out)
    assert len(after) == len(before) + 1
    for name, stat in before.items():  # the same file: linked, not rewritten, not even touched
        assert (after[name].st_ino, after[name].st_mtime_ns) == (stat.st_ino, stat.st_mtime_ns)
    (new,) = set(after) - set(before)
    assert len(pd.read_parquet(out / "current" / RESULTS / new)) == 5
    assert len(read_results(out)[0]) == 305


def test_a_load_gives_the_table_a_single_file_gave(store: ResultsStore, tmp_path: Path) -> None:
    """Appends, a replaced row, an edited row, a deleted row: the parts resolve to the table held,
    with the dtypes and row order of the single file the mbxval before parts wrote."""
    for k in range(3):
        for row in realistic_rows(40, start=300 + 40 * k):
            store.add(row)
        store.save(dict(META))
    keys = sorted(store.rows)
    store.add({**store.rows[keys[0]], "status": "failed", "error": float("nan")})  # a rerun
    store.rows[keys[1]]["stale"] = True  # an edit in place (a resume keeping a stale row)
    del store.rows[keys[2]]  # a reconcile dropping a row
    store.save(dict(META))
    frame, _ = read_results(store.directory)
    expected = single_file_frame(store.rows, tmp_path / "single.parquet")
    pd.testing.assert_frame_equal(frame, expected, check_dtype=True)
    assert keys[2] not in {key_of(r) for r in frame.to_dict("records")}
    assert same_rows(ResultsStore(store.directory).rows, store.rows)


def test_the_results_folder_reads_as_one_dataset_once_compacted(store: ResultsStore) -> None:
    for k in range(6):
        for row in realistic_rows(20, start=300 + 20 * k):
            store.add(row)
        store.save(dict(META))
    direct = pd.read_parquet(store.directory / RESULTS)  # every part, as pandas reads a folder
    assert len(direct) == len(store.rows) and not direct.duplicated(["scenario", "engine", "setting"]).any()


def test_a_clean_save_leaves_no_replaced_or_deleted_row_for_a_direct_read(store: ResultsStore) -> None:
    """A run's last save is clean: after a rerun of one row and the deletion of another, pandas
    reading the folder directly sees the store's rows, each once, without the old entries."""
    keys = sorted(store.rows)
    store.save(dict(META))
    store.add({**store.rows[keys[0]], "status": "failed"})  # a rerun: the old entry stays in its part
    del store.rows[keys[1]]
    store.save(dict(META))
    assert len(pd.read_parquet(store.directory / RESULTS)) > len(store.rows)  # a plain save appends
    store.save(dict(META), clean=True)
    direct = pd.read_parquet(store.directory / RESULTS)
    assert len(direct) == len(store.rows) == len(keys) - 1
    assert not direct.duplicated(["scenario", "engine", "setting"]).any()
    assert direct.set_index(["scenario", "engine", "setting"]).loc[keys[0], "status"] == "failed"


def test_a_part_the_sidecar_does_not_list_is_ignored_and_moved_aside_by_repair(
    store: ResultsStore, capsys: pytest.CaptureFixture[str]
) -> None:
    out = store.directory
    before = rows(out)
    folder = (out / "current" / RESULTS).resolve()
    stray = folder / "part-999999.parquet"  # as a save stopped between its part and its sidecar
    pd.DataFrame(realistic_rows(3, start=5000)).to_parquet(stray, index=False)
    assert rows(out).equals(before)  # never read
    assert main(["store", "repair", str(out)]) == 0
    said = capsys.readouterr().out
    assert "part-999999.parquet is not listed" in said and "moved aside" in said
    assert not stray.exists() and rows(out).equals(before)
    assert list((out / GENERATIONS).glob("quarantine-*part-999999*"))


def test_a_save_stopped_before_its_sidecar_commits_nothing(store: ResultsStore) -> None:
    """Killed after writing its part, before its sidecar: the old generation stays committed, the
    part is never read, and the next save removes what was left."""
    out = store.directory
    before = rows(out)
    pid = os.fork()
    if pid == 0:
        real = Path.write_text

        def die(self: Path, *args: object, **kwargs: object) -> int:
            if self.name == "results.json":
                os._exit(9)
            return real(self, *args, **kwargs)  # type: ignore[arg-type]

        Path.write_text = die  # type: ignore[assignment,method-assign]
        try:
            for row in realistic_rows(5, start=300):
                store.add(row)
            store.save(dict(META))
        finally:
            os._exit(0)
    _, status = os.waitpid(pid, 0)
    assert os.WEXITSTATUS(status) == 9
    left = list((out / GENERATIONS).glob("tmp-*/results.parquet/part-*.parquet"))
    assert left  # the part written, in a generation never committed
    assert rows(out).equals(before)
    ResultsStore(out).save(dict(META))
    assert not list((out / GENERATIONS).glob("tmp-*")) and rows(out).equals(before)


def test_a_torn_part_is_refused_in_one_line_naming_it_and_repair_goes_back(
    store: ResultsStore, capsys: pytest.CaptureFixture[str]
) -> None:
    out = store.directory
    before = rows(out)
    for row in realistic_rows(5, start=300):
        store.add(row)
    store.save(dict(META))
    newest = max(parts(out))
    torn = out / "current" / RESULTS / newest
    torn.write_bytes(torn.read_bytes()[: torn.stat().st_size // 2])  # only the newest lists it
    assert main(["report", str(out)]) == 2
    one_line_error(capsys, f"{RESULTS}/{newest}", "store repair")
    assert main(["store", "repair", str(out)]) == 0
    assert "does not verify" in capsys.readouterr().out
    assert rows(out).equals(before)  # the generation before the torn save


def test_an_altered_part_is_refused_in_one_line_naming_it(
    store: ResultsStore, capsys: pytest.CaptureFixture[str]
) -> None:
    part = table_files(store.directory / "current", RESULTS)[0]
    data = bytearray(part.read_bytes())
    data[len(data) // 2] ^= 0x10  # same size, other bytes
    part.write_bytes(bytes(data))
    with pytest.raises(StoreDamaged, match=f"{RESULTS}/{part.name} does not match its checksum"):
        ResultsStore(store.directory)
    assert main(["report", str(store.directory)]) == 2
    one_line_error(capsys, f"{RESULTS}/{part.name} does not match its checksum")


def test_a_second_writer_is_refused_and_the_parts_stay(store: ResultsStore) -> None:
    out = store.directory
    before = parts(out)
    with WriterLock(out), pytest.raises(StoreBusy, match="is being written by process"):
        WriterLock(out).__enter__()
    assert parts(out) == before


def test_a_store_from_before_parts_loads_and_its_first_save_converts_it(
    store: ResultsStore, tmp_path: Path
) -> None:
    old = write_schema_1(tmp_path / "old", store.directory)
    single = old / GENERATIONS / "g000001" / RESULTS
    assert single.is_file()
    expected = single_file_frame(store.rows, tmp_path / "single.parquet")
    pd.testing.assert_frame_equal(read_results(old)[0], expected, check_dtype=True)
    loaded = ResultsStore(old)
    assert same_rows(loaded.rows, store.rows) and set(loaded.trajectories) == set(store.trajectories)
    for row in realistic_rows(5, start=300):
        loaded.add(row)
    loaded.save(dict(loaded.meta))
    assert (old / RESULTS).is_symlink() and (old / "current" / RESULTS).is_dir()
    assert len(read_results(old)[0]) == 305 and same_rows(ResultsStore(old).rows, loaded.rows)
    assert single.is_file() and len(pd.read_parquet(single)) == 300  # kept, a generation to go back to


def test_lost_trajectory_parts_are_lost_trajectories_not_damage(store: ResultsStore) -> None:
    out = store.directory
    shutil.rmtree((out / "current" / TRAJECTORIES).resolve())
    loaded = ResultsStore(out)
    assert loaded.lost_trajectories and len(loaded.rows) == 300 and not loaded.trajectories
    key = min(loaded.rows)
    loaded.add(dict(loaded.rows[key]), trajectory(7))  # a resume rebuilds what the report draws
    loaded.save(dict(loaded.meta))
    again = ResultsStore(out)
    assert not again.lost_trajectories and set(again.trajectories) == {key}
    assert np.array_equal(again.trajectories[key].position, trajectory(7).position)


def test_every_part_is_a_hard_link_shared_by_the_generations(store: ResultsStore) -> None:
    out = store.directory
    store.save(dict(META))
    names = sorted(p.name for p in (out / GENERATIONS).iterdir())
    first, second = (table_files(out / GENERATIONS / n, RESULTS) for n in names[-2:])
    assert [p.stat().st_ino for p in first] == [p.stat().st_ino for p in second]
    assert store_files.KEEP == 3
    assert Repair(out).run()[-1].startswith("nothing to repair")


def test_trajectories_of_differing_columns_read_back_as_written(tmp_path: Path) -> None:
    """One part holds trajectories with and without accelerations and extras (a truth's forces
    beside an engine's bare positions): each reads back with its own columns and values."""
    generator = np.random.default_rng(7)
    times = np.linspace(0.0, 1.0, 5)
    full = Trajectory(
        times, ("crank",), *(generator.normal(size=(5, 1, 3)) for _ in range(3)),
        extras={"crank_drive.torque": generator.normal(size=5)},
    )  # fmt: skip
    bare = Trajectory(np.linspace(0.0, 2.0, 7), ("crank", "rod"), generator.normal(size=(7, 2, 3)))
    made = ResultsStore(tmp_path / "out")
    made.put_truth("four_bar", "closed form", full)
    made.put_truth("slider_crank", "closed form", bare)
    made.save(dict(META))
    again = ResultsStore(tmp_path / "out").trajectories
    for key, written in (("four_bar", full), ("slider_crank", bare)):
        (read,) = [t for k, t in again.items() if k[0] == key]
        assert read.bodies == written.bodies and set(read.extras) == set(written.extras)
        for name, values in written.columns().items():
            np.testing.assert_array_equal(read.columns()[name], values)
        assert read.acceleration is None if written.acceleration is None else read.acceleration is not None
