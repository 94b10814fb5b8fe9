"""The stress report's settings grid of a mode without a step size: one row per tolerance, never a
repeated `dt=nan` row per setting."""

from __future__ import annotations

import math

from reports.render.stability_render import settings_frames
from reports.render.stored_verdicts import Judgement


def judgement(setting: str, error: float) -> Judgement:
    return Judgement("slider_crank", "pinocchio", setting, False, "ok", math.nan, error, math.nan, "")


def test_a_tolerance_sweep_is_gridded_by_its_tolerance() -> None:
    labels = [f"kinematic gears=mimic tol={tol:g}" for tol in (1e-6, 1e-9, 1e-12)]
    frames = settings_frames([judgement(label, 10.0**-k) for k, label in enumerate(labels, start=3)])
    frame = frames["slider_crank · pinocchio kinematic"]
    assert list(frame.index) == ["tol=1e-06", "tol=1e-09", "tol=1e-12"]
    assert frame.shape == (3, 1)
    assert not any("nan" in str(i) for i in frame.index)


def test_a_step_sweep_is_still_gridded_by_dt() -> None:
    labels = [f"RK4 dt={dt:g} impedance=0.9999" for dt in (1e-3, 1e-4, 1e-5)]
    frame = next(iter(settings_frames([judgement(label, 1e-6) for label in labels]).values()))
    assert list(frame.index) == ["dt=0.001", "dt=0.0001", "dt=1e-05"]
