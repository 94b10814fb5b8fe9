"""The engines the tests run, drawn from the registry (adapters.names), so that a registered engine
joins every test that runs them all without the test being edited."""

from __future__ import annotations

import adapters

ENGINES = tuple(adapters.names())
"""Every registered engine, the native solver first."""
COMPARED = tuple(engine for engine in ENGINES if engine != adapters.NATIVE)
"""Every engine but the native solver: the ones set against it."""
