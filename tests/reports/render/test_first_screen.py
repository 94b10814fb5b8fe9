"""The first screen's one line on the native solver and its matrix cells, on hand-made rows."""

from __future__ import annotations

import math

import pandas as pd

from reports.render.first_screen import matrix_cells, native_line


def row(scenario: str, truth: str, status: str, errors: tuple[float, float, float]) -> dict[str, object]:
    return {
        "scenario": scenario, "engine": "reference", "is_default": True, "truth": truth, "status": status,
        "setting": "newton tolerance=1e-12", "message": "",
        "error_position": errors[0], "error_velocity": errors[1], "error_acceleration": errors[2],
    }  # fmt: skip


def test_the_native_line_names_the_worst_error_per_level_and_the_other_truths() -> None:
    frame = pd.DataFrame(
        [
            row("a", "closed form", "ok", (1e-15, 4e-14, 2e-13)),
            row("b", "closed form", "ok", (3e-15, 1e-14, 5e-13)),
            row("c", "native, tolerance 1e-12, grid refined 4x", "ok", (1e-3, 1e-3, 1e-3)),
        ]
    )
    line = native_line(frame, "reference")
    assert "on 2 scenarios" in line
    assert "position 3.00e-15 (b)" in line and "velocity 4.00e-14 (a)" in line
    assert "acceleration 5.00e-13 (b)" in line
    assert "1.00e-03" not in line  # the scenario without a closed form is not scored here
    assert "1 scenario(s) have no closed form" in line


def test_matrix_cells_show_status_and_leave_a_missing_level_out() -> None:
    cells = matrix_cells(pd.Series(row("a", "closed form", "ok", (1e-15, 2e-6, math.nan))))
    assert len(cells) == 4 and "2e-06" in cells[1] and "level not produced" in cells[2]
    assert "no forces reported" in cells[3]  # the row has no error_force
    failed = matrix_cells(pd.Series(row("a", "closed form", "diverged", (math.nan,) * 3)))
    assert failed == [failed[0]] and 'colspan="4"' in failed[0] and ">diverged<" in failed[0]


def test_the_force_column_shows_the_force_error() -> None:
    forces = pd.Series({**row("a", "closed form", "ok", (1e-15, 2e-6, 3e-4)), "error_force": 8e-5})
    cells = matrix_cells(forces)
    assert 'class="force"' in cells[3] and "8e-05" in cells[3]


def test_a_store_that_does_not_record_the_native_engine_says_so() -> None:
    frame = pd.DataFrame([row("a", "closed form", "ok", (1e-15, 4e-14, 2e-13))])
    assert "not recorded" in native_line(frame, "")
