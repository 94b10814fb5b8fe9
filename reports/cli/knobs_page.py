"""docs/engine-knobs.md, every built-in engine's modes, options and accuracy knobs as Markdown tables,
generated from the adapters' declarations so that the page cannot drift from the code
(tests/reports/cli/test_list_engine.py compares them). Write it with
`python -m reports.cli.knobs_page > docs/engine-knobs.md`."""

from __future__ import annotations

import adapters
from reports.cli.engine_listing import engine_markdown

DOCUMENT_HEAD = """# Every engine's accuracy knobs

Generated from the adapters' declarations (`Adapter.modes`, `Adapter.options`, `Adapter.knobs`) by
`python -m reports.cli.knobs_page > docs/engine-knobs.md`; a test checks that this page is what
the generator writes. `mbxval list --engine NAME` prints one engine's tables.

A knob is an option, or a setting of the engine's own, that changes the error. Each is **swept**
(rungs of the settings ladder or the untuned point vary it: docs/settings-rule.md), **fixed** (one
value everywhere, for the reason given) or **not applicable** (it cannot change an error measured
here, or it chooses the model rather than its accuracy). Every option an engine declares is one of
its knobs.
"""


def knobs_document() -> str:
    """docs/engine-knobs.md: every built-in engine's tables (EngineUnavailable if one is missing here,
    so that the page is never written without an engine)."""
    sections = ["\n".join(engine_markdown(adapters.adapter_class(name))) for name in adapters.ENGINES]
    return DOCUMENT_HEAD + "\n" + "\n".join(sections).rstrip("\n") + "\n"


if __name__ == "__main__":
    print(knobs_document(), end="")
