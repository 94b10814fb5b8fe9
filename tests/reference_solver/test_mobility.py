"""The mobility check's refusals, each on a hand-built mechanism whose ranks are known: one
redundant joint row (deficiency exactly 1), two (a duplicated pin), and a driver that acts on a
coordinate the joints already fix. Each pins a part of the check
that no other test reaches."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import scenarios
from reference_solver import MobilityError, analyse
from reference_solver.diagnostics import rank_report
from reference_solver.mobility import check_mobility
from reference_solver.system import ConstraintSystem
from scenarios import GROUND, AbsoluteDriver, Constant, Point, Prismatic, Revolute


def test_a_single_redundant_row_is_refused_with_deficiency_one() -> None:
    """A second slide on the slider-crank's slider, across the first: its angle row repeats the
    first slide's (theta_slider - theta_ground = 0), its normal row (x = 0) is new; so ten joint
    rows have rank nine. (A link that repeats a distance only on the constraint manifold would
    not do: ranks are judged at generic points near the configuration.)"""
    base = scenarios.build("slider_crank")
    across = Prismatic("slide2", Point("slider", (0.0, 0.0)), Point(GROUND, (0.0, 0.0)), axis=(0.0, 1.0))
    scenario = dataclasses.replace(base, joints=(*base.joints, across))
    with pytest.raises(
        MobilityError, match="redundantly constrained: 10 joint equations but only 9"
    ) as caught:
        analyse(scenario)
    assert caught.value.rank_deficiency == 1  # the two angle rows, one of them redundant
    assert set(caught.value.dependent_rows) == {"slide.angle", "slide2.angle"}


def test_two_dependent_rows_are_named_apart_by_a_comma() -> None:
    """A second pin at O4: two rows repeat two others, and the message lists them as the report
    at the configuration itself names them."""
    base = scenarios.build("four_bar")
    duplicate = Revolute("O4_again", Point(GROUND, (0.1, 0.0)), Point("rocker", (-0.0625, 0.0)))
    scenario = dataclasses.replace(base, joints=(*base.joints, duplicate))
    joints = ConstraintSystem(scenario, include_drivers=False)
    q = analyse(base).q[0]
    expected = rank_report(joints.scaled_jacobian(joints.jacobian(q, 0.0)), joints.labels)
    with pytest.raises(MobilityError) as caught:
        check_mobility(ConstraintSystem(scenario), q)
    assert caught.value.rank_deficiency == 2 == expected.deficiency
    assert caught.value.dependent_rows == expected.dependent_rows
    assert str(caught.value).endswith("; dependent rows: " + ", ".join(expected.dependent_rows))


def test_a_driver_on_a_coordinate_the_joints_fix_is_refused() -> None:
    """The slider-crank driven at its slider's angle, which the slide's angle row already holds
    (the same row, everywhere): one driver row for one degree of freedom, but not an independent
    one."""
    base = scenarios.build("slider_crank")
    held = AbsoluteDriver("slider_turn", "slider", "theta", Constant(0.0))
    scenario = dataclasses.replace(base, drivers=(held,))
    q = analyse(base).q[0]
    with pytest.raises(MobilityError, match=r"the drivers \(slider_turn\) do not act on independent degrees"):
        check_mobility(ConstraintSystem(scenario), q)


def test_the_counts_say_over_or_under_driven() -> None:
    base = scenarios.build("slider_crank")
    q = analyse(base).q[0]
    extra = AbsoluteDriver("rod_hold", "rod", "theta", Constant(0.0))
    with pytest.raises(MobilityError, match="over-driven: 2 driver equations"):
        check_mobility(ConstraintSystem(dataclasses.replace(base, drivers=(*base.drivers, extra))), q)
    with pytest.raises(MobilityError, match="under-driven: 0 driver equations"):
        check_mobility(ConstraintSystem(dataclasses.replace(base, drivers=())), q)
    assert check_mobility(ConstraintSystem(base), np.asarray(q)) == 1
