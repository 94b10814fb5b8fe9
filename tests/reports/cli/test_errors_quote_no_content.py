"""An error about a file names the file, the line and column (or the key) and what was expected,
never what the file says: a user may point `compare` at any file, and its error lands in a
terminal or a public CI log. Checked with files that hold a secret in every place a reader could
quote it: the header, a cell, a scenario file's values."""

from __future__ import annotations

from pathlib import Path

import pytest

import mbxval
from reports.cli.main import main

SECRET = "hunter2"
SHADOW = f"root:$6${SECRET}$abc:19000:0:99999:7:::\ndaemon:*:{SECRET}:0:99999:7:::\n"
"""The form of /etc/shadow (which this test cannot count on reading)."""

CSV_FILES = {
    "shadow": (SHADOW, "line 1, column 1: not a column name of slider_crank"),
    "password header": (f"password={SECRET}\nfoo\n", "line 1, column 1: not a column name"),
    "password cell": (
        f"t,crank.x,crank.y,crank.theta\n0,password={SECRET},0,0\n",
        "line 2, column 2: not a number; expected a finite number",
    ),
    "after a blank line": (
        f"t,crank.x,crank.y,crank.theta\n0,0,0,0\n\n0.1,{SECRET},0,0\n",
        "line 4, column 2: not a number",
    ),
    "not finite": (
        "t,crank.x,crank.y,crank.theta\n0,nan,0,0\n",
        "line 2, column 2: not finite",
    ),
    "empty cell": ("t,crank.x,crank.y,crank.theta\n0,,0,0\n", "line 2, column 2: empty"),
}


@pytest.mark.parametrize("case", CSV_FILES)
def test_compare_names_the_place_not_the_content(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text, expected = CSV_FILES[case]
    path = tmp_path / "secret.csv"
    path.write_text(text)
    assert main(["compare", "slider_crank", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"mbxval: error: {path}: {expected}") and err.count("\n") == 1, err
    said = err.replace(str(path), "FILE")
    assert SECRET not in said and "root" not in said and "password" not in said
    with pytest.raises(mbxval.ArgumentError) as raised:  # the API: the same message
        mbxval.compare("slider_crank", path)
    assert str(raised.value) == err.removeprefix("mbxval: error: ").rstrip("\n")


def test_a_scenario_file_is_named_by_key_not_quoted(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = (Path(__file__).resolve().parents[3] / "examples" / "slider_crank.toml").read_text()
    edits = {
        'description = "slider-crank driven by the crank"': f"description = {{ password = '{SECRET}' }}",
        'p_j = { body = "crank", local = [-0.1, 0.0] }': f'p_j = {{ body = "{SECRET}", local = [0.1, 0] }}',
        'kind = "revolute"': f'kind = "{SECRET}"',
        "steps = 200": f'steps = "{SECRET}"',
        'name = "rod"': f'name = ["{SECRET}"]',
    }
    for old, new in edits.items():
        assert old in source
        path = tmp_path / "s.toml"
        path.write_text(source.replace(old, new, 1))
        assert main(["solve", str(path)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"mbxval: error: {path}: ") and err.count("\n") == 1, err
        assert SECRET not in err, err
