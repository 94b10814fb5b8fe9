"""The mechanism drawing (reports.drawing.drawing): every family and every example file
draws at t = 0 and at mid-horizon as well-formed SVG with every body and joint labelled, and each
revolute joint is drawn where the native solver puts it.

The check of positions is independent of the drawing code: the test solves the scenario through the
public API (`mbxval.solve`, the command line's path), places each joint with
`scenarios.geometry.world_point`, and maps the drawn circle back to metres with the transform the
SVG declares on its root.
"""

from __future__ import annotations

import copy
import glob
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import mbxval
from reports.drawing import svg as svg_module
from reports.drawing.drawing import (
    DYNAMIC_RTOL,
    DrawingError,
    draw_svg,
    frame_grid,
    still_grid,
)
from scenarios import GROUND, Revolute, Scenario, catalogue, load
from scenarios.geometry import world_point

ROOT = Path(__file__).resolve().parents[3]
SVG = "{http://www.w3.org/2000/svg}"
EXAMPLES = sorted(str(Path(p).relative_to(ROOT)) for p in glob.glob(str(ROOT / "examples" / "*.toml")))
LOBED = ["cam_roller[profile=lobed]", "cam_knife_edge[profile=lobed]"]
SLOW = {
    "slider_crank_spring/undamped",
    "stiff_spring/k1e8_dt1e-4",
    "stiff_spring/k1e8_dt1e-3",
    "stiff_spring/k1e8_dt1e-2",
}
"""Dynamic scenarios whose drawing at mid-horizon takes 3 to 6 s (two native solves)."""
NOT_AT_MIDDLE = {"n_four_bar/spec"}
"""Forty loops integrated for 10 s take the native solver minutes: drawn at t = 0 only (its family,
n_four_bar, is drawn at mid-horizon too)."""


def _cases() -> list[object]:
    cases: list[object] = []
    for name in catalogue(include_dynamic=True) + LOBED + EXAMPLES:
        marks = [pytest.mark.slow] if name in NOT_AT_MIDDLE else []  # its one step takes 15 s
        cases.append(pytest.param(name, "start", marks=marks, id=f"{name}-start"))
        if name not in NOT_AT_MIDDLE:
            marks = [pytest.mark.slow] if name in SLOW else []
            cases.append(pytest.param(name, "middle", marks=marks, id=f"{name}-middle"))
    return cases


def _scenario(name: str) -> Scenario:
    return load(str(ROOT / name) if name.endswith(".toml") else name)


def _native(scenario: Scenario, times: np.ndarray) -> pd.DataFrame:
    """The native solver's trajectory on `times` (a grid from 0), through the public API."""
    settings = {"rtol": DYNAMIC_RTOL} if scenario.analysis == "dynamic" else None
    return mbxval.solve(scenario, settings=settings, t_end=float(times[-1]), steps=len(times) - 1)


def _labels(frame: ET.Element) -> set[str]:
    return {t.text or "" for t in frame.iter(f"{SVG}text") if t.get("class") == "label"}


def _check_frame(scenario: Scenario, root: ET.Element, frame: ET.Element, row: pd.Series) -> int:
    """Every name labelled; each revolute's drawn centre where the solver's row puts it (1e-9 of the
    mechanism's size); the number of joints checked."""
    labels = _labels(frame)
    names = set(scenario.body_names) | {j.name for j in scenario.joints}
    assert names - labels == set(), f"not labelled: {names - labels}"
    scale = float(root.get("data-scale", "nan"))
    ox, oy = float(root.get("data-origin-x", "nan")), float(root.get("data-origin-y", "nan"))
    drawn = {
        c.get("data-joint"): (
            (float(c.get("cx", "nan")) - ox) / scale,
            (oy - float(c.get("cy", "nan"))) / scale,
        )
        for c in frame.iter(f"{SVG}circle")
        if c.get("class") == "revolute"
    }
    expected = {}
    for joint in (j for j in scenario.joints if isinstance(j, Revolute)):
        body = joint.p_i.body
        if body == GROUND:
            expected[joint.name] = joint.p_i.local
        elif f"{body}.x" in row:
            pose = (row[f"{body}.x"], row[f"{body}.y"], row[f"{body}.theta"])
            expected[joint.name] = world_point(pose, joint.p_i.local)
    if not expected:
        return 0
    points = np.array(list(expected.values()))
    size = max(scenario.characteristic_length, float(np.max(np.ptp(points, axis=0))))
    for name, point in expected.items():
        # 1e-6: the native default through singular passages is ALI3-P at the rule's fixed step
        # (n_four_bar), whose pose differs from a tightly solved one by about 1e-6 of the size
        assert math.dist(drawn[name], point) <= 1e-6 * size, (name, drawn[name], point)
    return len(expected)


@pytest.mark.parametrize(("name", "where"), _cases())
def test_every_scenario_draws_labelled_with_its_joints_where_the_solver_puts_them(
    name: str, where: str
) -> None:
    scenario = _scenario(name)
    before = copy.deepcopy(scenario)
    t = 0.0 if where == "start" else scenario.t_end / 2
    root = ET.fromstring(draw_svg(scenario, t))
    assert scenario == before  # the drawing reads the scenario, never changes it
    frames = [g for g in root.iter(f"{SVG}g") if g.get("class") == "frame"]
    assert len(frames) == 1 and float(frames[0].get("data-t", "nan")) == t
    assert f"t = {t:.6g} s" in (root.findtext(f"{SVG}title") or "")
    times = still_grid(scenario, t)
    row = _native(scenario, times).iloc[0 if t == 0.0 else -1]
    checked = _check_frame(scenario, root, frames[0], row)
    assert checked > 0 or not any(isinstance(j, Revolute) for j in scenario.joints)


def test_an_animation_loops_its_frames_over_one_cycle_each_where_the_solver_puts_it() -> None:
    scenario = load("four_bar")
    frames = 6
    root = ET.fromstring(draw_svg(scenario, frames=frames))
    groups = [g for g in root.iter(f"{SVG}g") if g.get("class") == "frame"]
    assert len(groups) == frames
    period = 2 * math.pi / float(scenario.parameter("omega"))  # one crank turn
    times, indices = frame_grid(scenario, frames)
    assert times[-1] == pytest.approx(period, rel=1e-12)
    native = _native(scenario, times)
    for k, group in enumerate(groups):
        assert float(group.get("data-t", "nan")) == pytest.approx(k * period / frames, rel=1e-12, abs=1e-15)
        assert group.get("visibility") == ("visible" if k == 0 else "hidden")
        animate = group.find(f"{SVG}animate")
        assert animate is not None and animate.get("repeatCount") == "indefinite"
        values = (animate.get("values") or "").split(";")
        assert values.index("visible") == k and values.count("visible") == 1
        assert len((animate.get("keyTimes") or "").split(";")) == frames
        assert _check_frame(scenario, root, group, native.iloc[indices[k]]) == 4


def test_a_cam_is_drawn_with_its_profile_follower_and_contact_on_the_profile() -> None:
    """A lobed cam: the contact dot lies on the drawn profile (within the outline's spacing), and the
    roller, drawn at its true radius, touches it: its centre is one roller radius from the dot."""
    scenario = load("cam_roller", {"profile": "lobed"})
    root = ET.fromstring(draw_svg(scenario, 0.1))
    scale = float(root.get("data-scale", "nan"))
    assert {"cam", "roller", "stem", "contact"} <= {e.get("class") for e in root.iter()}
    assert any(g.get("data-name") == "guide" for g in root.iter(f"{SVG}g"))  # the follower's sleeve
    circles = {c.get("class"): c for c in root.iter(f"{SVG}circle")}
    touch = np.array([float(circles["contact"].get(k, "nan")) for k in ("cx", "cy")])
    centre = np.array([float(circles["roller"].get(k, "nan")) for k in ("cx", "cy")])
    radius = float(circles["roller"].get("r", "nan"))
    assert radius == pytest.approx(scenario.cams[0].roller_radius * scale, rel=1e-6)  # type: ignore[union-attr]
    assert np.linalg.norm(touch - centre) == pytest.approx(radius, rel=1e-6)
    outline = next(p for p in root.iter(f"{SVG}polygon") if p.get("class") == "cam")
    points = np.array([[float(v) for v in pair.split(",")] for pair in (outline.get("points") or "").split()])
    spacing = float(np.max(np.linalg.norm(np.diff(points, axis=0), axis=1)))
    assert float(np.min(np.linalg.norm(points - touch, axis=1))) <= spacing


@pytest.mark.parametrize(
    ("t", "frames", "message"),
    [
        (-0.1, 1, "t must be in"),
        (1.0, 1, "t must be in"),
        (math.nan, 1, "t must be in"),
    ],
)
def test_a_time_outside_the_horizon_is_refused(t: float, frames: int, message: str) -> None:
    with pytest.raises(DrawingError, match=message):
        draw_svg(load("four_bar"), t, frames)


@pytest.mark.parametrize("frames", [0, 241, -3])
def test_a_frame_count_out_of_range_is_refused(frames: int) -> None:
    with pytest.raises(DrawingError, match="frames must be in"):
        draw_svg(load("four_bar"), 0.0, frames)


def test_drawings_inline_in_one_page_share_no_ids_and_scope_their_styles() -> None:
    """Each drawing names its marker and pattern apart, every reference finds its target in the
    same drawing, and every style rule applies under the drawing's own root class only."""
    texts = [draw_svg(load("four_bar"), t) for t in (0.0, 0.05)]
    ids = []
    for text in texts:
        root = ET.fromstring(text)
        defined = {e.get("id") for e in root.iter() if e.get("id")}
        referenced = set(re.findall(r"url\(#([^)]+)\)", text))
        assert referenced and referenced <= defined
        ids.append(defined)
        style = root.findtext(f"{SVG}style") or ""
        rules = [line for line in style.strip().splitlines() if line]
        assert rules and all(line.startswith(f".{root.get('class')} ") for line in rules)
    assert ids[0].isdisjoint(ids[1])


def test_a_chain_keeps_its_pins_apart_and_one_tiny_link_is_drawn_to_scale() -> None:
    """Ten loops of 1 m links (the IFToMM benchmark's): the page grows so that pins are
    PIN_SPACING apart. A slider-crank whose crank is 1e-3 of its rod has three pins: it stays on
    the usual page, the crank as small as it is (its rod fills the width), not a 6000 px strip."""
    chain = ET.fromstring(draw_svg(load("n_four_bar[loops=10]")))
    assert float(chain.get("width", "nan")) > svg_module.WIDTH
    assert float(chain.get("data-scale", "nan")) * 1.0 >= svg_module.PIN_SPACING * (1 - 1e-9)
    tiny = load("slider_crank/stress_link_ratio_1e-3")
    root = ET.fromstring(draw_svg(tiny))
    assert float(root.get("width", "nan")) == svg_module.WIDTH
    crank = dict(tiny.parameters)["crank_length"] * float(root.get("data-scale", "nan"))
    assert crank < svg_module.PIN_SPACING / 10
