"""The four-bar chain's driver as built: one driver, named `crank_drive` (the name of its force
column in every engine's output), swinging the crank's absolute angle."""

from __future__ import annotations

import scenarios


def test_the_crank_s_angle_is_driven_by_crank_drive() -> None:
    scenario = scenarios.build("four_bar_chain")
    (driver,) = scenario.drivers
    assert (driver.name, driver.body, driver.coordinate) == ("crank_drive", "crank", "theta")
