"""Issue 22 replayed for verdicts and pages: the truth is always the truth of the mechanism judged
(a closed form only for a family's own mechanism, by digest), compare refuses numbers it cannot
score, a store made by `compare --out` renders, and the report escapes every name it did not write.
The command-line cases call `main` in this process."""

from __future__ import annotations

import json
import math
import re
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

import scenarios
from reports.cli.main import main
from reports.scoring.truth import CLOSED_FORM, NATIVE_REFINED, independent_truth
from scenarios.closed_form import NoClosedForm, exact
from scenarios.files import read_scenario, scenario_toml
from scenarios.identity import family_twin

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "slider_crank.toml"
RATE_20 = "drivers.crank_drive.motion.rate=20"


def compare_lines(capsys: pytest.CaptureFixture[str], *argv: str) -> dict[str, str]:
    """`mbxval compare` on argv: exit 0, and its verdict's lines by their first word."""
    assert main(["compare", *argv]) == 0
    lines = capsys.readouterr().out.splitlines()
    return {line.split(":")[0].split()[0]: line for line in lines if line.strip()}


def level_error(lines: dict[str, str], level: str) -> float:
    return float(lines[level].split()[1])


def edited_export(tmp_path: Path, old: str, new: str) -> Path:
    """The slider-crank family exported as a file, with `old` replaced by `new` once."""
    text = scenario_toml(scenarios.build("slider_crank"))
    assert old in text
    path = tmp_path / "edited.toml"
    path.write_text(text.replace(old, new, 1))
    return path


# --- the truth of the mechanism judged -----------------------------------------------------------
def test_the_readme_example_edited_by_set_scores_round_off(tmp_path: Path, capsys) -> None:
    csv = tmp_path / "r20.csv"
    assert main(["solve", str(EXAMPLE), "--set", RATE_20, "--out", str(csv)]) == 0
    lines = compare_lines(capsys, str(EXAMPLE), str(csv), "--set", RATE_20)
    assert lines["truth"] == f"truth: {NATIVE_REFINED}"
    for level in ("position", "velocity", "acceleration"):  # was 3.77, 1.34, 1.59 against 50 rad/s
        assert level_error(lines, level) < 1e-12
        assert lines[level].split()[2] == "green"


def test_an_export_with_its_rate_edited_gets_the_native_truth(tmp_path: Path) -> None:
    path = edited_export(tmp_path, " rate = 50.0 }", " rate = 20.0 }")
    scenario = read_scenario(path)
    assert family_twin(scenario) is None
    with pytest.raises(NoClosedForm, match="not the mechanism the family slider_crank builds"):
        exact(scenario)
    times = np.asarray(scenario.times())
    truth = independent_truth(scenario, times)
    assert truth.name == NATIVE_REFINED
    # The native truth turns the crank at 20 rad/s, as the file says, not at the table's 50.
    crank = truth.trajectory.velocity[:, 0, 2]  # type: ignore[index]
    assert np.allclose(crank, 20.0, rtol=0, atol=1e-9)


def test_an_old_files_parameters_table_alone_does_not_choose_a_closed_form(tmp_path: Path) -> None:
    """An old file's `[parameters]` table (exports no longer write one) is inert: saying omega = 20
    there leaves a mechanism turning at 50 rad/s, which the family at 20 rad/s is not."""
    path = tmp_path / "legacy.toml"
    path.write_text(scenario_toml(scenarios.build("slider_crank")) + "\n[parameters]\nomega = 20.0\n")
    scenario = read_scenario(path)
    assert family_twin(scenario) is None
    assert independent_truth(scenario, np.asarray(scenario.times())).name == NATIVE_REFINED


def test_the_family_mechanism_under_another_name_is_still_recognised_by_its_digest(tmp_path: Path) -> None:
    """Identity is the mechanism, not the name: the export renamed keeps no closed form (the name
    says which family to rebuild, and none is called so), and the export as written keeps it."""
    text = scenario_toml(scenarios.build("slider_crank"))
    renamed = tmp_path / "mine.toml"
    renamed.write_text(text.replace('name = "slider_crank"', 'name = "my_crank"', 1))
    assert family_twin(read_scenario(renamed)) is None
    with pytest.raises(NoClosedForm):
        exact(read_scenario(renamed))
    same = tmp_path / "same.toml"
    same.write_text(text)
    assert family_twin(read_scenario(same)) is not None


def test_an_unedited_export_keeps_the_closed_form_bit_for_bit() -> None:
    family, file = scenarios.build("slider_crank"), read_scenario(EXAMPLE)
    assert family_twin(file) is not None
    times = np.asarray(family.times())
    mine, theirs = independent_truth(file, times), independent_truth(family, times)
    assert mine.name == theirs.name == CLOSED_FORM
    for level in ("position", "velocity", "acceleration"):
        assert np.array_equal(mine.trajectory.level(level), theirs.trajectory.level(level))  # type: ignore[arg-type]


@pytest.mark.parametrize("name", scenarios.catalogue(include_stress=True))
def test_every_built_in_scenario_is_its_own_family_twin(name: str) -> None:
    scenario = scenarios.build(name)
    assert family_twin(scenario) is not None
    assert family_twin(scenarios.load(f"{name}[steps=7]")) is not None  # a swept point too


def test_a_changed_grid_is_still_the_family_mechanism() -> None:
    import dataclasses

    scenario = dataclasses.replace(scenarios.build("four_bar"), t_end=0.5, steps=17)
    assert family_twin(scenario) is not None
    assert math.isclose(float(exact(scenario).times[-1]), 0.5)


def test_a_file_taking_a_stress_case_name_gets_no_closed_form_truth(tmp_path: Path) -> None:
    from reports.stress.truth import stress_truth_name

    name = "slider_crank/stress_speed_1e1"
    built = scenarios.build(name)
    assert stress_truth_name(built) == "closed form"
    path = tmp_path / "fast.toml"
    path.write_text(scenario_toml(built).replace("mass = 0.5\n", "mass = 0.25\n", 1))
    assert "mass = 0.25" in path.read_text()
    edited = read_scenario(path)
    assert edited.name == name
    assert stress_truth_name(edited) == "native, tolerance 1e-12"


# --- compare's numbers ---------------------------------------------------------------------------
def one_line_error(capsys: pytest.CaptureFixture[str], *words: str) -> str:
    captured = capsys.readouterr()
    assert captured.err.startswith("mbxval: error: ") and captured.err.count("\n") == 1, captured.err
    for word in words:
        assert word in captured.err, captured.err
    return captured.err


def family_csv(path: Path, cell: tuple[int, str] | None = None, columns: tuple[str, ...] = ()) -> Path:
    """The slider-crank family's closed form as a CSV (only `columns` when given, with `t`), with
    the cell (row, column) replaced by the given text."""
    frame = exact(scenarios.build("slider_crank")).to_frame()
    if columns:
        frame = frame[["t", *columns]]
    text = frame.astype(float).map(lambda v: f"{v:.17g}").astype(str)
    if cell is not None:
        text.iloc[cell[0], text.columns.get_loc("crank.y")] = cell[1]
    text.to_csv(path, index=False)
    return path


@pytest.mark.parametrize(
    ("value", "words"),
    [
        ("1e308", ("line 5, column 3", "beyond the largest magnitude", "1e+100")),
        ("-1e101", ("line 5, column 3", "beyond the largest magnitude")),
        ("1_0", ("line 5, column 3: not a number",)),
        ("\u0661", ("not a number",)),  # Arabic-Indic one: float() reads it, a CSV does not
        ("nan", ("not finite",)),
        ("-Infinity", ("not finite",)),
    ],
)
def test_a_csv_number_compare_cannot_score_is_refused_in_one_line(
    tmp_path: Path, capsys, value: str, words: tuple[str, ...]
) -> None:
    csv = family_csv(tmp_path / "bad.csv", (3, value))
    out = tmp_path / "store"
    assert main(["compare", "slider_crank", str(csv), "--out", str(out)]) == 2
    one_line_error(capsys, *words)
    assert not out.exists()


def test_plain_csv_numbers_with_spaces_and_exponents_are_read(tmp_path: Path, capsys) -> None:
    csv = family_csv(tmp_path / "fine.csv", (3, " 3.0E-2 "))
    assert main(["compare", "slider_crank", str(csv)]) == 0
    assert "position" in capsys.readouterr().out


def test_an_overflowing_error_counts_as_infinite_not_as_undefined() -> None:
    from reports.scoring.level_error import largest
    from reports.scoring.metrics import summarise

    assert largest(np.array([1e-3, math.inf, math.nan])) == math.inf
    assert math.isnan(largest(np.array([math.nan, math.nan])))
    assert summarise(np.array([1.0, math.inf, math.nan]))["max"] == math.inf


def test_update_never_writes_a_baseline_check_refuses(tmp_path: Path, capsys) -> None:
    """An imported row without positions is ok but has no headline error: check would refuse a
    baseline holding it, so --update refuses to write one, in one line, and keeps the old file."""
    csv = family_csv(tmp_path / "vel.csv", columns=("crank.vx", "crank.vy", "crank.omega"))
    store = tmp_path / "store"
    assert main(["compare", "slider_crank", str(csv), "--out", str(store)]) == 0
    capsys.readouterr()
    baseline = tmp_path / "b.json"
    assert main(["check", "--baseline", str(baseline), "--results", str(store), "--update"]) == 2
    one_line_error(capsys, "cannot write baseline", "slider_crank x vel", "check would refuse it")
    assert not baseline.exists()


# --- a store made by compare --out renders ------------------------------------------------------
def test_report_renders_a_store_made_only_by_compare(tmp_path: Path, capsys) -> None:
    """The README's workflow: `compare --out DIR` then `report DIR`. The imported row has no run
    time: it is left off the time axes with a note saying so, never put at a time limit."""
    csv = family_csv(tmp_path / "mine.csv")
    store = tmp_path / "store"
    assert main(["compare", "slider_crank", str(csv), "--out", str(store)]) == 0
    capsys.readouterr()
    assert main(["report", str(store)]) == 0
    captured = capsys.readouterr()
    assert captured.err == "" and captured.out.strip() == f"report: {store / 'index.html'}"
    page = (store / "index.html").read_text()
    assert "Not on the time axes: mine on slider_crank (no run time" in page
    assert "no overview of error against run time: no timed run to draw" in page
    assert "no work-precision plot: no timed run to draw" in page
    assert 'aria-label="deviations"' in page  # the imported run against the truth, drawn over time
    assert "| mine |" in (store / "summary.md").read_text()


# --- the report escapes what it did not write ---------------------------------------------------
HOSTILE_NAME = 'q" onmouseover "alert(1)" x "<script>alert(3)<\\script>|$\\frac$'
"""Markup a scenario file's name may hold (a name is plain: no '/', '=', '[', ']' or ',', which
scenarios.names refuses where the name enters)."""
HOSTILE_LABEL = '"><img src=x onerror=alert(2)>|$x^$'


class PageParts(HTMLParser):
    """Every start tag, attribute and piece of text of a page, as a browser's tokenizer sees them."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[str] = []
        self.attributes: list[tuple[str, str | None]] = []
        self.text: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append(tag)
        self.attributes += attrs

    def handle_data(self, data: str) -> None:
        self.text.append(data)


@pytest.fixture(scope="module")
def hostile_store(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A store with a file scenario of a hostile name run on the native engine, and a trajectory
    imported under a hostile label, rendered."""
    folder = tmp_path_factory.mktemp("hostile")
    scenario = scenario_toml(scenarios.build("slider_crank", overrides={"steps": 40}))
    file = folder / "hostile.toml"
    file.write_text(scenario.replace('name = "slider_crank"', f"name = {json.dumps(HOSTILE_NAME)}", 1))
    store, csv = folder / "store", folder / "h.csv"
    quick = ["--engine", "reference", "--repeats", "1", "--warmup", "0", "--quiet"]
    assert main(["run", "--suite", "quick", "--scenario", str(file), "--out", str(store), *quick]) == 0
    assert main(["solve", str(file), "--out", str(csv)]) == 0
    assert main(["compare", str(file), str(csv), "--label", HOSTILE_LABEL, "--out", str(store)]) == 0
    assert main(["report", str(store)]) == 0
    return store


def test_a_hostile_name_and_label_render_as_text_in_the_page(hostile_store: Path) -> None:
    page = PageParts()
    page.feed((hostile_store / "index.html").read_text())
    assert page.tags.count("script") == 1  # the page's own plot check, nothing injected
    assert not [name for name, _ in page.attributes if name.startswith("on")]
    assert not [v for name, v in page.attributes if name == "x" and not re.fullmatch(r"-?[0-9.]+", v or "")]
    sources = [value or "" for name, value in page.attributes if name == "src"]
    assert page.tags.count("img") == len(sources) == 1  # the one image: the mechanism's drawing
    assert all(s.startswith("data:image/svg+xml;base64,") for s in sources)  # embedded, loaded from nowhere
    ids = [value or "" for name, value in page.attributes if name == "id"]
    hrefs = [value or "" for name, value in page.attributes if name == "href"]
    links = [href[1:] for href in hrefs if href.startswith("#")]
    section = [i for i in ids if i.startswith("s-")]
    assert len(section) == 1 and links == section  # the matrix's link finds its section
    assert all(c.isascii() and (c.isalnum() or c in "_-.~") for c in section[0])
    text = "".join(page.text)
    assert HOSTILE_NAME in text and HOSTILE_LABEL in text  # shown as written


def _as_markdown_text(value: str) -> str:
    """The hostile values' characters as Markdown text: backslash doubled, HTML escaped, pipe escaped."""
    return value.replace("\\", "\\\\").replace("<", "&lt;").replace(">", "&gt;").replace("|", "\\|")


def test_a_hostile_name_and_label_are_text_in_the_markdown_summary(hostile_store: Path) -> None:
    summary = (hostile_store / "summary.md").read_text()
    assert "<script" not in summary and "<img" not in summary
    heading = "## " + _as_markdown_text(HOSTILE_NAME)
    assert heading in summary.splitlines()
    label = _as_markdown_text(HOSTILE_LABEL)
    table_rows = [line for line in summary.splitlines() if "onerror" in line]
    assert len(table_rows) == 3  # the matrix's heading, the engines' reach and the scenario's table
    for line in table_rows:  # the label is one whole cell: its pipe does not split the row
        assert label in [cell.strip() for cell in re.split(r"(?<!\\)\|", line)]


def test_markup_boundary_escapes_what_lands_in_each_place() -> None:
    from reports.render import markup

    assert markup.escape('a"<b>&') == "a&quot;&lt;b&gt;&amp;"
    assert markup.anchor("four_bar/stress_toggle") == "s-four_bar-stress_toggle"  # old links still work
    assert markup.anchor('x" y') == "s-x~22~20y"
    assert markup.markdown_text("a|b<i>\nc") == "a\\|b&lt;i&gt; c"
    assert markup.markdown_text("`x` *y* [z](u) \\") == "\\`x\\` \\*y\\* \\[z\\](u) \\\\"
    assert markup.markdown_code("a``b") == "```a``b```" and markup.markdown_code("`a") == "`` `a ``"
    assert markup.figure_text("$x$") == "\\$x\\$"
