"""Mutation testing, run the same way every time: mutmut over one module with only the tests that
concern it, in a scratch copy of the sources (so runs never collide with the work tree or each other).

    mbxval bench mutation [--module PATH ...] [--keep DIR]

Each module of MODULES is mutated alone against its own test files (`-m "not slow"`, `-x`), one
worker, under `nice -n 19`. The table gives mutants total / killed / survived / timeout and lists
every survivor, marked "explained" when EXPLAINED gives the reason it cannot or need not be killed
(docs/mutation.md keeps the counts and the reasons). Mutant names are mutmut's (function and
ordinal), stable for a given source and mutmut version, which pyproject pins.

The numba kernels (KERNEL_MODULES) are mutated as Python: mutmut skips decorated functions, and a
trampoline could not be compiled anyway. In the scratch copy their `@njit(...)` lines are removed and
the whole run has NUMBA_DISABLE_JIT=1, under which numba's njit returns the function itself: the
kernels run the very source numba compiles, as Python, with the same tests (those chosen to stay fast
uncompiled). Other modules run with the kernels compiled, their numba cache in the scratch copy
(NUMBA_CACHE_DIR), so no run reuses machine code compiled from other sources.

Each mutant's tests run in a process forked from mutmut's fork server, which has only collected the
tests (`process_isolation = "forkserver"`): mutmut's default forks from the process that ran the whole
selection for its statistics, whose caches (the fast path's compiled programs, lru_cache) then hand
every mutant the unmutated result, so a mutant of a function behind a cache never ran and "survived".
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = (
    "mbxval",
    "scenarios",
    "reference_solver",
    "adapters",
    "reports",
    "benchmarks",
    "tests",
    "examples",
)

CLOSED_FORM_TESTS = (
    "tests/scenarios/test_closed_form.py",
    "tests/scenarios/test_closed_form_edges.py",
    "tests/scenarios/test_four_bar_chain.py",
    "tests/scenarios/test_cam_linkage.py",
    "tests/reference_solver/test_closed_forms.py",
    "tests/reports/harness/test_truth.py",
)
"""The tests of the closed forms, which sit beside their families (Family.closed_form): mutating a
family module mutates its builder too, which these tests reach only through the native solver."""

PLAIN_PATH_TESTS = (
    "tests/reference_solver/test_analysis.py",
    "tests/reference_solver/test_newton.py",
    "tests/reference_solver/test_constraint_derivatives.py",
    "tests/reference_solver/test_compiled_system.py",
    "tests/reference_solver/test_failures.py",
    "tests/reference_solver/test_closed_forms.py",
    "tests/reference_solver/equations",
)
"""The tests of the plain path's building blocks (system, layout, mobility, factorization): each
imports or runs them without the compiled kernel (not yet run under mutation)."""

DYNAMICS = "tests/reference_solver/dynamics/"
FORCE_ELEMENT_TESTS = (
    f"{DYNAMICS}test_force_elements.py",
    "tests/reference_solver/test_fast_load_kernel.py",
)
DRIVEN_DYNAMICS_TESTS = (
    f"{DYNAMICS}test_inverse_dynamics.py",
    f"{DYNAMICS}test_pendulum.py",
    f"{DYNAMICS}test_energy.py",
)
"""The native dynamics' fast tests: the force elements against finite differences, inverse dynamics
against the rate of kinetic energy and a static torque, the pendulum's closed forms, energy balance."""
ALI3P_FAST_TESTS = (
    f"{DYNAMICS}test_ali3p.py::test_the_same_motion_as_the_partitioned_method_to_second_order[compound_pendulum]",
    f"{DYNAMICS}test_ali3p.py::test_the_same_motion_as_the_partitioned_method_to_second_order[four_bar_gravity]",
    f"{DYNAMICS}test_ali3p.py::test_constraints_hold_to_round_off_and_the_energy_balance_closes_to_second_order",
)
"""ALI3-P's cheaper tests (a few seconds each): two without force elements (P = M), one with a
spring and damper (P dense, with K and D)."""
KERNEL_TESTS = "tests/reference_solver/test_fast_path_kernels.py"
WHOLE_PATH_TESTS = "tests/reference_solver/test_fast_path.py"
COMPILED_SYSTEM_TESTS = "tests/reference_solver/test_compiled_system.py"
ROWS_TESTS = "tests/reference_solver/test_fast_constraint_rows.py"
STRUCTURE_TESTS = "tests/reference_solver/test_fast_structure.py"
FAST_PATH_TESTS = (KERNEL_TESTS, WHOLE_PATH_TESTS, COMPILED_SYSTEM_TESTS, ROWS_TESTS)
"""The fast path's tests: its kernels against dense algebra and LAPACK, the whole path against the
plain path to 1e-12 on every scenario, the compiled rows against the plain rows on random states.
Uncompiled, the whole-path tests take minutes per surviving mutant on the shared machine: the kernel
modules other than the loop are mutated against the others only, which check the same values."""

ALI3P_STEP_TESTS = (
    *ALI3P_FAST_TESTS,
    f"{DYNAMICS}test_ali3p.py::test_the_same_motion_as_the_partitioned_method_to_second_order[slider_crank_spring]",
    f"{DYNAMICS}test_ali3p.py::test_a_reduced_a02_passes_its_singular_position_at_second_order",
    f"{DYNAMICS}test_ali3p.py::test_unknown_method_and_bad_step_are_refused",
    f"{DYNAMICS}test_compiled_ali3p.py",
    f"{DYNAMICS}test_forward.py",
    *(
        f"{DYNAMICS}test_ali3p.py::test_{name}"
        for name in (
            "the_tangent_s_stiffness_and_damping_are_the_force_elements_derivatives",
            "a_step_of_a_linear_oscillator_is_the_trapezoidal_rule_s",
            "the_penalties_give_each_row_a_unit_penalty_diagonal",
            "a_step_newton_cannot_finish_is_refused_with_where_and_how_far",
            "a_rod_hanging_at_rest_carries_its_weight_at_the_pin",
            "the_step_is_the_same_in_any_unit_of_length",
            "a_chain_long_enough_for_the_banded_tangent_steps_as_with_the_dense_one",
            "the_rockers_leave_the_crank_by_what_the_step_s_phase_at_the_passage_allows",
            "a_driven_rod_s_rates_are_the_driver_s_after_the_projection",
            "a_chain_with_force_elements_keeps_its_tangent_dense",
        )
    ),
    f"{DYNAMICS}test_ali3p_grid.py",
)
"""ALI3-P's plain step (ali3p.py) and its grid (ali3p_grid.py): the cheaper tests above, the slider-crank
with a spring (the plain step: force elements do not compile), a reduced A02 through its singular
position, the refusals, the compiled step against the plain one, a free body falling, and the
plain step's and the grid's value tests (test_ali3p_grid.py, the hand-built cases of test_ali3p.py).
The rockers' phase test (plain and compiled over 8000 steps, 3 s each) is the one that reaches the
stalled Newton's stopping rule; the Andrews squeezer (20 s) is left out."""

PARTITIONED_TESTS = (
    f"{DYNAMICS}test_partition.py",
    f"{DYNAMICS}test_forward.py",
    f"{DYNAMICS}test_compiled_rates.py",
    f"{DYNAMICS}test_anchor.py",
    f"{DYNAMICS}test_pendulum.py",
    f"{DYNAMICS}test_energy.py",
)
"""The partitioned method's fast tests: its right-hand side against the compiled one and finite
differences, the anchor, a free fall, the pendulum's closed forms and the energy balance (short
integrations, seconds each), and the value tests of partition.py and forward.py."""

MODULES: dict[str, tuple[str, ...]] = {
    **dict.fromkeys(
        (
            "scenarios/closed_form.py",
            "scenarios/link_kinematics.py",
            "scenarios/families/slider_crank.py",
            "scenarios/families/four_bar.py",
            "scenarios/families/spur_gears.py",
            "scenarios/families/planetary_gears.py",
            "scenarios/families/rack_pinion.py",
            "scenarios/families/disc_cam.py",
            "scenarios/families/four_bar_chain.py",
        ),
        CLOSED_FORM_TESTS,
    ),
    "reports/harness/metrics.py": ("tests/reports/harness/test_metrics.py",),
    "reports/harness/level_error.py": ("tests/reports/harness/test_level_error.py",),
    "reference_solver/newton.py": (
        "tests/reference_solver/test_newton.py",
        "tests/reference_solver/test_failures.py",
        "tests/reference_solver/test_closed_forms.py",
    ),
    **dict.fromkeys(
        (
            "reference_solver/kinematic_vectors.py",
            "reference_solver/equations/joints.py",
            "reference_solver/equations/drivers.py",
            "reference_solver/equations/gears.py",
            "reference_solver/equations/cams.py",
        ),
        (
            "tests/reference_solver/test_constraint_derivatives.py",
            "tests/reference_solver/test_closed_forms.py",
            "tests/reference_solver/test_failures.py",
            "tests/reference_solver/equations",
        ),
    ),
    "reference_solver/analysis.py": (
        "tests/reference_solver/test_analysis.py",
        "tests/reference_solver/test_branch_guard.py",
        "tests/reference_solver/test_fast_path.py",
        "tests/reference_solver/test_failures.py",
        "tests/reference_solver/test_closed_forms.py",
    ),
    "reference_solver/system.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_system.py"),
    "reference_solver/mobility.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_mobility.py"),
    "reference_solver/layout.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_layout.py"),
    "reference_solver/factorization.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_factorization.py"),
    "reference_solver/residual.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_residual.py"),
    # --- native dynamics (session 8, s8-mut2) ---
    "reference_solver/dynamics/loads.py": (*FORCE_ELEMENT_TESTS, *DRIVEN_DYNAMICS_TESTS),
    "reference_solver/dynamics/mass.py": (f"{DYNAMICS}test_mass.py", *DRIVEN_DYNAMICS_TESTS),
    "reference_solver/dynamics/inverse.py": (f"{DYNAMICS}test_inverse_dynamics.py",),
    "reference_solver/dynamics/augmented.py": (
        f"{DYNAMICS}test_augmented.py",
        *DRIVEN_DYNAMICS_TESTS,
        f"{DYNAMICS}test_andrews.py",
    ),
    "reference_solver/dynamics/projection.py": (f"{DYNAMICS}test_projection.py", *ALI3P_FAST_TESTS),
    "reference_solver/dynamics/tangent.py": (f"{DYNAMICS}test_tangent.py", *ALI3P_FAST_TESTS),
    # --- end of native dynamics ---
    # ---- the compiled kinematic fast path (session 8, mut3) ----
    "reference_solver/fast/constraint_rows.py": FAST_PATH_TESTS,
    "reference_solver/fast/program.py": FAST_PATH_TESTS,
    "reference_solver/fast/structure.py": (*FAST_PATH_TESTS, STRUCTURE_TESTS),
    "reference_solver/fast/evaluate.py": (KERNEL_TESTS, COMPILED_SYSTEM_TESTS, ROWS_TESTS),
    "reference_solver/fast/band.py": (KERNEL_TESTS, STRUCTURE_TESTS),
    "reference_solver/fast/dense_lu.py": (KERNEL_TESTS,),
    "reference_solver/fast/loop.py": (KERNEL_TESTS, WHOLE_PATH_TESTS),
    "reference_solver/fast/path.py": (KERNEL_TESTS, WHOLE_PATH_TESTS),
    "reference_solver/fast/dense.py": (COMPILED_SYSTEM_TESTS,),
    "reference_solver/compiled_system.py": (COMPILED_SYSTEM_TESTS,),
    "reference_solver/equation.py": PLAIN_PATH_TESTS,
    "reference_solver/solution.py": (
        "tests/reference_solver/test_solution.py",
        "tests/reference_solver/test_analysis.py",
    ),
    "reference_solver/diagnostics.py": (
        "tests/reference_solver/test_diagnostics.py",
        "tests/reference_solver/test_mobility.py",
        "tests/reference_solver/test_failures.py",
    ),
    # --- ALI3-P's plain step and its grid (session 8, s8-mut5) ---
    "reference_solver/dynamics/ali3p_grid.py": ALI3P_STEP_TESTS,
    "reference_solver/dynamics/ali3p.py": ALI3P_STEP_TESTS,
    # --- end of ALI3-P ---
    # --- the partitioned method (session 8, s8-mut4) ---
    "reference_solver/dynamics/partition.py": PARTITIONED_TESTS,
    "reference_solver/dynamics/forward.py": PARTITIONED_TESTS,
    # --- end of the partitioned method ---
}

KERNEL_MODULES = frozenset(
    f"reference_solver/fast/{name}.py" for name in ("evaluate", "band", "dense_lu", "loop", "dense")
)
"""Modules of numba kernels, mutated as Python (NUMBA_DISABLE_JIT=1, their `@njit` lines removed)."""
NJIT_LINE = re.compile(r"^@njit\(.*\)\n", re.MULTILINE)

_STRICT_ZIP = "zip of two 2-tuples: strict or not, the pairs are the same"
_DTYPE = "the values are floats already: asarray(..., dtype=float) and asarray(...) are the same array"
_NEARBY = (
    "the nearby point's draw (seed None or 1, the sign, 1e-3 times, divided by or 1.001 times the "
    "columns' scales, a fourth try): the check needs a point off the singular set, and any such draw "
    "gives the structural rank; a duplicate, or a driver repeating a joint row, is dependent everywhere"
)
_LATER_REPORT = (
    "the later report of equal or lower rank kept: the loop stops at the first full-rank point, and a "
    "structurally dependent system has the same rank and dependent rows (rows repeating others "
    "everywhere) at every point"
)
_TANGENT = "reference_solver.dynamics.tangent.xǁTangentǁ"
EXPLAINED: dict[str, str] = {
    **dict.fromkeys(
        tuple(
            f"reference_solver.mobility.x__structural_report__mutmut_{k}" for k in (2, 3, 16, 21, 22, 23, 24)
        ),
        _NEARBY,
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.mobility.x__structural_report__mutmut_{k}" for k in (14, 36)),
        "C_q at t = 1 for t = 0: no constraint's Jacobian depends on time (a driver's time is in C, C_t)",
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.mobility.x__structural_report__mutmut_{k}" for k in (39, 40)),
        _LATER_REPORT,
    ),
    "reference_solver.mobility.x_check_mobility__mutmut_4": "include_drivers=None for False: the flag is "
    "only tested for truth",
    "reference_solver.mobility.x_check_mobility__mutmut_34": "over-driven if driver_rows >= dof: the branch "
    "runs only when driver_rows != dof, so the two comparisons agree there",
    "reports.harness.metrics.x_error_metrics__mutmut_25": _STRICT_ZIP,
    "reports.harness.metrics.x_error_metrics__mutmut_28": _STRICT_ZIP,
    "reports.harness.metrics.x_error_metrics__mutmut_29": _STRICT_ZIP,
    "reports.harness.metrics.x_residual_metrics__mutmut_4": _DTYPE
    + " (a residual is float; float() ends it)",
    "reports.harness.metrics.x_residual_metrics__mutmut_6": _DTYPE
    + " (a residual is float; float() ends it)",
    "reports.harness.level_error.x_level_series__mutmut_35": _DTYPE + " (fmax of float arrays)",
    "reports.harness.level_error.x_level_series__mutmut_37": _DTYPE + " (fmax of float arrays)",
    **dict.fromkeys(
        (
            "scenarios.link_kinematics.x_unit__mutmut_7",
            "scenarios.families.four_bar_chain.x_closed_form__mutmut_48",
            "scenarios.families.four_bar_chain.x_closed_form__mutmut_57",
        ),
        "stack(..., axis=-1) -> axis=+1: the angles are 1-D (one per grid time), so both axes are the last",
    ),
    "scenarios.families.four_bar_chain.x_closed_form__mutmut_108": (
        "a body's `turns` False -> None: it is only tested for truth, and None is false too"
    ),
    **dict.fromkeys(
        tuple(
            f"scenarios.families.disc_cam.x_disc_cam_closed_form__mutmut_{k}"
            for k in (135, 137, 138, 144, 145, 146, 147, 148)
        ),
        "the contact angle's 2 pi shift: its argument is pi/2 minus the contact point's polar angle, within "
        "pi/2 for a contact above the cam's axis (where the follower is), so round() and the shift are 0; "
        "these mutants scale the 0, or move the argument by less than pi/2",
    ),
    **dict.fromkeys(
        (
            "scenarios.families.four_bar.x_closed_form__mutmut_122",
            "scenarios.families.four_bar.x_closed_form__mutmut_123",
            "scenarios.families.slider_crank.x_closed_form__mutmut_39",
            "scenarios.families.slider_crank.x_closed_form__mutmut_46",
            "scenarios.families.disc_cam.x_disc_cam_closed_form__mutmut_154",
        ),
        "a term times the driver's angular acceleration, exactly 0: every closed form's driver turns at "
        "constant speed (link_kinematics.constant_speed), so the term is 0 whatever its sign, or a factor "
        "/ cos(theta) instead of * (cos of a float angle is never exactly 0)",
    ),
    "reference_solver.newton.x_newton__mutmut_6": "range(max_iterations + 2) for + 1: the loop breaks at "
    "iteration == max_iterations before it reaches the range's end, so the extra pass is never run",
    "reference_solver.newton.x__backtrack__mutmut_18": "a trial accepted when its scaled residual equals "
    "the current one (<= for <): differs only on an exact tie of two floating residuals, a step that is "
    "neither progress nor harm",
    **dict.fromkeys(
        ("reference_solver.newton.x_newton__mutmut_74", "reference_solver.newton.x_newton__mutmut_78"),
        "the empty step's branch (dx.size 0): a step is taken only after a factorization with rcond > 0, "
        "which an empty matrix never has (its rcond is 0 and the loop stops first): unreachable",
    ),
    **dict.fromkeys(
        (
            "reference_solver.kinematic_vectors.x_translate__mutmut_4",
            "reference_solver.kinematic_vectors.x_translate__mutmut_8",
        ),
        "translate's jac[0, col] += 1 and jac[1, col + 1] += 1 -> = 1: its two callers (body_point and a "
        "cam's profile point) pass a Jacobian filled only in the angle column col + 2 and the contact's phi "
        "column (after every body column), so those two entries are 0 before and 1 after either way",
    ),
    "reference_solver.analysis.x__singular__mutmut_33": "the message's 'unknown' (no dependent rows) -> "
    "'XXunknownXX': unreachable, rank_report names every row weighing > 0.1 in a unit singular vector, "
    "so at least one whenever C_q has fewer than 100 rows",
    "reference_solver.analysis.x__singular__mutmut_34": "the message's 'unknown' -> 'UNKNOWN': "
    "unreachable, as for _33",
    "reference_solver.analysis.x__approach__mutmut_2": "the first retaken step 2 (t1 - t0) instead of half "
    "of it: min/max clip it to t1, where Newton has just failed, so it fails again and is halved to the "
    "whole step, then to the half: two wasted solves, the same steps after",
    "reference_solver.analysis.x__approach__mutmut_25": "t1 >= t0 for t1 > t0 (which way to clip the "
    "step): differs only when t1 == t0, where h = 0 and the halving loop never runs",
    "reference_solver.analysis.x__approach__mutmut_5": "`last` starts as '' for None: it is only tested "
    "for truth, and '' is false too",
    "reference_solver.analysis.x__approach__mutmut_7": "the halving loop's bound >= for >: differs only "
    "when |h| equals 1e-12 max(|t1|, |t1 - t0|) exactly, and then by one more halving",
    "reference_solver.analysis.x__approach__mutmut_16": "the step resolution 1e-12 max(|t1|, |t1 + t0|) "
    "for |t1 - t0|: on a grid of times >= 0 (every scenario's) it is at most twice as coarse (one halving "
    "fewer), moving a stop time by about 1e-14 s, below what the stroke-end test can bound",
    "reference_solver.analysis.x__approach__mutmut_54": "rcond > SINGULAR_RCOND for >=: differs only "
    "on an exact tie of the rcond estimate with 1e-9",
    "reference_solver.analysis.x__approach__mutmut_85": "the step grows by 3 instead of 2 after a success: "
    "the answer at t1 is a converged Newton solution either way (the same to the tolerance) and the "
    "halvings still stop at the same resolution; only the number of solves changes",
    "reference_solver.factorization.x_factorize__mutmut_4": "warnings.simplefilter('ignore') without "
    "LinAlgWarning: the block holds lu_factor alone, whose only warning is LinAlgWarning",
    "reference_solver.factorization.x_factorize__mutmut_9": "lu_factor's check_finite False -> None: "
    "only tested for truth",
    **dict.fromkeys(
        (
            "reference_solver.factorization.x_factorize__mutmut_22",
            "reference_solver.factorization.x_factorize__mutmut_32",
        ),
        "dgecon also for a 1-norm of 0: only a zero matrix has it, whose pivots are 0, so rcond is set to 0 "
        "after anyway",
    ),
    **dict.fromkeys(
        (
            "reference_solver.factorization.x_factorize__mutmut_26",
            "reference_solver.factorization.x_factorize__mutmut_29",
        ),
        "dgecon's norm='1' dropped or None: scipy's wrapper defaults to the 1-norm",
    ),
    "reference_solver.factorization.x_factorize__mutmut_43": "the sign divided by (-1)^swaps instead of "
    "multiplied: (-1)^k is +1 or -1, its own reciprocal",
    **dict.fromkeys(
        (
            "reference_solver.factorization.x_factorize__mutmut_58",
            "reference_solver.factorization.x_factorize__mutmut_62",
        ),
        "the guard setting rcond 0 for a zero or non-finite pivot weakened: a NaN in the matrix makes its "
        "1-norm NaN, which `anorm > 0` already sends to 0, and this LAPACK's dgecon itself returns 0 for an "
        "exactly zero pivot and for an infinite one (checked on [[1e308, 1e308], [-1e308, 1e308]], whose "
        "second pivot overflows): the guard only protects against a LAPACK that would not",
    ),
    **dict.fromkeys(
        (
            "reference_solver.factorization.xǁFactorizationǁsolve__mutmut_3",
            "reference_solver.factorization.xǁFactorizationǁsolve__mutmut_6",
            "reference_solver.factorization.xǁFactorizationǁsolve__mutmut_7",
        ),
        "lu_solve's check_finite False -> None, default or True: differs only on non-finite input, and "
        "every caller solves with finite factors (rcond > 0 needs a finite diagonal) and a finite "
        "right-hand side (Newton returns on a non-finite residual before solving)",
    ),
    "reference_solver.analysis.x__approach__mutmut_99": "smallest <= NEAR_SINGULAR for <: differs only "
    "on an exact tie of the singular value ratio with 1e-4",
    # --- native dynamics (session 8, s8-mut2) ---
    **dict.fromkeys(
        (
            "reference_solver.dynamics.loads.xǁLoadsǁ__init____mutmut_16",
            "reference_solver.dynamics.loads.xǁLoadsǁ__init____mutmut_18",
            "reference_solver.dynamics.loads.xǁLoadsǁ_point__mutmut_3",
            "reference_solver.dynamics.loads.xǁLoadsǁ_point__mutmut_5",
            "reference_solver.dynamics.loads.xǁLoadsǁ_at_point__mutmut_9",
            "reference_solver.dynamics.loads.xǁLoadsǁ_at_point__mutmut_11",
        ),
        _DTYPE + " (gravity and a point's local coordinates are numbers: times a float mass, rotated, "
        "or subtracted from a float position they give the same floats; an integer ground point is "
        "only ever subtracted from or added to float arrays)",
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.dynamics.inverse.x_inverse_dynamics__mutmut_{k}" for k in (23, 28, 29)),
        "zip(times, q, qd, qdd, strict=True) -> None, dropped, False: the four arrays are one "
        "analysis's, one row per grid time, so they are never of different lengths",
    ),
    **dict.fromkeys(
        (
            *(f"reference_solver.dynamics.inverse.x_inverse_dynamics__mutmut_{k}" for k in (47, 50, 53)),
            *(
                f"reference_solver.dynamics.augmented.x_accelerations__mutmut_{k}"
                for k in (31, 33, 34, 38, 41, 44)
            ),
        ),
        "check_finite False -> None, default or True: differs only on a non-finite matrix or right-hand "
        "side, which no scenario gives (a spring of zero length would make Q_e NaN: NaN results from the "
        "original, a ValueError from the mutant)",
    ),
    "reference_solver.dynamics.augmented.x_accelerations__mutmut_12": "a zero row's norm set to 2 "
    "instead of 1: the row stays 0 whatever it is divided by, and the saddle-point matrix is singular "
    "either way (refused by LU's warning)",
    "reference_solver.dynamics.augmented.x_accelerations__mutmut_26": "warnings.simplefilter('error') "
    "without LinAlgWarning: the block holds lu_factor alone, whose only warning is LinAlgWarning",
    "reference_solver.dynamics.augmented.x_constraint_outputs__mutmut_48": "a joint's force taken over "
    "the columns x, y and theta instead of x and y: the third entry is computed and never read (fx and fy "
    "take entries 0 and 1)",
    **dict.fromkeys(
        tuple(f"reference_solver.dynamics.augmented.x_constraint_outputs__mutmut_{k}" for k in (6, 10)),
        "zip(constraints, equations, offsets, strict=False) -> None or dropped: the same as False (offsets "
        "has one entry more, the end, which the loop never needs)",
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.dynamics.augmented.x_constraint_outputs__mutmut_{k}" for k in (28, 31, 32)),
        "zip(labels, rows, strict=True) -> None, dropped, False: a driver's equation has one label per "
        "row by construction (equations/drivers.py)",
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.dynamics.projection.x_project__mutmut_{k}" for k in (43, 45, 46)),
        "the stopping rule's <= SETTLED, < STALLED, > 0.5 previous turned to <, <=, >=: differ only on an "
        "exact tie of a relative move with the bound (or with half the move before)",
    ),
    **dict.fromkeys(
        tuple(f"{_TANGENT}__init____mutmut_{k}" for k in (4, 7)),
        "zip(equations, offsets, strict=False) -> None or dropped: the same as False (offsets has one "
        "entry more, the end, which the loop never needs)",
    ),
    **dict.fromkeys(
        (
            *(f"{_TANGENT}__init____mutmut_{k}" for k in (11, 13)),
            f"{_TANGENT}factor__mutmut_28",
        ),
        _DTYPE + " (an equation's columns are ints, a bincount with weights is float64)",
    ),
    f"{_TANGENT}__init____mutmut_20": "meshgrid's indexing 'ij' -> default 'xy': for a grid of one vector "
    "with itself 'xy' is the transpose, so (first, second) runs over the same pairs in another order, "
    "and W is a sum over them",
    **dict.fromkeys(
        tuple(f"{_TANGENT}__init____mutmut_{k}" for k in (50, 59)),
        "first or second np.zeros(1) for a system without constraint rows: the rows' index stays empty, "
        "so the band's index (2w + first - second) n + second broadcasts to empty all the same",
    ),
    f"{_TANGENT}__init____mutmut_73": "n > BANDED_FROM for >=: differs only on a system of "
    "exactly 40 coordinates, and then only in which factorization solves W "
    "(both give W^-1 to round-off: the choice is speed)",
    f"{_TANGENT}__init____mutmut_76": "4 width < n for <=: differs only when n is exactly 4 "
    "times the half-bandwidth, and then only in which factorization solves W (both give W^-1 to round-off)",
    f"{_TANGENT}__init____mutmut_78": "factors start as '' for None: only `solve` reads them, "
    "after `factor` has set them (ALI3-P factors at each step's first Newton "
    "iteration, before its first solve)",
    **dict.fromkeys(
        (
            *(f"{_TANGENT}factor__mutmut_{k}" for k in (4, 6, 10)),
            *(f"{_TANGENT}solve__mutmut_{k}" for k in (5, 8, 9)),
        ),
        "check_finite False -> None, default or True: W (M plus the penalty term) and the residual are "
        "finite at any finite state; differs only on non-finite input, which no scenario gives",
    ),
    # --- end of native dynamics ---
    # ---- the compiled fast path (session 8, mut3) ----
    "reference_solver.fast.dense_lu.x_lu_solve_transposed__mutmut_16": "the L^T back substitution from "
    "row n - 2: row n - 1 has nothing right of its unit diagonal (j from n to n), so it is left as it is",
    "reference_solver.fast.dense_lu.x_lu_solve_transposed__mutmut_39": "the pivots undone from k = n - 2: "
    "piv[n - 1] is always n - 1 (the last column has one candidate row), so its swap does nothing",
    **dict.fromkeys(
        tuple(f"reference_solver.fast.band.x__signs__mutmut_{k}" for k in (1, 2, 13)),
        "the estimator's stop on a repeated sign vector (dlacn2's shortcut) never or always falsy: with "
        "the same signs the next iterate repeats the last one, so its estimate does not grow and the "
        "`estimate <= previous` stop ends the loop one step later with the same value",
    ),
    "reference_solver.fast.band.x__signs__mutmut_12": "the sign-vector stop taken when every sign "
    "flipped instead of none: the iteration then ends early with the current estimate; on the tests' "
    "matrices (random, scaled by 1e-3 to 1e3) no iterate flips every sign, and a matrix made to do so "
    "was not built",
    "reference_solver.fast.band.x_solve_transposed__mutmut_35": "the L^T solve from j = n - 2: row n - 1 "
    "has no multipliers below it (i from n on) and piv[n - 1] = n - 1, so that step changes nothing",
    **dict.fromkeys(
        (
            "reference_solver.fast.band.x__argmax_abs__mutmut_3",
            "reference_solver.fast.band.x__argmax_abs__mutmut_4",
        ),
        "the argmax's start (best -2 for -1, k 1 for 0): any |x_i| >= 0 beats -1 and -2 alike, so the "
        "first entry always replaces the start (a NaN iterate aside, which makes the estimate 0 anyway)",
    ),
    "reference_solver.fast.band.x__argmax_abs__mutmut_7": "the argmax takes the last of equal |x_i| (>=) "
    "instead of the first: differs only on an exact tie of two floating iterates",
    "reference_solver.fast.evaluate.x_radii__mutmut_50": "the bisection's middle (low + high + 2) // 2 for "
    "+ 1: still strictly above low and at most high while low < high, so it finds the same interval",
    "reference_solver.fast.evaluate.x_evaluate__mutmut_21": "the Jacobian written when the store has more "
    "than 1 entry instead of more than 0: a store is empty (no Jacobian asked) or holds at least 3 entries "
    "(every scenario has a body, 3 columns)",
    **dict.fromkeys(
        tuple(f"reference_solver.fast.path.x_compiled__mutmut_{k}" for k in (7, 8, 18, 23)),
        "a Compiled's layout or guess when it has no program, or its reason when it has one, set to None or "
        "'XXXX': run reads the layout and guess only with a program and the reason only without one",
    ),
    **dict.fromkeys(
        tuple(f"reference_solver.fast.evaluate.x__vectors__mutmut_{k}" for k in (133, 137, 143, 147)),
        "a profile term's second derivative read at us[contact, d - 2] for d + 2: d is 0 or 1 and the axis "
        "has 4 entries, so index -2 is 2 and -1 is 3 (Python and numba wrap negative indices alike)",
    ),
    **dict.fromkeys(
        ("reference_solver.fast.path.x_run__mutmut_14", "reference_solver.fast.path.x_run__mutmut_16"),
        "the grid made contiguous without dtype=float: differs only for an integer grid, and every caller "
        "passes Scenario.times() or an analysis' float grid",
    ),
    "reference_solver.fast.path.x_run__mutmut_2": "run's default max_iterations 26 for 25: every caller "
    "(analysis.solve through fast.analyse) passes its own",
    **dict.fromkeys(
        tuple(
            f"reference_solver.compiled_system.xǁCompiledSystemǁevaluate__mutmut_{k}" for k in (3, 5, 12, 14)
        ),
        "q or qd made contiguous without dtype=float: differs only for integer coordinates, and the "
        "integrator and Newton pass float arrays",
    ),
    "reference_solver.fast.evaluate.x__vectors__mutmut_4": "vectors A and B cleared over 7 entries for 6: "
    "the scratch rows are at least WIDTH = 10 long and entry 6 of a vector row is never read",
    "reference_solver.fast.band.x_rcond__mutmut_11": "the signs start at 1 instead of 0: the first call of "
    "_signs overwrites every one before any is read, and its answer (signs unchanged) is not used",
    **dict.fromkeys(
        ("reference_solver.fast.band.x_rcond__mutmut_59", "reference_solver.fast.band.x_rcond__mutmut_61"),
        "the estimator's iterations from 0 or 3 instead of 2 (up to 6 or 3 steps for dlacn2's 4): differs "
        "only on a matrix whose estimate still grows after 3 steps; every test matrix (random, scaled, "
        "identity) stops by itself within them, and one made to go on was not built",
    ),
    "reference_solver.fast.band.x_rcond__mutmut_62": "range(2, 7) for range(2, 6): the loop breaks at "
    "iteration 5 whatever happened (`or iteration == 5`), so 6 is never reached",
    "reference_solver.fast.band.x_rcond__mutmut_118": "`iteration == 6` for 5: the range ends after "
    "iteration 5 anyway, so the loop stops at the same point",
    "reference_solver.fast.band.x_rcond__mutmut_114": "the stop on a repeated column (x[last] == |x[j]|) "
    "dropped: the next step then solves for the same column, its estimate does not grow and "
    "`estimate <= previous` stops one step later with the same value (a tie of two columns aside)",
    "reference_solver.fast.band.x_rcond__mutmut_91": "estimate < previous for <=: differs only on an "
    "exact tie of two floating estimates",
    "reference_solver.fast.band.x_factor__mutmut_65": "the determinant's sign flipped for a pivot <= 0 "
    "instead of < 0: a zero pivot has returned 0 before, so the two agree on every pivot that gets there",
    "reference_solver.fast.band.x_rcond__mutmut_164": "the guard for a zero or non-finite estimate with "
    "`and`: an infinite estimate gives (1 / inf) / anorm = 0 all the same, and a zero or NaN one needs "
    "zero or NaN factors, which factor refuses (its caller then skips the estimate)",
    "reference_solver.diagnostics.x_rank_report__mutmut_25": "the zero matrix's top singular value 2 for "
    "1: any positive top gives it rank 0 and the ratio 0 / top = 0",
    **dict.fromkeys(
        (
            "reference_solver.diagnostics.x_rank_report__mutmut_45",
            "reference_solver.diagnostics.x_rank_report__mutmut_52",
        ),
        "the weights' branch for an empty `lost`: unreachable, `lost` holds at least the last column of U "
        "(rows > 0 there, the empty matrix returns first)",
    ),
    "reference_solver.diagnostics.x_rank_report__mutmut_56": "a row named for a weight >= 0.1 instead of > "
    "0.1: differs only on an exact tie of a singular vector's entry with 0.1",
}

# Session 8: the rest of analysis.py, system.py and residual.py.
_TIE = "differs only on an exact tie of two floats"
EXPLAINED.update(
    {
        "reference_solver.analysis.x_jumped__mutmut_18": "correction >= the threshold for >: " + _TIE,
        "reference_solver.analysis.x_assemble__mutmut_34": "a row named when it misses by >= 10 "
        "tolerances for >: " + _TIE,
        "reference_solver.analysis.x_analyse__mutmut_134": "rcond <= SINGULAR_RCOND for <: " + _TIE,
        "reference_solver.analysis.x_analyse__mutmut_161": "at a sign change of det C_q, the later point "
        "reported when the two rconds are equal (<= for <): " + _TIE,
        "reference_solver.analysis.x_analyse__mutmut_61": "the rates' start qd = qdd = zeros -> None: the "
        "first pass of the loop (k = 0) sets both from _rates before any step reads them",
        **dict.fromkeys(
            (
                "reference_solver.system.xǁConstraintSystemǁevaluate__mutmut_14",
                "reference_solver.system.xǁConstraintSystemǁevaluate__mutmut_17",
            ),
            "zip(equations, offsets, strict=False) -> strict=None or dropped: not strict either way (offsets "
            "has one entry more, the end, which is why it is not strict)",
        ),
        **dict.fromkeys(
            (
                "reference_solver.system.xǁConstraintSystemǁ__init____mutmut_26",
                "reference_solver.system.xǁConstraintSystemǁ__init____mutmut_28",
            ),
            "the row scales' dtype=float dropped or None: L**p of a float L is a float (and an integer L "
            "would give the same quotients)",
        ),
        "reference_solver.residual.x_constraint_residual__mutmut_7": "the compiled rows also tried for a "
        "scenario with cams: constraint_system gives it the plain system, which takes the plain branch",
        "reference_solver.residual.x_constraint_residual__mutmut_27": "q[: 4 n] for q[: 3 n] on the "
        "compiled path: a scenario that compiles has no cam contacts, so q has 3 n entries and both slices "
        "are all of it",
        **dict.fromkeys(
            (
                "reference_solver.residual.x_constraint_residual__mutmut_37",
                "reference_solver.residual.x_constraint_residual__mutmut_39",
            ),
            "max(..., initial=0.0) -> initial None or dropped: the compiled rows are never empty (a scenario "
            "without constraints does not compile: constraint_system gives it the plain system)",
        ),
        **dict.fromkeys(
            tuple(f"reference_solver.residual.x__plain_residual__mutmut_{k}" for k in (38, 41, 42)),
            "zip(equations, scales, strict=True) -> None, dropped or False: one scale array is built per "
            "equation, so the lists are as long",
        ),
    }
)

# Session 8 (s8-mut5): ALI3-P's plain step (ali3p.py) and its time grid (ali3p_grid.py).
_ALI3P = "reference_solver.dynamics.ali3p.xǁAli3pǁ"
_GRID = "reference_solver.dynamics.ali3p_grid.x_"
_FLOOR = (
    "the penalties' floor 1e-12 x the largest row inertia made an absolute 1e-12 (typical 1.0 for "
    "inertias below 1): it acts only on a row whose inertia (C_q M^-1 C_q^T)_ii is below 1e-12, a row of "
    "C_q that vanishes at the first predictor or masses above 1e12 kg (the families stop at 1e9)"
)
EXPLAINED.update(
    {
        f"{_GRID}integrate__mutmut_39": "the start's C_q set to None: never read (each step evaluates its "
        "own C_q, the interpolant takes q, q' and q'' only, and a step end's output is the stepped state)",
        f"{_GRID}integrate__mutmut_119": "fraction clipped at 2 instead of 1: it exceeds 1 only for an "
        "output time within SAME_TIME (1e-9 of a step) past a step's end, where the state is the step's "
        "either way and the work moves by that fraction of one step's work",
        f"{_GRID}integrate__mutmut_126": "fraction > 1 - SAME_TIME for >=: " + _TIE,
        f"{_ALI3P}_factor__mutmut_14": "einsum's subscripts 'ij,j,ij->i' in capitals: the same contraction",
        **dict.fromkeys(
            (f"{_ALI3P}_factor__mutmut_{k}" for k in (18, 24)),
            _FLOOR,
        ),
        f"{_ALI3P}_factor__mutmut_25": "typical = 2.0 for 1.0 when every row inertia is 0: only a system "
        "without rows (alpha empty either way) or with every row of C_q vanishing",
        f"{_ALI3P}multipliers__mutmut_23": "lstsq's rcond=None dropped: None is numpy 2's default",
        f"{_ALI3P}weigh__mutmut_2": "P x as weight @ x also without force elements: the weight is then "
        "diag(M), set in __init__ and changed only by _factor's stiff branch, so M x either way",
        **dict.fromkeys(
            (f"{_ALI3P}step__mutmut_{k}" for k in (107, 109, 110, 111)),
            "Newton's stopping rule's <=, <=, >, > turned to <, <, >=, >=: " + _TIE,
        ),
    }
)

# Session 8 (s8-mut4): the partitioned method, partition.py and forward.py.
_PARTITION = "reference_solver.dynamics.partition."
EXPLAINED.update(
    {
        f"{_PARTITION}xǁPartitionedǁconditioning__mutmut_5": "svd's compute_uv=False -> None: only "
        "tested for truth, and None is false too",
        **dict.fromkeys(
            (f"{_PARTITION}x_driver_power__mutmut_2", f"{_PARTITION}x_driver_power__mutmut_4"),
            "the drivers' power summed over every row, not the driver rows alone: the joints' rows add "
            "lambda_j C_q,j q', which is 0 to round-off (q' solves C_q q' = -C_t, and a joint's C_t is 0)",
        ),
        f"{_PARTITION}x_driver_power__mutmut_3": "slice(first driver row, None) for (first driver row, "
        "system.size): lambda and C_q have system.size rows, so both slices end at the last",
        **dict.fromkeys(
            tuple(
                f"{_PARTITION}xǁPartitionedǁpositions__mutmut_{k}"
                for k in (14, 17, 18, 37, 39, 40, 56, 59, 60)
            ),
            "check_finite False -> None, default or True (the predictor's lu_solve, Newton's lu_factor "
            "and lu_solve): differs only on a non-finite C_q, move or residual, which no finite state gives",
        ),
        **dict.fromkeys(
            (
                f"{_PARTITION}xǁPartitionedǁ__init____mutmut_9",
                f"{_PARTITION}xǁPartitionedǁ__init____mutmut_11",
            ),
            "the first C_q and C_t (zeros) -> None: they sit in Newton's start beside factors None, and "
            "positions reads them only with factors, which the first solve replaces them with",
        ),
        "reference_solver.dynamics.forward.x__walk__mutmut_5": "k <= len(step_times) for <: the last "
        "step is the integration's end, at or after every output, so the loop stops on the time test first",
        **dict.fromkeys(
            tuple(f"reference_solver.dynamics.forward.x__walk__mutmut_{k}" for k in (3, 6, 10, 11)),
            "the walk from the second step (k = 1), through a step at an output time (<=, the same point "
            "anchored twice), or skipping steps (k -= 1 stops at once, the last step time being the end; "
            "k += 2): only Newton's start moves, the states are Newton's solutions either way",
        ),
        "reference_solver.dynamics.forward.x__result__mutmut_17": "einsum's subscripts 'IJ,J,IJ->I' "
        "for 'ij,j,ij->i': the same contraction under other letters",
        f"{_PARTITION}x_choose_independent__mutmut_9": "qr's mode 'economic' dropped (mode 'full'): "
        "only R's and Q's shapes change; the column pivots are the same",
        f"{_PARTITION}xǁPartitionedǁpositions__mutmut_43": "residual <= STALLED for <: " + _TIE,
        f"{_PARTITION}xǁPartitionedǁpositions__mutmut_44": "residual >= 0.5 previous for >: " + _TIE,
        f"{_PARTITION}xǁPartitionedǁpositions__mutmut_49": "residual < RESIDUAL for <=: " + _TIE,
    }
)

KILLED, SURVIVED = 1, 0
TIMEOUTS = {-24, 24, 152}  # SIGXCPU, as mutmut reports a mutant that outran its time limit


@dataclass(frozen=True)
class Outcome:
    """The result of one module's mutation run."""

    module: str
    total: int
    killed: int
    timeout: int
    survivors: tuple[str, ...]
    other: int  # mostly 'no tests': no selected test runs the mutated function

    @property
    def unexplained(self) -> tuple[str, ...]:
        return tuple(name for name in self.survivors if name not in EXPLAINED)


def _scratch_copy(module: str, where: Path) -> None:
    """The sources and tests under `where`, with a mutmut configuration for `module` alone."""
    for package in PACKAGES:
        shutil.copytree(
            ROOT / package, where / package, ignore=shutil.ignore_patterns("__pycache__", "*.pyc")
        )
    config = (ROOT / "pyproject.toml").read_text()
    tests = ", ".join(json.dumps(t) for t in MODULES[module])
    also = ", ".join(json.dumps(p) for p in PACKAGES)
    config += (
        f'\n[tool.mutmut]\nsource_paths = ["{module}"]\npytest_add_cli_args_test_selection = [{tests}]\n'
        f"also_copy = [{also}]\n"
        'pytest_add_cli_args = ["-p", "no:cacheprovider", "-x", "-q", "-m", "not slow"]\n'
        'process_isolation = "forkserver"\n'
    )
    (where / "pyproject.toml").write_text(config)
    if module in KERNEL_MODULES:
        source = where / module
        source.write_text(NJIT_LINE.sub("", source.read_text()))


def _environment(module: str, where: Path) -> dict[str, str]:
    """No bytecode; numba's cache in the scratch copy, or numba off for a kernel module."""
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1", "NUMBA_CACHE_DIR": str(where / "numba-cache")}
    env.pop("NUMBA_DISABLE_JIT", None)
    if module in KERNEL_MODULES:
        env["NUMBA_DISABLE_JIT"] = "1"
    return env


def _outcome(module: str, where: Path) -> Outcome:
    meta = json.loads((where / "mutants" / f"{module}.meta").read_text())
    codes: dict[str, int | None] = meta["exit_code_by_key"]
    survivors = tuple(sorted(name for name, code in codes.items() if code == SURVIVED))
    killed = sum(code == KILLED for code in codes.values())
    timeout = sum(code in TIMEOUTS for code in codes.values())
    other = len(codes) - killed - timeout - len(survivors)
    return Outcome(module, len(codes), killed, timeout, survivors, other)


def run(module: str, keep: Path | None = None) -> Outcome:
    """Mutate `module` (a key of MODULES) in a scratch copy, one worker at the lowest priority."""
    if module not in MODULES:
        raise ValueError(f"no mutation setup for {module}: one of {', '.join(MODULES)}")
    mutmut = Path(sys.executable).with_name("mutmut")
    with tempfile.TemporaryDirectory(prefix="mbxval-mutation-") as scratch:
        where = keep if keep is not None else Path(scratch)
        where.mkdir(parents=True, exist_ok=True)
        _scratch_copy(module, where)
        env = _environment(module, where)
        subprocess.run(
            ["nice", "-n", "19", str(mutmut), "run", "--max-children", "1"],
            cwd=where,
            env=env,
            check=True,
            stdout=subprocess.DEVNULL,
        )
        return _outcome(module, where)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="mbxval bench mutation", description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--module",
        action="append",
        choices=sorted(MODULES),
        help="module to mutate (repeatable; default all)",
    )
    parser.add_argument(
        "--keep", type=Path, help="run in this directory and keep it (mutmut show works there)"
    )
    args = parser.parse_args(argv)
    print(f"{'module':<40} {'total':>6} {'killed':>7} {'survived':>9} {'timeout':>8} {'no tests':>9}")
    for module in args.module or list(MODULES):
        outcome = run(module, args.keep / module.replace("/", "_") if args.keep else None)
        print(
            f"{module:<40} {outcome.total:>6} {outcome.killed:>7} {len(outcome.survivors):>9} "
            f"{outcome.timeout:>8} {outcome.other:>9}"
        )
        for name in outcome.survivors:
            print(f"    survived {name}: {EXPLAINED.get(name, 'NOT EXPLAINED')}")


if __name__ == "__main__":
    main()
