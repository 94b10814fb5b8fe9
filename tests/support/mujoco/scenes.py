"""The catalogue's kinematic scenes that several of MuJoCo's tests run."""

from __future__ import annotations

import scenarios

LINKAGES = (
    "slider_crank",
    "slider_crank/offset",
    "slider_crank/slider_drive",
    "four_bar",
    "four_bar/crossed",
    "four_bar_chain",
)
"""The slider-cranks, four-bars and the four-bar chain: closed loops of pins and sliders only."""
DISC_SCENARIOS = tuple(name for name in scenarios.catalogue() if not name.endswith("/spline"))
"""The kinematic catalogue but its spline cams: every cam on its disc, which MuJoCo models as the
disc's equivalent linkage (the default cam model)."""
