"""The compiled loops marched in chunks (so that a signal's handler runs between two calls) give
the answer of one call over the whole grid, bit for bit: the kinematic kernel stops at the same
event and index, and the compiled inverse dynamics gives the same forces and energies."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.compiled import chunks, path
from reference_solver.dynamics import inverse_dynamics


def _points_a_chunk(monkeypatch: pytest.MonkeyPatch, points: int, point_seconds: float) -> None:
    """Chunks of `points` grid points where one point is estimated at `point_seconds`."""
    monkeypatch.setattr(chunks, "CHUNK_SECONDS", points * point_seconds * (1 + 1e-9))


def _runs(monkeypatch: pytest.MonkeyPatch, name: str, steps: int, chunk_points: int) -> tuple:  # type: ignore[type-arg]
    scenario = scenarios.load(name)
    grid = np.asarray(scenario.times(steps=steps))
    whole = path.run(scenario, grid)
    n = path.compiled(scenario).program.n  # type: ignore[union-attr]
    _points_a_chunk(monkeypatch, chunk_points, chunks.banded_point_seconds(n))
    return whole, path.run(scenario, grid)


def test_chunks_cover_the_grid_in_order_with_the_size_asked(monkeypatch) -> None:
    _points_a_chunk(monkeypatch, 3, 0.01)
    assert list(chunks.chunks(7, 0.01)) == [(0, 3), (3, 6), (6, 7)]
    assert list(chunks.chunks(2, 1e3)) == [(0, 1), (1, 2)]  # a point costlier than a chunk: one each
    assert list(chunks.chunks(0, 0.01)) == []


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


@pytest.mark.parametrize("chunk_points", [1, 3])
@pytest.mark.parametrize("name", ["slider_crank", "four_bar_chain", "planetary_gears"])
def test_chunked_inverse_dynamics_gives_the_whole_grid_s_forces(
    monkeypatch, name: str, chunk_points: int
) -> None:
    scenario = scenarios.load(name)
    analysis = path.run(scenario, np.asarray(scenario.times(steps=20))).analysis
    assert analysis is not None
    whole = inverse_dynamics(scenario, analysis)
    rows = len(analysis.q[0])
    _points_a_chunk(monkeypatch, chunk_points, chunks.dense_point_seconds(rows))
    chunked = inverse_dynamics(scenario, analysis)
    assert whole.keys() == chunked.keys() and len(whole) > 2
    for key, values in whole.items():
        np.testing.assert_array_equal(chunked[key], values, err_msg=key)
