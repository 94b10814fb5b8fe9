"""A plug-in engine is another package's code: one that raises at import, has a syntax error, names
a module or class that is not there, or is no adapter is one warning line and that engine missing,
never `list`, `run`, `solve` or `--version` down; a plug-in's bad colour is one warning and a
palette colour, never a report that fails after its rows were stored.

The plug-ins are installed as pip leaves them (a `*.dist-info` folder with `entry_points.txt`
beside the module) in a folder put on sys.path, so `importlib.metadata` finds them as it finds any."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

import adapters
from reports.cli.main import main
from reports.run import engine_facts
from reports.store.results_store import read_results
from tests.support.engines import ENGINES

GOOD = """
from adapters.reference import ReferenceAdapter


class Engine(ReferenceAdapter):
    name = "{name}"
    colour = {colour!r}

    def version(self) -> str:
        return "0.1"
"""
# name: (the module's source, or None for no module; the detail its warning gives); a plug-in that
# calls sys.exit at import is broken too (a Ctrl-C while it loads still interrupts: no Exception)
BROKEN = {
    "raises": ('raise RuntimeError("broke\\non import")', "RuntimeError: broke on import"),
    "syntax": ("def broken(:\n", "SyntaxError: "),
    "nomodule": (None, "No module named 'plug_nomodule'"),
    "noclass": ("x = 1\n", "AttributeError: module 'plug_noclass' has no attribute 'Engine'"),
    "notadapter": ("class Engine:\n    pass\n", "plug_notadapter:Engine is not an Adapter subclass"),
    "misnamed": (GOOD.format(name="other", colour=""), "its adapter calls itself 'other'"),
    "exits": ("import sys\n\nsys.exit(3)\n", "SystemExit: 3"),
}


def install(site: Path, plugins: dict[str, str | None]) -> None:
    """Plug-ins `name -> module source` as one distribution in `site` (entry point `plug_NAME:Engine`)."""
    info = site / "plugs-0.1.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: plugs\nVersion: 0.1\n")
    lines = [f"{name} = plug_{name}:Engine" for name in plugins]
    (info / "entry_points.txt").write_text("[mbxval.engines]\n" + "\n".join(lines) + "\n")
    for name, source in plugins.items():
        if source is not None:
            (site / f"plug_{name}.py").write_text(source)


@pytest.fixture
def site(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A folder on sys.path for plug-ins; the registry's caches and the modules imported from it
    cleared around the test."""
    folder = tmp_path / "site"
    folder.mkdir()
    monkeypatch.syspath_prepend(str(folder))
    clear = (adapters.plugin_problem, engine_facts.declared, engine_facts.warn_once)
    for cached in clear:
        cached.cache_clear()
    yield folder
    for cached in clear:
        cached.cache_clear()
    for module in [m for m in sys.modules if m.startswith("plug_")]:
        del sys.modules[module]


def warnings_of(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.startswith("mbxval: warning: engine plug-in")]


@pytest.mark.parametrize("name", BROKEN)
def test_a_broken_plugin_is_one_warning_and_missing(
    name: str, site: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source, detail = BROKEN[name]
    install(site, {name: source})
    assert adapters.names() == list(adapters.ENGINES)
    assert adapters.names() == list(adapters.ENGINES)  # asked twice, warned once
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert err.startswith(f"mbxval: warning: engine plug-in {name} could not be loaded: {detail}"), err
    with pytest.raises(adapters.EngineUnavailable) as raised:
        adapters.load(name)
    assert str(raised.value) == err.removeprefix("mbxval: warning: ").rstrip("\n")


def test_the_commands_run_beside_broken_plugins(
    site: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    install(site, {name: BROKEN[name][0] for name in ("raises", "syntax")})
    assert main(["list", "four_bar"]) == 0
    listed = capsys.readouterr()
    header = next(line for line in listed.out.splitlines() if line.startswith("scenario"))
    assert header.split()[1:] == list(ENGINES)  # the installed ones
    assert len(warnings_of(listed.err)) == 2  # once each in the process
    assert main(["solve", "four_bar", "--steps", "4"]) == 0
    out = tmp_path / "run"
    argv = ["run", "--suite", "quick", "--scenario", "four_bar", "--engine", "reference", "--steps", "4"]
    assert main([*argv, "--out", str(out), "--quiet"]) == 0, capsys.readouterr().err
    assert set(read_results(out)[0]["engine"]) == {"reference"}
    capsys.readouterr()
    assert main(["solve", "four_bar", "--engine", "raises"]) == 2
    err = capsys.readouterr().err
    assert err == (
        "mbxval: error: engine plug-in raises could not be loaded: RuntimeError: broke on import\n"
    )
    with pytest.raises(SystemExit) as exited:
        main(["--version"])
    assert exited.value.code == 0


def test_a_plugins_bad_colour_is_a_warning_and_a_palette_colour(
    site: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    install(site, {"tinted": GOOD.format(name="tinted", colour='red"><script>')})
    out = tmp_path / "run"
    argv = ["run", "--suite", "quick", "--scenario", "four_bar", "--engine", "tinted", "--steps", "4"]
    assert main([*argv, "--out", str(out), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "mbxval: warning: engine tinted: colour 'red\"><script>' is not '#rrggbb' or '#rgb'" in err
    assert err.count(": colour ") == 1
    rows, meta = read_results(out)
    assert set(rows["status"]) == {"ok"} and "tinted" not in meta["engine_colours"]
    assert 'red"><script>' not in (out / "index.html").read_text()


@pytest.mark.parametrize("colour", ["#0a0b0c", "#abc", "#ABCDEF"])
def test_a_hex_colour_is_taken(colour: str, site: Path, capsys: pytest.CaptureFixture[str]) -> None:
    install(site, {"tinted": GOOD.format(name="tinted", colour=colour)})
    assert engine_facts.colour("tinted") == colour
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("colour", ["red", "#12", "#1234567", "0.5", "#ggg", " #abc"])
def test_anything_else_is_no_colour(colour: str, site: Path, capsys: pytest.CaptureFixture[str]) -> None:
    install(site, {"tinted": GOOD.format(name="tinted", colour=colour)})
    assert engine_facts.colour("tinted") is None
    assert capsys.readouterr().err.count("engine tinted: colour") == 1
