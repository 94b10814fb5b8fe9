"""An engine's accuracy knobs: every documented option or mode choice that changes the error, and how
the harness treats it (swept in the ladder, fixed at one value, or not applicable), with why.

Each adapter declares its knobs as data (`Adapter.knobs`), so that `mbxval list --engine NAME` and
docs/engine-knobs.md show the same table, and a new option cannot arrive unclassified (every
declared Option is one of the knobs: tests/adapters/test_knobs.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final, Literal

SWEPT: Final = "swept"
FIXED: Final = "fixed"
NOT_APPLICABLE: Final = "not applicable"
TREATMENTS = (SWEPT, FIXED, NOT_APPLICABLE)
"""How the harness treats a knob: swept (rungs of the settings ladder or the untuned point vary
it), fixed (one value everywhere, the reason saying why), not applicable (it cannot change an
error measured here, or it chooses the model rather than its accuracy)."""

Treatment = Literal["swept", "fixed", "not applicable"]


@dataclass(frozen=True)
class Knob:
    """One accuracy knob of an engine: its `name` (an option's name where it is one, else the
    engine's own name for it), its `treatment` (TREATMENTS) and `why`, one sentence."""

    name: str
    treatment: Treatment
    why: str

    def __post_init__(self) -> None:
        if self.treatment not in TREATMENTS:
            raise ValueError(f"knob {self.name}: treatment must be one of {', '.join(TREATMENTS)}")
        if not self.why.strip():
            raise ValueError(f"knob {self.name}: says no why")
