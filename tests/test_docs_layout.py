"""The layout section of docs/layout.md names every package directory of the tree, and nothing that is
not."""

from __future__ import annotations

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGES = ("mbxval", "scenarios", "reference_solver", "adapters", "reports")


def test_the_layout_section_matches_the_package_tree() -> None:
    text = (ROOT / "docs" / "layout.md").read_text()
    section = text[text.index("## Layout") : text.index("Imports flow one way")]
    named = set(re.findall(r"^    ([a-z_/]+/)\s", section, flags=re.M))
    packages = {
        str(init.parent.relative_to(ROOT)) + "/"
        for top in PACKAGES
        for init in (ROOT / top).rglob("__init__.py")
        if "__pycache__" not in init.parts
    }
    assert packages - named == set(), "package directories missing from the layout in docs/layout.md"
    assert {n for n in named if n.split("/")[0] in PACKAGES} - packages == set(), "named but not in the tree"
