"""The drawings a run leaves beside its results: written and indexed per scenario (earlier runs'
kept), a scenario that cannot be drawn left out with a warning, read back for the report, shown as
an image (never as markup), and a bad index or a name reaching out of the folder ignored."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import scenarios
from reports.drawing.files import MAX_ANIMATION_BYTES, MAX_BODIES, REPORT_FRAMES, file_name, write_drawings
from reports.render.drawings import DRAWINGS, INDEX, read_drawings


def test_drawings_are_written_indexed_and_read_back(tmp_path: Path) -> None:
    four_bar, cam = scenarios.build("four_bar"), scenarios.build("cam_roller")
    write_drawings(tmp_path, [four_bar])
    index = write_drawings(tmp_path, [cam])  # a second run: the first one's drawing stays
    assert set(index) == {"four_bar", "cam_roller"}
    found = read_drawings(tmp_path)
    assert set(found) == {"four_bar", "cam_roller"}
    assert all(text.lstrip().startswith("<svg") for text in found.values())
    assert ">crank<" in found["four_bar"] or "crank" in found["four_bar"]


def test_a_small_cycle_is_animated_and_a_large_one_left_as_the_still(tmp_path: Path) -> None:
    """The four-bar's cycle in REPORT_FRAMES frames fits the page's budget; a cam's twelve redrawn
    profiles do not, so its drawing is the still at t = 0."""
    write_drawings(tmp_path, [scenarios.build("four_bar"), scenarios.build("cam_roller")])
    found = read_drawings(tmp_path)
    animated = found["four_bar"]
    assert animated.count('<g class="frame"') == REPORT_FRAMES
    assert animated.count("<animate ") == REPORT_FRAMES
    assert len(animated.encode()) <= MAX_ANIMATION_BYTES
    assert "four_bar: one cycle" in animated
    still = found["cam_roller"]
    assert still.count('<g class="frame"') == 1 and "<animate " not in still
    assert "<title>cam_roller at t = 0 s</title>" in still


def test_what_cannot_be_drawn_is_left_out_with_a_warning(tmp_path: Path) -> None:
    good = scenarios.build("slider_crank")
    broken = scenarios.build("four_bar", overrides={"coupler_length": 0.2, "rocker_length": 0.05})
    with pytest.warns(RuntimeWarning, match="not drawn"):  # the loop cannot close: no pose
        index = write_drawings(tmp_path, [broken, good])
    assert set(index) == {"slider_crank"}
    long_chain = scenarios.build("n_four_bar/spec")
    assert len(long_chain.bodies) > MAX_BODIES
    assert "n_four_bar/spec" not in write_drawings(tmp_path, [long_chain])


def test_a_bad_index_or_a_name_out_of_the_folder_reads_as_no_drawing(tmp_path: Path) -> None:
    folder = tmp_path / DRAWINGS
    folder.mkdir()
    (tmp_path / "secret.svg").write_text("<svg>outside</svg>")
    (folder / INDEX).write_text(json.dumps({"a": "../secret.svg", "b": "missing.svg"}))
    assert read_drawings(tmp_path) == {}
    (folder / INDEX).write_text("not json")
    assert read_drawings(tmp_path) == {}


def test_file_names_keep_scenarios_apart() -> None:
    assert file_name("a/b") != file_name("a_b")
    assert file_name("slider_crank[offset=0.05]").endswith(".svg")
    assert "/" not in file_name("../../x")
