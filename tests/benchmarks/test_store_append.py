"""`mbxval bench store`: one run prints, per store size, the old save and the new side by side with
their ratio, and the rows it stores are the store's declared columns."""

from __future__ import annotations

import pytest

from benchmarks.store_append import realistic_rows
from reports.cli.main import main
from reports.store.columns import COLUMNS
from reports.store.results_store import key_of


def test_the_rows_are_the_declared_columns_with_distinct_keys() -> None:
    rows = realistic_rows(50) + realistic_rows(50, start=50)
    assert all(tuple(r) == COLUMNS for r in rows)
    assert len({key_of(r) for r in rows}) == 100


def test_bench_store_prints_old_and_new_side_by_side(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(["bench", "store", "--sizes", "200,400", "--batch", "10", "--appends", "2", "--grow", "40"]) == 0
    )
    lines = capsys.readouterr().out.splitlines()
    header = "rows old best old med new best new med new worst old/new load sha256"
    assert lines[1].split() == header.split()
    table = [line.split() for line in lines[2:4]]
    assert [int(row[0]) for row in table] == [200, 400]
    assert all(float(value) > 0 for row in table for value in row[1:7])  # seconds and ratio
    assert all(float(value) >= 0 for row in table for value in row[7:])  # a load: 0.000 s at 200 rows
    assert lines[4].startswith("a sweep of 40 rows saved every 10 (4 saves): old ")
