"""The Python API's argument checks: each argument of a public function (mbxval.api) against its
declared type where it enters, so that a misuse is one ArgumentError naming the argument, what it
must be and what it got, never a TypeError or AttributeError from deep inside. Ranges are then
checked by the command line's own code, with its messages.

A bool is refused where a number is expected (`steps=True` is no step count), bytes where text is,
and text with a control or line-break character anywhere: every name and path given here reaches a
message, a terminal or a file name.
"""

from __future__ import annotations

import numbers
import os
import unicodedata
from collections.abc import Callable, Mapping, Sequence
from typing import TypeVar

from scenarios.shown import shown

NOT_TEXT = ("Cc", "Zl", "Zp")
"""Unicode categories a name or path may not hold: control characters and line separators."""

T = TypeVar("T")


class ArgumentError(ValueError):
    """An argument the command line would refuse (the message is the command line's)."""


def refuse(name: str, expected: str, value: object) -> ArgumentError:
    """The error for argument `name`: what it must be and what it got, on one line."""
    return ArgumentError(f"{name} must be {expected}, got {type(value).__name__} {shown(value)}")


def _plain(name: str, value: str, longest: int | None) -> str:
    if any(unicodedata.category(c) in NOT_TEXT for c in value):
        raise refuse(name, "text without control or line-break characters", value)
    if longest is not None and len(value) > longest:
        raise ArgumentError(f"{name} must be at most {longest} characters, got {len(value)}")
    return value


def text(name: str, value: object, longest: int | None = None) -> str:
    """A str (not bytes), without control characters, at most `longest` characters."""
    if not isinstance(value, str):
        raise refuse(name, "a str", value)
    return _plain(name, value, longest)


def optional_text(name: str, value: object) -> str | None:
    """None, or text as `text` takes it."""
    return None if value is None else text(name, value)


def path(name: str, value: object, what: str = "a path") -> str:
    """A path (or a name, as `what` says) given as a non-empty str or an os.PathLike of one."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str) or not value:
        raise refuse(name, f"{what} (a non-empty str or os.PathLike)", value)
    return _plain(name, value, None)


def scenario_name(name: str, value: object) -> str:
    """A built-in scenario's name or a scenario file's path."""
    return path(name, value, "a scenario name or file")


def whole(name: str, value: object) -> int | None:
    """An int (numpy's too) or None; a bool or a float is no count."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise refuse(name, "an int or None", value)
    return int(value)


def real(name: str, value: object) -> float | None:
    """A real number (an int or float, numpy's too) or None; not a bool, not text."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise refuse(name, "a number (float or int) or None", value)
    return float(value)


def flag(name: str, value: object) -> bool:
    """True or False, nothing that only behaves like one."""
    if not isinstance(value, bool):
        raise refuse(name, "True or False", value)
    return value


def names(name: str, value: object, one: Callable[[str, object], str]) -> list[str]:
    """None (none given), one name, or a list or tuple of them, each checked by `one`."""
    if value is None:
        return []
    if isinstance(value, str | os.PathLike):
        return [one(name, value)]
    if not isinstance(value, Sequence) or isinstance(value, bytes | bytearray):
        raise refuse(name, "a name, a list of names or None", value)
    return [one(f"{name}[{k}]", item) for k, item in enumerate(value)]


def mapping(name: str, value: object, check: Callable[[str, object], T]) -> dict[str, T]:
    """None (empty) or a mapping of `NAME` to values each passing `check`; NAME as `--set` takes
    it: text, not empty, without '='."""
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise refuse(name, "a mapping of names to values (a dict) or None", value)
    checked: dict[str, T] = {}
    for key, item in value.items():
        if not isinstance(key, str) or not key or "=" in key:
            raise refuse(f"a key of {name}", "a non-empty str without '='", key)
        checked[key] = check(f"{name}[{_plain(name, key, None)!r}]", item)
    return checked


def scenario_value(name: str, value: object) -> str:
    """A scenario parameter's value as the text `--set` takes: a number, a bool (a file's `true` or
    `false`) or text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return option_value(name, value)


def option_value(name: str, value: object) -> str:
    """An engine option's value as the text `--setting` takes: a number or text (no option is a
    bool)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return str(value)
    if isinstance(value, str):
        return _plain(name, value, None)
    raise refuse(name, "a number or a str", value)
