"""`--set KEY.PATH=VALUE` on a scenario file: change one value of the parsed file before it is read.

A path walks tables by key and arrays of tables by index or by the `name` of an element:
`t_end`, `bodies.crank.mass`, `drivers.drive.motion.rate`, `joints.0.p_i.local`. A value given as
text is read as a TOML value (`2`, `0.5`, `[0, 0.1]`, `true`), else kept as a string.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable, Mapping
from typing import Any, NoReturn

from scenarios.files.schema import suggestion
from scenarios.scenario import ScenarioError


def override_value(text: object) -> object:
    """A command-line value as TOML would read it; text that is no TOML value stays a string."""
    if not isinstance(text, str):
        return text
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text
    except RecursionError:
        raise ScenarioError("a --set value nested too deeply to read") from None


def _element(items: list[Any], part: str) -> Any:
    if part.isdigit() and int(part) < len(items):
        return int(part)
    for k, item in enumerate(items):
        if isinstance(item, dict) and item.get("name") == part:
            return k
    return None


def apply_overrides(
    doc: dict[str, Any], overrides: Mapping[str, object], fail: Callable[[str, str], NoReturn]
) -> None:
    """Set each dotted path of `doc` to its value; `fail(path, message)` for a path that leads nowhere."""
    for dotted, raw in overrides.items():
        parts = dotted.split(".")
        node: Any = doc
        for depth, part in enumerate(parts):
            where = f"--set {dotted}"
            last = depth == len(parts) - 1
            if isinstance(node, list):
                index = _element(node, part)
                if index is None:
                    names = [str(i.get("name")) for i in node if isinstance(i, dict)]
                    fail(where, f"no element '{part}'{suggestion(part, names)}; names: {', '.join(names)}")
            elif isinstance(node, dict):
                index = part
                if part not in node and not last:
                    fail(where, f"no key '{part}'{suggestion(part, list(node))}")
            else:
                fail(where, f"'{'.'.join(parts[:depth])}' holds a value, not a table")
            if last:
                node[index] = override_value(raw)
            else:
                node = node[index]
