"""Results stores edited as the store itself commits them, for tests of what reads them."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path

import pandas as pd

from reports.harness.results_store import ResultsStore, key_of, read_results


def doctor(source: Path, target: Path, edit: Callable[[pd.DataFrame], None]) -> Path:
    """A copy of the results with rows edited and committed as the store commits them (an edit of
    the file alone is refused as damage: see tests/reports/test_reliability.py)."""
    shutil.copytree(source, target, symlinks=True)
    store = ResultsStore(target)
    frame, _ = read_results(target)
    edit(frame)
    store.rows = {key_of(r): r for r in frame.to_dict("records")}
    store.save(store.meta)
    return target
