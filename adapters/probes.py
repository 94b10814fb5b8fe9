"""What a stress case probes, where an engine may answer with settings of its own
(Adapter.probe_settings): the vocabulary the stress suite (reports.stress.cases) and the engines
share, so that no engine's settings for a case sit outside its subpackage."""

from __future__ import annotations

from typing import Literal

Probe = Literal["stiffness", "mass"]
STIFFNESS: Probe = "stiffness"
"""The constraint stiffness (or stabilisation) against the step: the engine's own knobs swept."""
MASS: Probe = "mass"
"""Masses far apart: the engines whose result depends on the masses run a finer or dynamic setting."""
