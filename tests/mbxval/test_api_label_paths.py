"""A label is a name, never a path: `compare` writes nothing anywhere for a DataFrame (the frame is
checked in memory by the CSV reader's own checks), and a label with a separator, `..`, a control
character, blank or over-long is refused before anything is read or written."""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path
from typing import ClassVar

import pytest

import mbxval
from scenarios.names import MAX_NAME_LENGTH

STEPS = 10


@pytest.fixture(scope="module")
def frame():  # type: ignore[no-untyped-def]
    return mbxval.solve("slider_crank", steps=STEPS)


def _files(root: Path) -> set[Path]:
    return {p for p in root.rglob("*")}


@pytest.mark.parametrize(
    "label",
    ["../../victim", "a/b", "a\\b", "..", ".hidden", "", "  ", "tab\there", "esc\x1b]0;x\x07", "x" * 101],
)
def test_a_label_that_is_not_a_plain_name_is_refused_and_writes_nothing(
    label: str, frame, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    inner = tmp_path / "a" / "b"
    inner.mkdir(parents=True)
    monkeypatch.setattr(tempfile, "tempdir", str(inner))  # where the reader once wrote `<label>.csv`
    with pytest.raises(mbxval.ArgumentError) as refused:
        mbxval.compare("slider_crank", frame, label=label, steps=STEPS)
    message = str(refused.value)
    assert "label" in message and "\n" not in message and "\x1b" not in message
    assert _files(tmp_path) == {tmp_path / "a", inner}  # no victim.csv, above or inside


def test_the_limit_is_stated_and_a_name_at_it_is_taken(frame) -> None:
    assert MAX_NAME_LENGTH == 100
    with pytest.raises(mbxval.ArgumentError, match=f"at most {MAX_NAME_LENGTH} characters"):
        mbxval.compare("slider_crank", frame, label="x" * (MAX_NAME_LENGTH + 1), steps=STEPS)
    row = mbxval.compare("slider_crank", frame, label="x" * MAX_NAME_LENGTH, steps=STEPS).iloc[0]
    assert row["engine"] == "x" * MAX_NAME_LENGTH


class Writes:
    """Every path made or opened for writing while `watching` (Python's audit events `open` and
    `os.mkdir`: pandas, tempfile and os alike), from one hook added for the process."""

    paths: ClassVar[list[str]] = []
    watching = False
    hooked = False

    @classmethod
    def hook(cls, event: str, args: tuple) -> None:  # type: ignore[type-arg]
        if not cls.watching:
            return
        if event == "os.mkdir":
            cls.paths.append(str(args[0]))
        elif event == "open" and args[0] is not None:
            mode, flags = args[1], args[2]
            if any(c in (mode or "") for c in "wax+") or flags & (os.O_WRONLY | os.O_RDWR | os.O_CREAT):
                cls.paths.append(str(args[0]))


def test_a_frame_is_scored_without_a_file_written(frame) -> None:  # type: ignore[no-untyped-def]
    if not Writes.hooked:
        sys.addaudithook(Writes.hook)
        Writes.hooked = True
    Writes.paths, Writes.watching = [], True
    try:
        row = mbxval.compare("slider_crank", frame, label="mine", steps=STEPS).iloc[0]
    finally:
        Writes.watching = False
    assert row["engine"] == "mine" and Writes.paths == []
    broken = frame.drop(columns=["rod.theta"])  # checked exactly as a file is
    with pytest.raises(
        mbxval.ArgumentError, match=r"^the trajectory DataFrame: body 'rod' has rod\.x, rod\.y"
    ):
        mbxval.compare("slider_crank", broken, label="mine", steps=STEPS)
