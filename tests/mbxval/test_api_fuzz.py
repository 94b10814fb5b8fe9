"""A property of the Python API: whatever its public functions are given, a call either returns or
raises ArgumentError or ScenarioError with a one-line message; never another exception.

Each argument is drawn from values it takes (a few, cheap to run) and from values of any type
(None, bools, numbers at their edges, text, bytes, containers, arrays, frames, objects), so that
most calls are misuse and some succeed (test_the_calls_see_both_outcomes)."""

from __future__ import annotations

import math
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import mbxval

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "slider_crank.toml"
STEPS = 6
FRAME = mbxval.solve("four_bar", steps=STEPS)
"""A trajectory the API scores: four_bar's on its own grid of STEPS steps."""

NUMBERS = st.sampled_from([0, -1, 1, 2**63, 1e-300, 1e300, math.inf, -math.inf, math.nan, 0.5, -0.0])
ANY = st.one_of(
    st.none(),
    st.booleans(),
    NUMBERS,
    st.integers(),
    st.floats(),
    st.text(max_size=20),
    st.binary(max_size=8),
    st.lists(st.integers() | st.text(max_size=5) | st.none(), max_size=3),
    st.dictionaries(
        st.text(max_size=5) | st.integers(), st.integers() | st.text(max_size=5) | st.none(), max_size=3
    ),
    st.sampled_from([object(), np.zeros(3), np.float64(0.1), np.int64(3), pd.DataFrame(), Path("x"), 1j]),
)
"""A value of any type: what a caller can pass by mistake."""


def maybe(valid: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    """A value `valid` draws, or one in six times a value of any type: so that a call with several
    arguments is often right everywhere (and runs) and often wrong in one or two places."""
    return st.integers(0, 5).flatmap(lambda k: ANY if k == 0 else valid)


SCENARIOS = maybe(st.sampled_from(["four_bar", "slider_crank", str(EXAMPLE), EXAMPLE, "four_bar[omega=5]"]))
PARAMETER_NAMES = st.sampled_from(["offset", "omega", "crank_length", "t_end", "steps", "bodies.crank.mass"])


def parameters(*taken: str) -> st.SearchStrategy[dict[str, Any]]:
    """Scenario parameters as keywords, none named as one of the function's own arguments."""
    names = (PARAMETER_NAMES | st.text(max_size=8).filter(str.isidentifier)).filter(lambda n: n not in taken)
    return st.dictionaries(names, maybe(st.sampled_from(["0.05", 0.05, 5, "5"])), max_size=2)


GRID_STEPS = maybe(st.sampled_from([None, STEPS, 1]))
T_ENDS = maybe(st.sampled_from([None, 0.05, 1e-3]))


def outcome(call: Callable[[], object]) -> str:
    """'ok', or 'refused' for an ArgumentError or ScenarioError of one line; anything else fails."""
    try:
        call()
    except (mbxval.ArgumentError, mbxval.ScenarioError) as error:
        message = str(error)
        assert message and len(message.splitlines()) == 1, message
        return "refused"
    return "ok"


FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@FUZZ
@given(SCENARIOS, parameters("name_or_file"))
def test_load_scenario(name: Any, parameters: dict[str, Any]) -> None:
    event(outcome(lambda: mbxval.load_scenario(name, **parameters)))


@FUZZ
@given(
    SCENARIOS,
    maybe(st.sampled_from(["reference", "nope"])),
    maybe(st.sampled_from([None, "newton"])),
    maybe(st.sampled_from([None, {"tolerance": 1e-10}])),
    T_ENDS,
    GRID_STEPS,
    parameters("scenario", "engine", "mode", "settings", "t_end", "steps"),
)
def test_solve(
    scenario: Any, engine: Any, mode: Any, options: Any, t_end: Any, steps: Any, parameters: dict[str, Any]
) -> None:
    if isinstance(steps, int) and not isinstance(steps, bool) and steps > STEPS:
        steps = STEPS  # a valid count of many steps costs time, not coverage
    event(outcome(lambda: mbxval.solve(scenario, engine, mode, options, t_end, steps, **parameters)))


@FUZZ
@given(
    SCENARIOS,
    maybe(st.sampled_from([FRAME, FRAME.iloc[:3], FRAME.drop(columns="t")])),
    maybe(st.sampled_from(["mine", "reference", ""])),
    st.just({"steps": STEPS}) | parameters("scenario", "trajectory", "label"),
)
def test_compare(scenario: Any, trajectory: Any, label: Any, parameters: dict[str, Any]) -> None:
    event(outcome(lambda: mbxval.compare(scenario, trajectory, label, **parameters)))


def _narrow(value: Any, instead: str) -> Any:
    """`value`, or `instead` for None or an empty container: a run given no scenarios or engines
    runs all of them, for minutes."""
    empty = value is None or (isinstance(value, list | dict | str | bytes) and len(value) == 0)
    return instead if empty else value


def _few(steps: Any) -> Any:
    """A valid count of many steps costs time, not coverage: STEPS instead."""
    return STEPS if isinstance(steps, int) and not isinstance(steps, bool) and steps > STEPS else steps


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    maybe(st.sampled_from(["four_bar", ["four_bar"]])).map(lambda v: _narrow(v, "four_bar")),
    maybe(st.sampled_from(["reference", ["reference"]])).map(lambda v: _narrow(v, "reference")),
    maybe(st.sampled_from(["quick"])),
    maybe(st.just(STEPS)).map(_few),
    maybe(st.sampled_from([None, {"omega": 5}])),
    maybe(st.sampled_from([None, {"omega": "5,6"}])),
    maybe(st.sampled_from([1, None])),
    maybe(st.sampled_from([False])),
)
def test_run(
    scenarios: Any,
    engines: Any,
    suite: Any,
    steps: Any,
    parameters: Any,
    sweep: Any,
    repeats: Any,
    rerun: Any,
) -> None:
    with tempfile.TemporaryDirectory() as folder:
        arguments = {"parameters": parameters, "sweep": sweep, "repeats": repeats, "rerun": rerun}
        out = Path(folder) / "store"

        def call() -> object:
            return mbxval.run(
                scenarios, engines, suite=suite, out=out, steps=steps, report=False, **arguments
            )

        event(outcome(call))


@settings(max_examples=60, deadline=None)
@given(maybe(st.sampled_from(["/nonexistent", str(EXAMPLE), str(EXAMPLE.parent)])))
def test_read_results(directory: Any) -> None:
    event(outcome(lambda: mbxval.read_results(directory)))


def test_the_calls_see_both_outcomes() -> None:
    """The properties cannot pass by refusing everything, nor by taking everything."""
    assert outcome(lambda: mbxval.solve("four_bar", steps=STEPS)) == "ok"
    assert outcome(lambda: mbxval.solve("four_bar", steps=True)) == "refused"
    assert outcome(lambda: mbxval.compare("four_bar", FRAME, "mine", steps=STEPS)) == "ok"
    assert outcome(lambda: mbxval.compare("four_bar", FRAME, None)) == "refused"
