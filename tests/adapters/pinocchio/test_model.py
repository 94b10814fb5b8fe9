"""Pinocchio's model carries the scenario's gravity in free dynamics, and none in a kinematically
driven scene even where the scenario declares one (the drivers prescribe the motion; gravity would
only enter the forces the kinematic mode does not report)."""

from __future__ import annotations

import dataclasses

import numpy as np

import scenarios
from adapters.pinocchio.model import build_model
from adapters.pinocchio.tree import plan


def test_gravity_is_the_scenario_s_in_free_dynamics_and_none_when_driven() -> None:
    free = scenarios.build("four_bar_gravity")
    assert free.analysis == "dynamic"
    assert (build_model(free, plan(free)).model.gravity.linear == [0.0, -9.81, 0.0]).all()
    driven = dataclasses.replace(scenarios.build("four_bar"), gravity=(0.0, -9.81))
    assert driven.analysis == "kinematic"
    assert (build_model(driven, plan(driven)).model.gravity.linear == np.zeros(3)).all()
