"""The slider-crank's guessed start as built: the rod's centre midway between the crank's tip and the
slider's pin, which sits at the offset h above the crank's pivot line (assembly moves a poorer
guess onto the mechanism, so the closed-form tests cannot see it)."""

from __future__ import annotations

import pytest

import scenarios


@pytest.mark.parametrize("name", ["slider_crank", "slider_crank/offset"])
def test_the_rod_is_guessed_midway_between_the_crank_s_tip_and_the_slider_s_pin(name: str) -> None:
    scenario = scenarios.build(name)
    guess = {body.name: body.guess for body in scenario.bodies}
    tip = (2 * guess["crank"][0], 2 * guess["crank"][1])  # the crank's centre is half its tip
    pin = guess["slider"][:2]
    assert guess["rod"][:2] == pytest.approx(((tip[0] + pin[0]) / 2, (tip[1] + pin[1]) / 2), abs=1e-15)
    if name.endswith("offset"):
        assert pin[1] != 0.0
