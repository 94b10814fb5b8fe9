"""The names a user gives, checked where they enter, and the one way a name becomes a file name.

A name (a scenario file's `name` and `variant`, its bodies', constraints' and outputs' names,
`export --name`, `compare --label`, a swept point's keys and values) is printed on terminals and in
logs, written into HTML, Markdown and SVG, and stored as a key. So it is text of at most
MAX_NAME_LENGTH characters, not empty or blank, without control or format characters (a newline
would start a line of the name's making, an escape sequence would drive the terminal, and XML
cannot hold most of them even escaped). A name that becomes a file name (`safe_file_stem`) is
moreover one path component: no separator, not `.` or `..`, not hidden.
"""

from __future__ import annotations

import unicodedata

from scenarios.scenario import POINT_RESERVED, Scenario, ScenarioError

MAX_NAME_LENGTH = 100
"""The most characters of a name (a scenario's, a body's, a label): far past any a user types, and
a file stem of at most 400 UTF-8 bytes, well within the 255 bytes of common file systems only when
mostly ASCII: MAX_FILE_STEM_BYTES bounds that apart."""
MAX_FILE_STEM_BYTES = 200
"""The most UTF-8 bytes of a name that becomes a file name (255 on common file systems, less a
suffix)."""
CONTROL_CATEGORIES = frozenset({"Cc", "Cf", "Cs", "Co", "Zl", "Zp"})
"""Unicode categories refused in a name: controls (newline, escape, NUL), format characters
(bidirectional overrides that reorder what is shown), surrogates, private use, line and
paragraph separators."""
SEPARATORS = "/\\"


class NameRefused(ScenarioError):
    """A name that cannot be taken; the message names what it is for and the rule it breaks."""


def _control(name: str) -> int | None:
    """The position of the first control or format character in `name`, or None."""
    return next((k for k, c in enumerate(name) if unicodedata.category(c) in CONTROL_CATEGORIES), None)


def check_name(name: object, what: str) -> str:
    """`name` as given when it is a name (see the module docstring); NameRefused saying why,
    without the name itself where it holds what a terminal would act on."""
    if not isinstance(name, str):
        raise NameRefused(f"{what} must be a text, got {type(name).__name__}")
    if not name.strip():
        raise NameRefused(f"{what} must not be empty or blank")
    if len(name) > MAX_NAME_LENGTH:
        raise NameRefused(f"{what} must be at most {MAX_NAME_LENGTH} characters, got {len(name)}")
    position = _control(name)
    if position is not None:
        code = f"U+{ord(name[position]):04X}"
        raise NameRefused(
            f"{what} must not hold control or format characters: {code} at character {position + 1}"
        )
    return name


def check_scenario_name(name: object, what: str) -> str:
    """A name a scenario file gives itself (`name`, `variant`, `export --name`): a name, and not one
    the scenario loader reads as something else: no '/' (a family's variant), no '.toml' ending (a
    file) and none of POINT_RESERVED (a swept point, `slider_crank[offset=0.05]`)."""
    text = check_name(name, what)
    if any(c in POINT_RESERVED + "/" for c in text) or text.endswith(".toml"):
        raise NameRefused(f"{what} must be a plain name, without '/', '.toml' or any of {POINT_RESERVED}")
    return text


def check_scenario_names(scenario: Scenario) -> Scenario:
    """`scenario` when every name it holds passes the checks a scenario file's names pass (its
    `name` and `variant` as check_scenario_name; its bodies', joints', drivers', forces', angle
    outputs' and parameters' names as check_name), for a Scenario built in Python rather than read;
    NameRefused naming the first that does not, by where it is."""
    check_scenario_name(scenario.family, "the scenario's name")
    check_scenario_name(scenario.variant, "the scenario's variant")
    groups = {
        "bodies": scenario.bodies,
        "joints": scenario.joints,
        "drivers": scenario.drivers,
        "forces": scenario.forces,
        "angle_outputs": scenario.angle_outputs,
    }
    for group, items in groups.items():
        for k, item in enumerate(items):
            check_name(item.name, f"{group}[{k}].name")
    for key, _ in scenario.parameters:
        check_name(key, "a parameter's name")
    return scenario


def safe_file_stem(name: object, what: str) -> str:
    """`name` when it can be a file's name in a directory chosen for it, and never leads out of
    it: a name (check_name) that is one path component, not hidden, of at most MAX_FILE_STEM_BYTES
    bytes; NameRefused otherwise. Every label that becomes a file name passes here."""
    text = check_name(name, what)
    if any(c in SEPARATORS for c in text):
        raise NameRefused(
            f"{what} must not hold a path separator ('/' or '\\'): it names, it does not locate"
        )
    if text.startswith("."):
        raise NameRefused(f"{what} must not start with '.' (no '.', '..' or hidden names)")
    size = len(text.encode("utf-8"))
    if size > MAX_FILE_STEM_BYTES:
        raise NameRefused(f"{what} must be at most {MAX_FILE_STEM_BYTES} bytes in UTF-8, got {size}")
    return text


def printable(text: str) -> str:
    """`text` with every control or format character written as its escape (`\\x1b`, `\\u202e`), so
    that a message quoting a value cannot act on the terminal it is printed to."""
    if _control(text) is None:
        return text
    return "".join(_escaped(c) if unicodedata.category(c) in CONTROL_CATEGORIES else c for c in text)


def _escaped(character: str) -> str:
    return character.encode("unicode_escape").decode("ascii")
