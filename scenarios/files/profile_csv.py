"""Tabulated cam profiles kept in a CSV file beside the scenario file."""

from __future__ import annotations


def read_radii(text: str, source: str) -> list[float]:
    """The radii in a CSV file's `text`: one per line (the last comma-separated field), an optional
    header. ValueError says what is wrong with the line number (never the line: the file may be
    anything a pull request names)."""
    radii: list[float] = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        try:
            radii.append(float(line.split(",")[-1]))
        except ValueError:
            if radii or number > 1:
                raise ValueError(f"{source} line {number}: not a number") from None
    return radii
