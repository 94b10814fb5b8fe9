"""How a message shows what it did not make (a value given to the API, a plug-in's declaration or
error): on one line, whatever the text holds, and cut short, so that an error or a warning is
always the one line the command line promises."""

from __future__ import annotations

MOST = 60
"""The most characters of a value a message repeats."""


def one_line(text: str) -> str:
    """`text` with every control or line-break character a space and each run of spaces one."""
    return " ".join("".join(c if c.isprintable() else " " for c in text).split())


def shown(value: object, most: int = MOST) -> str:
    """The repr of `value` on one line, cut to `most` characters."""
    text = one_line(repr(value))
    return text if len(text) <= most else text[: most - 3] + "..."
