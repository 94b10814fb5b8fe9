"""The catalogue's kinematic scenes that several of MuJoCo's tests run."""

from __future__ import annotations

LINKAGES = (
    "slider_crank",
    "slider_crank/offset",
    "slider_crank/slider_drive",
    "four_bar",
    "four_bar/crossed",
    "four_bar_chain",
)
"""The slider-cranks, four-bars and the four-bar chain: closed loops of pins and sliders only."""
