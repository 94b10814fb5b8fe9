"""Files named by a user or a pull request are read within bounds, through the real command line:
a FIFO, a device, a directory, an oversized or deeply nested file, a data path outside the scenario
file's folder: each is one error line, exit 2, at once, and never echoes the file's contents."""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

import pytest

import scenarios
from reports.cli.main import main
from scenarios.files import scenario_toml
from scenarios.files.bounded_read import MAX_SCENARIO_FILE_BYTES, FileRefused, inside, read_bounded_text

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "slider_crank.toml"
SECRET = "root:x:0:0:the contents of a private file"


def refused(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    """Run the command; it must end in one error line, exit 2, within a few seconds."""
    started = time.monotonic()
    assert main(argv) == 2
    assert time.monotonic() - started < 20
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err[:500]
    return err


@pytest.fixture
def fifo(tmp_path: Path) -> Path:
    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    return path


def test_a_fifo_as_scenario_file_never_blocks(capsys, fifo: Path) -> None:
    assert "a FIFO, not a regular file" in refused(capsys, ["solve", str(fifo)])


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_an_endless_device_is_refused_before_reading(capsys, device: str, tmp_path: Path) -> None:
    link = tmp_path / "device.toml"  # the reader is given a .toml name that is a device
    link.symlink_to(device)
    assert "character device" in refused(capsys, ["solve", str(link)])


def test_a_directory_is_refused(capsys, tmp_path: Path) -> None:
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    assert "a directory" in refused(capsys, ["solve", str(folder)])


def test_an_oversized_file_is_refused_by_its_size(capsys, tmp_path: Path) -> None:
    big = tmp_path / "big.toml"
    with big.open("wb") as stream:  # sparse: the size is checked before anything is read
        stream.truncate(MAX_SCENARIO_FILE_BYTES + 1)
    assert "MiB a scenario file may have" in refused(capsys, ["solve", str(big)])


def test_the_read_stops_at_the_limit(tmp_path: Path) -> None:
    path = tmp_path / "f.txt"
    path.write_text("x" * 100)
    assert read_bounded_text(path, 100, "file") == "x" * 100
    with pytest.raises(FileRefused, match="over"):
        read_bounded_text(path, 99, "file")


def test_deeply_nested_toml_is_one_line(capsys, tmp_path: Path) -> None:
    deep = tmp_path / "deep.toml"
    deep.write_text("x = " + "[" * 100_000 + "]" * 100_000 + "\n")
    assert "nested too deeply" in refused(capsys, ["solve", str(deep)])


def test_a_deeply_nested_set_value_is_one_line(capsys) -> None:
    value = "[" * 100_000 + "]" * 100_000
    assert "nested too deeply" in refused(capsys, ["solve", str(EXAMPLE), "--set", f"t_end={value}"])


def spline_file(folder: Path, csv: str) -> Path:
    """The spline cam exported, with its inline table replaced by `csv = ...`."""
    text = scenario_toml(scenarios.build("cam_roller/spline"))
    path = folder / "spline.toml"
    path.write_text(re.sub(r"table = \[[^\]]*\]", f"csv = {csv!r}".replace("'", '"'), text, count=1))
    return path


def test_a_profile_csv_beside_the_file_is_read(tmp_path: Path, capsys) -> None:
    radii = scenarios.build("cam_roller/spline").cams[0].profile.table  # type: ignore[attr-defined]
    (tmp_path / "radii.csv").write_text("r\n" + "\n".join(repr(r) for r in radii) + "\n")
    assert main(["solve", str(spline_file(tmp_path, "radii.csv")), "--steps", "4"]) == 0
    assert capsys.readouterr().out.startswith("t,")


def test_a_profile_csv_outside_the_folder_is_refused_unread(capsys, tmp_path: Path) -> None:
    secret = tmp_path / "secret.csv"
    secret.write_text(f"r\n{SECRET}\n")
    inner = tmp_path / "pr"
    inner.mkdir()
    err = refused(capsys, ["solve", str(spline_file(inner, "../secret.csv"))])
    assert "outside the scenario file's folder" in err and SECRET not in err


def test_a_link_to_a_file_outside_the_folder_is_refused(capsys, tmp_path: Path) -> None:
    secret = tmp_path / "secret.csv"
    secret.write_text(f"r\n{SECRET}\n")
    inner = tmp_path / "pr"
    inner.mkdir()
    (inner / "radii.csv").symlink_to(secret)
    err = refused(capsys, ["solve", str(spline_file(inner, "radii.csv"))])
    assert "outside the scenario file's folder" in err and SECRET not in err


def test_a_bad_line_in_a_profile_csv_is_named_not_echoed(capsys, tmp_path: Path) -> None:
    (tmp_path / "radii.csv").write_text(f"r\n0.05\n{SECRET}\n")
    err = refused(capsys, ["solve", str(spline_file(tmp_path, "radii.csv"))])
    assert "line 3: not a number" in err and SECRET not in err


def test_inside_keeps_paths_in_the_folder(tmp_path: Path) -> None:
    assert inside(tmp_path, "a/b.csv") == (tmp_path / "a" / "b.csv").resolve()
    with pytest.raises(FileRefused):
        inside(tmp_path, "/etc/passwd")


def test_a_fifo_as_compare_trajectory_never_blocks(capsys, fifo: Path) -> None:
    assert "a FIFO" in refused(capsys, ["compare", "slider_crank", str(fifo)])


@pytest.mark.parametrize(
    "text",
    [
        "[" * 100_000 + "]" * 100_000,
        '{"schema_version": 1, "cells": [{"error": 1' + "0" * 400 + "}]}",
        '{"schema_version": 1, "cells": [{"scenario": "s", "engine": "e", "setting": "", "status": "ok", '
        '"is_default": true, "message": "", "error_velocity": 1e-3, "error_acceleration": 1e-3, '
        '"error_position": 1' + "0" * 400 + ', "error": 1' + "0" * 400 + "}]}",
        '{"schema_version": 1, "cells": [{"error": 1' + "0" * 5000 + "}]}",
    ],
    ids=["nested", "huge-number", "huge-number-in-a-cell", "more-digits-than-python-converts"],
)
def test_a_hostile_baseline_is_one_line(capsys, tmp_path: Path, text: str) -> None:
    baseline = tmp_path / "baseline.json"
    baseline.write_text(text)
    err = refused(capsys, ["check", "--baseline", str(baseline), "--results", str(tmp_path / "none")])
    assert "baseline" in err


def test_a_fifo_as_baseline_never_blocks(capsys, fifo: Path, tmp_path: Path) -> None:
    assert "a FIFO" in refused(capsys, ["check", "--baseline", str(fifo), "--results", str(tmp_path)])
