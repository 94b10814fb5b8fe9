"""The engines the tests run, drawn from the registry (adapters.names), so that a registered engine
joins every test that runs them all without the test being edited. An engine whose package is not
installed here (an optional extra, such as Drake without `pip install -e '.[drake]'`) is left out,
as `mbxval run` leaves it out (reports.run.runner.not_installed); an engine whose own module is
broken stays in, and its tests fail."""

from __future__ import annotations

import adapters
from reports.run.runner import not_installed


def _installed(name: str) -> bool:
    try:
        adapters.adapter_class(name)
    except adapters.EngineUnavailable as error:
        return not not_installed(error)
    return True


ENGINES = tuple(name for name in adapters.names() if _installed(name))
"""Every registered engine installed here, the native solver first."""
COMPARED = tuple(engine for engine in ENGINES if engine != adapters.NATIVE)
"""Every engine but the native solver: the ones set against it."""
