"""Adding an engine touches its subpackage, one registry line and its tests (docs/adding-an-engine.md):
a toy engine (tests/support/toy_engine.py), registered by that one line and nothing else,
appears in `mbxval list`, runs in `mbxval run`, has its package recorded in the results' provenance
and printed by `--version`, is drawn in its own colour (stored with the run) and gets its own
settings in the stress cases that probe its knobs."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from importlib import metadata
from pathlib import Path

import pytest

import adapters
import scenarios
from reports.cli.main import main
from reports.render import plots
from reports.run import engine_facts
from reports.store.results_store import read_results
from reports.stress.cases import stress_settings
from tests.support.engines import ENGINES
from tests.support.toy_engine import COLOUR, PACKAGE, STIFF

TOY = "toy"


@pytest.fixture
def registered(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The toy's one registry line (the facts read from the registry are cached: cleared around)."""
    monkeypatch.setitem(adapters.ENGINES, TOY, ("tests.support.toy_engine", "ToyAdapter"))
    engine_facts.declared.cache_clear()
    yield
    engine_facts.declared.cache_clear()


@pytest.mark.usefixtures("registered")
def test_a_registered_engine_is_listed(capsys: pytest.CaptureFixture[str]) -> None:
    assert adapters.names()[-1] == TOY
    assert main(["list", "slider_crank"]) == 0
    lines = capsys.readouterr().out.splitlines()
    header = next(line for line in lines if line.startswith("scenario"))
    listed = [name for name in adapters.names() if name in ENGINES or name == TOY]  # the installed
    assert header.split()[1:] == listed
    row = next(line for line in lines if line.startswith("slider_crank "))
    assert row.split()[len(listed)] == "yes"  # the toy's cell, the last


@pytest.mark.usefixtures("registered")
def test_a_registered_engine_runs_with_its_provenance_and_colour_stored(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    args = ["run", "--suite", "quick", "--scenario", "slider_crank", "--engine", TOY, "--out", str(out)]
    assert main([*args, "--quiet"]) == 0, capsys.readouterr().err
    rows, meta = read_results(out)
    assert set(rows["engine"]) == {TOY} and set(rows["status"]) == {"ok"}
    assert meta["engines"] == {TOY: "0.1-toy"}
    assert meta["packages"][PACKAGE] == metadata.version(PACKAGE)
    assert meta["engine_colours"] == {TOY: COLOUR}
    assert COLOUR in (out / "index.html").read_text()  # its figures drawn in its colour


@pytest.mark.usefixtures("registered")
def test_a_registered_engine_s_package_is_in_the_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    assert f"{PACKAGE} {metadata.version(PACKAGE)}" in capsys.readouterr().out.splitlines()


@pytest.mark.usefixtures("registered")
def test_a_registered_engine_has_its_colour_and_its_stress_settings() -> None:
    assert engine_facts.colour(TOY) == COLOUR and engine_facts.colours([TOY, "my_tool"]) == {TOY: COLOUR}
    toy = adapters.load(TOY)
    stiffness = scenarios.build("slider_crank/stress_stiffness")
    assert stress_settings(stiffness, toy) == [toy.default_setting(stiffness), STIFF]
    assert stress_settings(scenarios.build("four_bar/stress_mass_1e3"), toy) is None


def test_an_engine_without_a_colour_and_a_label_that_is_no_engine_get_one_from_the_palette() -> None:
    """The report draws each engine as its store records it, and a name the store gives no colour
    (an imported label, a store from before colours were stored) in one of its palette's."""
    plots.use_stored_colours({"reference": "#444444"})
    assert plots.colour("reference") == "#444444"
    for name in ("my_tool", "reference_like_label", "mujoco"):
        assert engine_facts.colour(name) is None or name == "mujoco"
        assert plots.colour(name) in plots.PALETTE and plots.colour(name) == plots.colour(name)
    plots.use_stored_colours({})
    declared = {name: adapters.adapter_class(name).colour for name in ENGINES}
    assert all(declared.values()) and len(set(declared.values())) == len(declared)  # each its own
    assert engine_facts.colours(list(ENGINES)) == declared


ROOT = Path(__file__).resolve().parents[1]


def test_no_module_outside_the_adapters_spells_an_engine_s_name() -> None:
    """Outside `adapters/`, an engine is named by the registry (adapters.NATIVE for the native one),
    never by a string of its own: a string constant equal to an engine's name is a fact misplaced."""
    engines = set(adapters.names())
    found = {}
    for top in ("reports", "mbxval"):
        for path in sorted((ROOT / top).rglob("*.py")):
            named = {
                node.value
                for node in ast.walk(ast.parse(path.read_text()))
                if isinstance(node, ast.Constant) and node.value in engines
            }
            if named:
                found[str(path.relative_to(ROOT))] = named
    assert found == {}, found
    assert all(named == {adapters.NATIVE} for named in found.values()), found
