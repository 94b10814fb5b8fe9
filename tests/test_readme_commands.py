"""Every `mbxval` command the README shows, run in order in a fresh directory as a newcomer would
(with the repository's examples beside it), exits 0. Commands are read from the README's code
blocks, fenced or indented, so the test follows the README as it is rewritten: a line starting with
`mbxval ` (a `$ ` prompt allowed, `\\` continuing it, a `# comment` after it dropped). Synopsis lines
(placeholders such as SCENARIO or DIR, `[optional]` parts, `a|b` choices, a description column)
are not commands and are left out; so are the few commands in SKIPPED, each with the test that
runs what it shows."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

SKIPPED = {
    "mbxval bench": "measurements, run on demand (tests/benchmarks run their quick forms)",
    "--workers": "200 points on a Dask cluster: minutes (tests/reports/run/test_dask_backend.py)",
}
GIVEN = {
    "my_tool.csv": ["solve", "slider_crank"],  # 'a trajectory made by any tool': the reader's own
}
"""Files the README takes the reader to have, made before the commands run."""


def _blocks(text: str) -> list[list[str]]:
    """The README's code blocks, fenced (```) or indented by four spaces, as lists of lines."""
    blocks: list[list[str]] = []
    fenced: list[str] | None = None
    indented: list[str] = []
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            if fenced is None:
                if indented:
                    blocks.append(indented)
                    indented = []
                fenced = []
            else:
                blocks.append(fenced)
                fenced = None
            continue
        if fenced is not None:
            fenced.append(line)
        elif line.startswith("    ") and line.strip():
            indented.append(line[4:])
        elif indented and not line.strip():
            continue
        elif indented:
            blocks.append(indented)
            indented = []
    if indented:
        blocks.append(indented)
    return blocks


def _is_synopsis(command: str) -> bool:
    """A usage line, not a command: a description column, a placeholder, an optional part, a choice."""
    if re.search(r"\S\s{3,}\S", command):
        return True
    words = command.split()
    return any(
        re.fullmatch(r"[A-Z][A-Z_]{2,}(\.[a-z]+)?(\.\.\.)?", word) or word.startswith("[") or "|" in word
        for word in words
    )


def readme_commands(text: str) -> list[str]:
    """The `mbxval` commands of the README's code blocks, in order, synopsis lines left out."""
    commands = []
    for block in _blocks(text):
        lines = iter(block)
        for line in lines:
            command = re.sub(r"^\s*\$\s+", "", line).strip()
            while command.endswith("\\"):
                command = command[:-1].rstrip() + " " + next(lines, "").strip()
            command = re.sub(r"\s+#.*$", "", command).strip()
            if command.startswith("mbxval ") and not _is_synopsis(command):
                commands.append(command)
    return commands


def test_the_reader_finds_commands_and_leaves_synopses_out() -> None:
    text = (
        "intro\n\n    mbxval solve slider_crank --out a.csv   # a comment\n"
        "    mbxval list [--stress]          what it does\n"
        "    mbxval check --baseline default|dynamics|FILE\n\n"
        "```bash\n$ mbxval run --scenario 'slider_crank[offset=0.05]' \\\n    --engine mujoco\n```\n"
        "    import mbxval\n"
    )
    assert readme_commands(text) == [
        "mbxval solve slider_crank --out a.csv",
        "mbxval run --scenario 'slider_crank[offset=0.05]' --engine mujoco",
    ]


def test_the_reader_parses_every_command_of_the_readme() -> None:
    """Fast: a command the shell could not split (an unclosed quote) fails here, not in the slow run."""
    commands = readme_commands((ROOT / "README.md").read_text())
    assert len(commands) >= 10, commands
    assert all(shlex.split(command)[0] == "mbxval" for command in commands)


def _run(argv: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "mbxval", *argv], cwd=cwd, env=env, capture_output=True, text=True, timeout=900
    )


@pytest.mark.slow
def test_every_command_in_the_readme_exits_0_in_order(tmp_path: Path) -> None:
    commands = readme_commands((ROOT / "README.md").read_text())
    assert len(commands) >= 10, commands  # the reader still finds the README's commands
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    for name, argv in GIVEN.items():
        assert _run([*argv, "--out", name], tmp_path).returncode == 0
    ran = []
    for command in commands:
        if any(marker in command for marker in SKIPPED):
            continue
        done = _run(shlex.split(command)[1:], tmp_path)
        assert done.returncode == 0, f"{command}: exit {done.returncode}\n{done.stderr[-2000:]}"
        ran.append(command)
    assert len(ran) >= 10, ran
