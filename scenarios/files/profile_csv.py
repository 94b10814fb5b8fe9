"""Tabulated cam profiles kept in a CSV file beside the scenario file."""

from __future__ import annotations

from pathlib import Path


def read_radii(file: Path) -> list[float]:
    """The radii in `file`: one per line (the last comma-separated field), an optional header.

    ValueError says what is wrong, with the line number; OSError if the file cannot be read.
    """
    radii: list[float] = []
    for number, line in enumerate(file.read_text().splitlines(), start=1):
        if not line.strip():
            continue
        try:
            radii.append(float(line.split(",")[-1]))
        except ValueError:
            if radii or number > 1:
                raise ValueError(f"{file} line {number}: not a number: {line.strip()!r}") from None
    return radii
