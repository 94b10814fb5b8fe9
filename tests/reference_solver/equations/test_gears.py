"""The gears' residuals at hand-worked configurations.

A spur pair rolls without slip at its contact: measured from the carrier, the arcs the two pitch
circles turn through are equal and opposite (external mesh) or equal (internal mesh, j the ring):
r_i (dth_i - dth_k) = -/+ r_j (dth_j - dth_k), with each angle measured from its assembled reference.
A rack is pushed along its axis u by the pinion's turn relative to the rack: the centre's position
along u, relative to a pitch point P of the rack, is radius * (th_pinion - th_rack) + offset.
"""

from __future__ import annotations

import math

import numpy as np

from scenarios import GROUND, GearPair, Point, RackPinion
from tests.support.constraint_systems import residual, system_of

# a, b and the carrier c turned from their references (0.1, 0.3, 0.2) to (0.5, -1.0, 0.7)
POSES = {"a": (0.0, 0.0, 0.5), "b": (0.0, 0.0, -1.0), "c": (0.0, 0.0, 0.7)}
TURNED_A, TURNED_B, TURNED_C = 0.5 - 0.1, -1.0 - 0.3, 0.7 - 0.2


def on_carrier(radius_i: float, radius_j: float, internal: bool) -> GearPair:
    """Gears a and b on the carrier c, assembled at the reference angles above."""
    return GearPair("m", "a", radius_i, "b", radius_j, "c", internal, 0.1, 0.3, 0.2)


def test_an_external_pair_on_a_carrier_is_its_slip_at_the_contact() -> None:
    gear = on_carrier(0.2, 0.1, internal=False)
    slip = 0.2 * (TURNED_A - TURNED_C) + 0.1 * (TURNED_B - TURNED_C)
    np.testing.assert_allclose(residual(gear, POSES), [slip], rtol=0, atol=1e-15)


def test_an_internal_pair_on_a_carrier_is_its_slip_at_the_contact() -> None:
    gear = on_carrier(0.1, 0.3, internal=True)
    slip = 0.1 * (TURNED_A - TURNED_C) - 0.3 * (TURNED_B - TURNED_C)
    np.testing.assert_allclose(residual(gear, POSES), [slip], rtol=0, atol=1e-15)


def test_a_pair_on_fixed_centres_rolls_in_the_inverse_ratio_of_the_radii() -> None:
    """The ground as carrier: turning a by 0.4 turns b by -0.4 * 0.2 / 0.1 with no slip."""
    gear = GearPair("m", "a", 0.2, "b", 0.1, theta0_i=0.1, theta0_j=0.3)
    rolled = {"a": (0.0, 0.0, 0.5), "b": (0.0, 0.0, 0.3 - 0.4 * 2.0)}
    np.testing.assert_allclose(residual(gear, rolled), [0.0], rtol=0, atol=1e-15)


def test_a_fixed_sun_drives_the_planet_by_the_carrier_alone() -> None:
    """The ground as sun i: the planet b turns by (1 + r_i / r_j) times the carrier's turn."""
    gear = GearPair("m", GROUND, 0.2, "b", 0.1, carrier="c", theta0_j=0.3, theta0_carrier=0.2)
    rolled = {"b": (0.0, 0.0, 0.3 + 3.0 * 0.5), "c": (0.0, 0.0, 0.2 + 0.5)}
    np.testing.assert_allclose(residual(gear, rolled), [0.0], rtol=0, atol=1e-15)
    held = {"b": (0.0, 0.0, 0.3), "c": (0.0, 0.0, 0.2 + 0.5)}  # the planet held: both arcs slip
    np.testing.assert_allclose(residual(gear, held), [0.2 * (0.0 - 0.5) + 0.1 * (0.0 - 0.5)], atol=1e-15)


def test_a_gear_that_is_its_own_carrier_locks_the_other_gear_to_it() -> None:
    """Gear a is also the carrier: it cannot turn relative to the carrier, so neither can b; the slip
    is r_b (dth_b - dth_a). The row's two terms on a add up (r_a - (r_a + r_b)) rather than replace."""
    gear = GearPair("m", "a", 0.2, "b", 0.1, "a", False, 0.1, 0.3, 0.1)
    np.testing.assert_allclose(residual(gear, POSES), [0.1 * (TURNED_B - TURNED_A)], rtol=0, atol=1e-15)


def test_a_rack_on_the_ground_along_an_inclined_axis() -> None:
    """The rack's pitch line through the origin along (3, 4) (not unit); the pinion's centre at (1, 2)
    is (3 + 8) / 5 along it from P, so P is -11/5 along u from the centre; the pinion turned by 0.4."""
    gear = RackPinion("rp", Point("a"), 0.5, Point(GROUND), axis=(3.0, 4.0), offset=0.3)
    np.testing.assert_allclose(
        residual(gear, {"a": (1.0, 2.0, 0.4)}), [-11 / 5 - 0.5 * 0.4 - 0.3], rtol=0, atol=1e-15
    )


def test_a_turned_rack_measures_along_its_own_axis_and_the_pinion_turns_relative_to_it() -> None:
    """Rack b at (0.5, 0) turned by 90 degrees: its axis (3, 4)/5 points along (-4, 3)/5 and its local
    P = (1, 0) is at (0.5, 1). The centre at (1.5, 2): P - c = (-1, -1), (4 - 3) / 5 along u."""
    gear = RackPinion("rp", Point("a"), 0.5, Point("b", (1.0, 0.0)), axis=(3.0, 4.0), offset=0.3)
    c = residual(gear, {"a": (1.5, 2.0, 0.4), "b": (0.5, 0.0, math.pi / 2)})
    np.testing.assert_allclose(c, [1 / 5 - 0.5 * (0.4 - math.pi / 2) - 0.3], rtol=0, atol=1e-15)


def test_a_gear_row_is_named_mesh() -> None:
    system = system_of(GearPair("m", "a", 0.2, "b", 0.1), RackPinion("rp", Point("a"), 0.5, Point("c")))
    assert system.labels == ["m.mesh", "rp.mesh"]
    assert [e.name for e in system.equations] == ["m", "rp"]
