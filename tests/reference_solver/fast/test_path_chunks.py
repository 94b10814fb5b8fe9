"""The compiled loop marched in chunks (so that a signal's handler runs between two calls) gives
the answer of one call over the whole grid, bit for bit, and stops at the same event and index."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.fast import path


def _runs(monkeypatch: pytest.MonkeyPatch, name: str, steps: int, chunk_points: int) -> tuple:  # type: ignore[type-arg]
    scenario = scenarios.load(name)
    grid = np.asarray(scenario.times(steps=steps))
    whole = path.run(scenario, grid)
    n = path.compiled(scenario).program.n  # type: ignore[union-attr]
    monkeypatch.setattr(path, "CHUNK_ROW_STEPS", chunk_points * n)
    return whole, path.run(scenario, grid)


@pytest.mark.parametrize("chunk_points", [1, 2, 7])
@pytest.mark.parametrize("name", ["slider_crank", "four_bar_chain", "cam_roller/spline"])
def test_chunks_give_the_whole_grid_s_answer(monkeypatch, name: str, chunk_points: int) -> None:
    whole, chunked = _runs(monkeypatch, name, 40, chunk_points)
    assert whole.event == chunked.event == "ok"
    for level in ("q", "qd", "qdd", "iterations", "residual", "rcond"):
        np.testing.assert_array_equal(getattr(chunked.analysis, level), getattr(whole.analysis, level))


@pytest.mark.parametrize("name", ["four_bar/stress_toggle", "four_bar/stress_change_point"])
def test_an_event_in_a_later_chunk_is_found_where_one_call_finds_it(monkeypatch, name: str) -> None:
    """The determinant's sign and the rates are carried from one chunk to the next: a four-bar
    driven into its toggle or change point stops at the same event and index either way."""
    whole, chunked = _runs(monkeypatch, name, 400, 1)
    assert whole.event != "ok" and 1 < whole.index < 400, (whole.event, whole.index)
    assert (chunked.event, chunked.index) == (whole.event, whole.index)
