"""Analysis.trajectory: each body's three columns at each level, in the order asked, and each
contact's phi as an extra, on arrays whose every entry says where it came from."""

from __future__ import annotations

import numpy as np

from reference_solver.layout import Layout
from reference_solver.solution import Analysis


def _analysis() -> Analysis:
    """Two bodies and a contact (7 columns), 2 times; entry (k, c) of level m is 100 m + 10 k + c."""
    layout = Layout(("crank", "cam"), ("touch",), 1.0)
    times = np.array([0.0, 0.5])
    q, qd, qdd = (100.0 * m + 10 * np.arange(2)[:, None] + np.arange(7)[None, :] for m in range(3))
    return Analysis(layout, times, q, qd, qdd, np.zeros(2), np.zeros(2), np.ones(2))


def test_trajectory_picks_each_body_and_the_contact_parameter() -> None:
    result = _analysis().trajectory()
    assert result.position is not None and result.velocity is not None and result.acceleration is not None
    assert result.bodies == ("crank", "cam")
    np.testing.assert_array_equal(result.times, [0.0, 0.5])
    np.testing.assert_array_equal(result.position[1], [[10, 11, 12], [13, 14, 15]])
    np.testing.assert_array_equal(result.velocity[0], [[100, 101, 102], [103, 104, 105]])
    np.testing.assert_array_equal(result.acceleration[1, 1], [213, 214, 215])
    assert list(result.extras) == ["touch.phi"]
    np.testing.assert_array_equal(result.extras["touch.phi"], [6, 16])


def test_trajectory_of_chosen_bodies_in_their_order_and_copies() -> None:
    analysis = _analysis()
    result = analysis.trajectory(["cam"])
    assert result.bodies == ("cam",) and result.position is not None
    np.testing.assert_array_equal(result.position[:, 0], [[3, 4, 5], [13, 14, 15]])
    result.times[0] = result.extras["touch.phi"][0] = -1.0  # the analysis keeps its own arrays
    assert analysis.times[0] == 0.0 and analysis.q[0, 6] == 6.0
