"""Mutation testing, run the same way every time: mutmut over one module with only the tests that
concern it, in a scratch copy of the sources (so runs never collide with the work tree or each other).

    mbxval bench mutation [--module PATH ...] [--keep DIR]

Each module of MODULES is mutated alone against its own test files (`-m "not slow"`, `-x`), one
worker, under `nice -n 19`. The table gives mutants total / killed / survived / timeout and lists
every survivor, marked "explained" when benchmarks/mutation_explained/ gives the reason it cannot or need
not be killed (docs/mutation.md keeps the counts and the reasons). Mutant names are mutmut's (function and
ordinal), stable for a given source and mutmut version, which pyproject pins.

The numba kernels (KERNEL_MODULES) are mutated as Python: mutmut skips decorated functions, and a
trampoline could not be compiled anyway. In the scratch copy their `@njit(...)` lines are removed and
the whole run has NUMBA_DISABLE_JIT=1, under which numba's njit returns the function itself: the
kernels run the very source numba compiles, as Python, with the same tests (those chosen to stay fast
uncompiled). Other modules run with the kernels compiled, their numba cache in the scratch copy
(NUMBA_CACHE_DIR), so no run reuses machine code compiled from other sources.

Each mutant's tests run in a process forked from mutmut's fork server, which has only collected the
tests (`process_isolation = "forkserver"`): mutmut's default forks from the process that ran the whole
selection for its statistics, whose caches (the compiled path's compiled programs, lru_cache) then hand
every mutant the unmutated result, so a mutant of a function behind a cache never ran and "survived".
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from benchmarks.mutation_results import explained

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
    "tests/reports/scoring/test_truth.py",
    "tests/scenarios/families",
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
    "tests/reference_solver/compiled/test_load_kernel.py",
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
KERNEL_TESTS = "tests/reference_solver/compiled/test_kernels.py"
WHOLE_PATH_TESTS = "tests/reference_solver/compiled/test_path.py"
COMPILED_SYSTEM_TESTS = "tests/reference_solver/test_compiled_system.py"
ROWS_TESTS = "tests/reference_solver/compiled/test_constraint_rows.py"
STRUCTURE_TESTS = "tests/reference_solver/compiled/test_structure.py"
FAST_PATH_TESTS = (KERNEL_TESTS, WHOLE_PATH_TESTS, COMPILED_SYSTEM_TESTS, ROWS_TESTS)
"""The compiled path's tests: its kernels against dense algebra and LAPACK, the whole path against the
plain path to 1e-12 on every scenario, the compiled rows against the plain rows on random states.
Uncompiled, the whole-path tests take minutes per surviving mutant on the shared machine: the kernel
modules other than the loop are mutated against the others only, which check the same values."""

RESIDUAL_TESTS = tuple(
    f"tests/reference_solver/test_residual{suffix}.py" for suffix in ("", "_cams", "_nan", "_reach")
)
"""The constraint residual's tests: compiled against plain rows on random states and solutions, cam
contacts with and without their parameter, NaN coordinates, two contacts and an 81-body chain."""

LOOP_MUTANT_TESTS = "tests/reference_solver/compiled/test_loop_events.py"
LOOP_TESTS = (
    LOOP_MUTANT_TESTS,
    KERNEL_TESTS,
    *(
        f"{WHOLE_PATH_TESTS}::test_{name}"
        for name in (
            "fast_path_gives_the_plain_answer[cam_roller/spline]",
            "fast_path_gives_the_plain_answer[planetary_gears]",
            "looser_tolerance_gives_the_plain_answer_too",
        )
    ),
    "tests/reference_solver/test_branch_guard.py::test_the_kernel_hands_a_jump_to_the_plain_path",
)
"""The kernel loop uncompiled (a kernel module): the hand-worked crank through the kernel and each of
its events (compiled/test_loop_events.py, quick uncompiled), two catalogue scenarios against the plain
path (a spline cam's profile points, a planetary train), a looser tolerance, and a branch jump. Left
out: the rest of the catalogue, the singular cases of compiled/test_path.py (they run the plain path's
diagnosis, seconds each uncompiled) and its iteration-limit test (minutes uncompiled)."""

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
    f"{DYNAMICS}test_partition_stall.py",
    f"{DYNAMICS}test_forward.py",
    f"{DYNAMICS}test_compiled_rates.py",
    f"{DYNAMICS}test_anchor.py",
    f"{DYNAMICS}test_pendulum.py",
    f"{DYNAMICS}test_energy.py",
)
"""The partitioned method's fast tests: its right-hand side against the compiled one and finite
differences, the anchor, a free fall, the pendulum's closed forms and the energy balance (short
integrations, seconds each), and the value tests of partition.py and forward.py (the stall rule on a four-bar
moved 10 m off the origin)."""

COMPILED_RATES_TESTS = (
    f"{DYNAMICS}test_compiled_rates.py",
    f"{DYNAMICS}test_anchor.py",
    f"{DYNAMICS}test_compiled_rates_fallbacks.py",
)
"""The compiled partitioned right-hand side (dynamics.compiled_rates over compiled.rates): against the
plain one and finite differences on random states, the anchor, and its own value tests."""
RATES_KERNEL_TESTS = (
    f"{DYNAMICS}test_compiled_rates.py::test_compiled_right_hand_side_is_the_plain_one_on_random_states",
    f"{DYNAMICS}test_compiled_rates.py::test_compiled_rates_are_the_derivatives_of_the_compiled_positions",
    f"{DYNAMICS}test_compiled_rates.py::test_compiled_conditioning_is_the_plain_one",
    f"{DYNAMICS}test_anchor.py::test_a_far_trial_stage_leaves_the_next_right_hand_side_unchanged",
    f"{DYNAMICS}test_compiled_rates_fallbacks.py",
    "tests/reference_solver/compiled/test_rates.py",
)
"""compiled.rates' kernels uncompiled: the compiled right-hand side, state and conditioning against the
plain path's on random states, its rates against finite differences of its positions, the anchor,
and the value tests; about 15 s as Python. No integration: Radau's comparison alone takes 21 s
uncompiled, the energy balance at rtol 1e-6 longer."""
LOAD_KERNEL_TESTS = (*FORCE_ELEMENT_TESTS, "tests/reference_solver/compiled/test_load_program.py")
"""The compiled force elements against the plain ones (themselves against finite differences)."""

MUJOCO_TESTS = (
    "tests/adapters/mujoco/test_adapter.py",
    "tests/adapters/mujoco/test_compile.py",
    "tests/adapters/mujoco/test_simulation.py",
    "tests/adapters/mujoco/test_tree.py",
)
EXUDYN_TESTS = ("tests/adapters/exudyn/test_adapter.py", "tests/adapters/exudyn/test_simulation.py")
PINOCCHIO_TESTS = (
    "tests/adapters/pinocchio/test_adapter.py",
    "tests/adapters/pinocchio/test_branch.py",
    "tests/adapters/pinocchio/test_kinematics.py",
    "tests/adapters/pinocchio/test_model.py",
)
"""Each engine's builder (its model from a scenario) and reader (the trajectory from its state) are
mutated against the engine's adapter tests: every catalogue scenario it runs against its truth."""

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
    "reports/scoring/metrics.py": ("tests/reports/scoring/test_metrics.py",),
    "reports/scoring/level_error.py": ("tests/reports/scoring/test_level_error.py",),
    "reference_solver/newton.py": (
        "tests/reference_solver/test_newton.py",
        "tests/reference_solver/test_newton_round_off.py",
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
        "tests/reference_solver/test_assemble_singular_refusal.py",
        "tests/reference_solver/test_assemble_round_off_refusal.py",
        "tests/reference_solver/test_branch_guard.py",
        "tests/reference_solver/compiled/test_path.py",
        "tests/reference_solver/test_failures.py",
        "tests/reference_solver/test_closed_forms.py",
    ),
    "reference_solver/system.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_system.py"),
    "reference_solver/mobility.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_mobility.py"),
    "reference_solver/layout.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_layout.py"),
    "reference_solver/factorization.py": (*PLAIN_PATH_TESTS, "tests/reference_solver/test_factorization.py"),
    "reference_solver/residual.py": (*PLAIN_PATH_TESTS, *RESIDUAL_TESTS),
    # --- native dynamics ---
    "reference_solver/dynamics/loads.py": (*FORCE_ELEMENT_TESTS, *DRIVEN_DYNAMICS_TESTS),
    "reference_solver/dynamics/mass.py": (f"{DYNAMICS}test_mass.py", *DRIVEN_DYNAMICS_TESTS),
    "reference_solver/dynamics/inverse.py": (
        f"{DYNAMICS}test_inverse_dynamics.py",
        f"{DYNAMICS}test_compiled_inverse.py",
    ),
    "reference_solver/dynamics/compiled_inverse.py": (f"{DYNAMICS}test_compiled_inverse.py",),
    "reference_solver/compiled/inverse_kernel.py": (f"{DYNAMICS}test_compiled_inverse.py",),
    "reference_solver/dynamics/partition_passage.py": (f"{DYNAMICS}test_partition_passage.py",),
    "reference_solver/dynamics/augmented.py": (
        f"{DYNAMICS}test_augmented.py",
        *DRIVEN_DYNAMICS_TESTS,
        f"{DYNAMICS}test_andrews.py",
    ),
    "reference_solver/dynamics/projection.py": (f"{DYNAMICS}test_projection.py", *ALI3P_FAST_TESTS),
    "reference_solver/dynamics/tangent.py": (f"{DYNAMICS}test_tangent.py", *ALI3P_FAST_TESTS),
    # --- end of native dynamics ---
    # ---- the compiled kinematic compiled path ----
    "reference_solver/compiled/constraint_rows.py": FAST_PATH_TESTS,
    "reference_solver/compiled/program.py": (
        "tests/reference_solver/compiled/test_program_parts.py",
        "tests/reference_solver/compiled/test_program_instructions.py",
        *FAST_PATH_TESTS,
    ),
    "reference_solver/compiled/structure.py": (
        STRUCTURE_TESTS,
        "tests/reference_solver/compiled/test_structure_edges.py",
        KERNEL_TESTS,
        ROWS_TESTS,
    ),
    "reference_solver/compiled/evaluate.py": (
        KERNEL_TESTS,
        COMPILED_SYSTEM_TESTS,
        ROWS_TESTS,
        f"{DYNAMICS}test_ali3p_offset.py::test_the_compiled_rows_lose_nothing_to_the_coordinates_size",
    ),
    "reference_solver/compiled/band.py": (
        KERNEL_TESTS,
        STRUCTURE_TESTS,
        "tests/reference_solver/compiled/test_band_rcond.py",
    ),
    "reference_solver/compiled/dense_lu.py": (KERNEL_TESTS,),
    "reference_solver/compiled/loop.py": (
        *LOOP_TESTS,
        "tests/reference_solver/compiled/test_loop_margins.py",
        "tests/reference_solver/compiled/test_loop_singular_after_convergence.py",
    ),
    "reference_solver/compiled/path.py": (LOOP_MUTANT_TESTS, KERNEL_TESTS, WHOLE_PATH_TESTS),
    "reference_solver/compiled/dense.py": (
        "tests/reference_solver/compiled/test_dense.py",
        COMPILED_SYSTEM_TESTS,
    ),
    "reference_solver/compiled/residuals.py": RESIDUAL_TESTS,
    "reference_solver/compiled_system.py": (COMPILED_SYSTEM_TESTS,),
    "reference_solver/equation.py": (
        *PLAIN_PATH_TESTS,
        "tests/reference_solver/test_equation_ground_rows.py",
    ),
    "reference_solver/solution.py": (
        "tests/reference_solver/test_solution.py",
        "tests/reference_solver/test_analysis.py",
    ),
    "reference_solver/diagnostics.py": (
        "tests/reference_solver/test_diagnostics.py",
        "tests/reference_solver/test_mobility.py",
        "tests/reference_solver/test_failures.py",
    ),
    # --- ALI3-P's plain step and its grid ---
    "reference_solver/dynamics/ali3p_grid.py": (
        *ALI3P_STEP_TESTS,
        f"{DYNAMICS}test_ali3p_schedule.py",  # the watch's and the placement's use
    ),
    "reference_solver/dynamics/ali3p.py": ALI3P_STEP_TESTS,
    # --- end of ALI3-P ---
    # --- the partitioned method ---
    "reference_solver/dynamics/partition.py": PARTITIONED_TESTS,
    "reference_solver/dynamics/forward.py": (
        *PARTITIONED_TESTS,
        f"{DYNAMICS}test_forward_repartition.py",
        f"{DYNAMICS}test_forward_termination.py",
    ),
    # --- end of the partitioned method ---
    # --- the compiled partitioned right-hand side and its support ---
    "reference_solver/dynamics/compiled_rates.py": COMPILED_RATES_TESTS,
    "reference_solver/compiled/rates.py": (
        *RATES_KERNEL_TESTS,
        "tests/reference_solver/compiled/test_rates_stall.py",
    ),
    "reference_solver/compiled/load_kernel.py": LOAD_KERNEL_TESTS,
    "reference_solver/compiled/load_program.py": LOAD_KERNEL_TESTS,
    "scenarios/kept.py": (
        f"{WHOLE_PATH_TESTS}::test_an_empty_grid_and_an_unhashable_scenario",
        "tests/scenarios/test_kept.py",
    ),
    "reference_solver/compiled/cache_guard.py": (
        f"{KERNEL_TESTS}::test_cache_guard_drops_machine_code_of_changed_sources",
        "tests/reference_solver/compiled/test_cache_guard.py",
    ),
    "reference_solver/errors.py": (
        "tests/reference_solver/test_failures.py",
        "tests/reference_solver/test_errors.py",
    ),
    # --- end of the compiled partitioned right-hand side ---
    # --- ALI3-P's compiled step ---
    "reference_solver/compiled/ali3p_matrix.py": (
        "tests/reference_solver/compiled/test_ali3p_matrix.py",
        f"{DYNAMICS}test_compiled_ali3p.py",
    ),
    "reference_solver/dynamics/compiled_ali3p.py": (
        f"{DYNAMICS}test_compiled_ali3p_run.py",
        f"{DYNAMICS}test_compiled_ali3p.py",
        f"{DYNAMICS}test_ali3p_offset.py",
    ),
    "reference_solver/compiled/ali3p_kernel.py": (
        f"{DYNAMICS}test_compiled_ali3p_run.py",
        f"{DYNAMICS}test_compiled_ali3p.py",
        "tests/reference_solver/compiled/test_ali3p_kernel_near_singular.py",
        "tests/reference_solver/compiled/test_ali3p_kernel_careful_steps.py",
    ),
    # --- end of ALI3-P's compiled step ---
    # --- ALI3-P's singular passages ---
    "reference_solver/dynamics/passage.py": (
        f"{DYNAMICS}test_passage.py",
        f"{DYNAMICS}test_passage_readings.py",
    ),
    "reference_solver/dynamics/ali3p_schedule.py": (
        f"{DYNAMICS}test_passage.py",
        f"{DYNAMICS}test_ali3p_grid.py",
        f"{DYNAMICS}test_ali3p_schedule.py",
    ),
    # --- end of ALI3-P's singular passages ---
    # --- the engines' builders and readers, the profiles and laws, the scoring (issue 41) ---
    "scenarios/cam_profiles.py": (
        "tests/scenarios/test_derivatives_by_finite_differences.py",
        "tests/scenarios/test_cam_profiles.py",
        "tests/reference_solver/equations/test_cams.py",
    ),
    "scenarios/motion_laws.py": (
        "tests/scenarios/test_derivatives_by_finite_differences.py",
        "tests/scenarios/test_motion_laws.py",
    ),
    "reports/scoring/agreement.py": ("tests/reports/scoring/test_agreement.py",),
    "reports/scoring/energy_drift.py": (
        "tests/reports/scoring/test_energy_drift.py",
        "tests/reports/scoring/test_energy_balance.py",
    ),
    "reports/scoring/self_check.py": ("tests/reports/scoring/test_self_check.py",),
    **dict.fromkeys(("adapters/mujoco/tree.py", "adapters/mujoco/simulation.py"), MUJOCO_TESTS),
    **dict.fromkeys(("adapters/exudyn/model.py", "adapters/exudyn/simulation.py"), EXUDYN_TESTS),
    **dict.fromkeys(("adapters/pinocchio/model.py", "adapters/pinocchio/kinematics.py"), PINOCCHIO_TESTS),
}

KERNEL_MODULES = frozenset(
    f"reference_solver/compiled/{name}.py"
    for name in (
        "evaluate",
        "band",
        "dense_lu",
        "loop",
        "dense",
        "rates",
        "load_kernel",
        "ali3p_matrix",
        "ali3p_kernel",
        "residuals",
    )
)
"""Modules of numba kernels, mutated as Python (NUMBA_DISABLE_JIT=1, their `@njit` lines removed)."""
NJIT_LINE = re.compile(r"^@njit\(.*\)\n", re.MULTILINE)

EXPLAINED = explained()

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
    verdicts: dict[str, str] = field(default_factory=dict)  # each planted mutant's, by name
    mutants: int = 0  # in the module (more than `total` when only some were planted)

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


def _codes(module: str, where: Path) -> dict[str, int | None]:
    meta = json.loads((where / "mutants" / f"{module}.meta").read_text())
    codes: dict[str, int | None] = meta["exit_code_by_key"]
    return codes


def verdict(code: int | None) -> str:
    """mutmut's exit code as benchmarks.mutation_results records it (None, not run, is left out)."""
    if code == KILLED:
        return "killed"
    if code == SURVIVED:
        return "survived"
    return "timeout" if code in TIMEOUTS else "no tests"


def _outcome(module: str, where: Path, names: list[str] | None = None) -> Outcome:
    every = _codes(module, where)
    codes = every if names is None else {name: every[name] for name in names}
    survivors = tuple(sorted(name for name, code in codes.items() if code == SURVIVED))
    killed = sum(code == KILLED for code in codes.values())
    timeout = sum(code in TIMEOUTS for code in codes.values())
    other = len(codes) - killed - timeout - len(survivors)
    verdicts = {name: verdict(code) for name, code in codes.items() if code is not None}
    return Outcome(module, len(codes), killed, timeout, survivors, other, verdicts, len(every))


NO_MUTANT = "no-such-mutant"
"""A name no mutant has: `mutmut run` with it generates the mutants and collects the tests' stats,
then stops (nothing matches), which lists the mutants to draw a sample from."""


def _listing(module: str, where: Path, command: list[str], env: dict[str, str]) -> list[str]:
    """Every mutant name of the module, none of them run."""
    subprocess.run(
        [*command, NO_MUTANT], cwd=where, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    return sorted(_codes(module, where))


def _sample(
    module: str, where: Path, command: list[str], env: dict[str, str], size: int, seed: int
) -> list[str]:
    """`size` of the module's mutant names, drawn at random with `seed` (all of them if fewer)."""
    names = _listing(module, where, command, env)
    return sorted(random.Random(seed).sample(names, min(size, len(names))))


def run(
    module: str,
    keep: Path | None = None,
    niceness: int = 19,
    names: list[str] | None = None,
    sample: int | None = None,
    seed: int = 0,
    planted_before: frozenset[str] | None = None,
) -> Outcome:
    """Mutate `module` (a key of MODULES) in a scratch copy, one worker, at the lowest priority by
    default (the bench shares the machine). mutmut stops a mutant's tests after a wall time that
    is a multiple of their unmutated time, so a test that runs a pass beside other work of its own
    priority (a CI job) passes `niceness=0`: at 19 it would starve and count every mutant a timeout.
    `names` plants only those mutants; `sample` plants that many drawn at random with `seed`;
    `planted_before` plants every mutant but those (the rest of a stopped pass)."""
    if module not in MODULES:
        raise ValueError(f"no mutation setup for {module}: one of {', '.join(MODULES)}")
    mutmut = Path(sys.executable).with_name("mutmut")
    with tempfile.TemporaryDirectory(prefix="mbxval-mutation-") as scratch:
        where = keep if keep is not None else Path(scratch)
        where.mkdir(parents=True, exist_ok=True)
        _scratch_copy(module, where)
        env = _environment(module, where)
        command = ["nice", "-n", str(niceness), str(mutmut), "run", "--max-children", "1"]
        if sample is not None:
            names = _sample(module, where, command, env, sample, seed)
        elif planted_before is not None:
            names = [name for name in _listing(module, where, command, env) if name not in planted_before]
        subprocess.run([*command, *(names or ())], cwd=where, env=env, check=True, stdout=subprocess.DEVNULL)
        return _outcome(module, where, names)


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
    parser.add_argument("--sample", type=int, help="plant this many mutants drawn at random, not all")
    parser.add_argument("--seed", type=int, default=0, help="the sample's seed (default 0)")
    parser.add_argument("--names", nargs="+", help="plant only these mutants (mutmut's names)")
    parser.add_argument(
        "--record",
        action="store_true",
        help="write the verdicts to benchmarks/mutation_results/ (a pass; with --names, an update)",
    )
    parser.add_argument(
        "--rest",
        action="store_true",
        help="plant the mutants the module's recorded stopped pass did not reach (with --record, resume it)",
    )
    parser.add_argument("--niceness", type=int, default=19, help="nice level of the run (default 19)")
    parser.add_argument(
        "--record-stopped",
        type=Path,
        metavar="DIR",
        help="record, as a stopped pass, the verdicts a run kept in DIR (--keep) reached before its stop",
    )
    args = parser.parse_args(argv)
    if args.record_stopped:
        for module in args.module or ():
            _record_stopped(module, args.record_stopped / module.replace("/", "_"), args.rest)
        return
    print(f"{'module':<40} {'total':>6} {'killed':>7} {'survived':>9} {'timeout':>8} {'no tests':>9}")
    for module in args.module or list(MODULES):
        mine = [name for name in args.names or () if name.startswith(_dotted(module) + ".")]
        if args.names and not mine:
            continue
        outcome = run(
            module,
            args.keep / module.replace("/", "_") if args.keep else None,
            args.niceness,
            names=mine or None,
            sample=args.sample,
            seed=args.seed,
            planted_before=_planted(module) if args.rest else None,
        )
        if args.record:
            _record(module, outcome, args)
        print(
            f"{module:<40} {outcome.total:>6} {outcome.killed:>7} {len(outcome.survivors):>9} "
            f"{outcome.timeout:>8} {outcome.other:>9}"
        )
        for name in outcome.survivors:
            print(f"    survived {name}: {EXPLAINED.get(name, 'NOT EXPLAINED')}")


def _dotted(module: str) -> str:
    return module.removesuffix(".py").replace("/", ".")


def _planted(module: str) -> frozenset[str]:
    """The mutants the module's recorded stopped pass planted."""
    from benchmarks import mutation_results

    record = mutation_results.load(module)
    if record is None or not record.stopped:
        raise SystemExit(f"mbxval: error: --rest: no stopped pass of {module} recorded")
    return frozenset(record.verdicts)


def _record_stopped(module: str, where: Path, rest: bool = False) -> None:
    """A pass stopped by hand: the mutants it reached, as a first pass marked stopped (with `rest`,
    added to the recorded stopped pass it resumed)."""
    from benchmarks import mutation_results

    reached = [name for name, code in _codes(module, where).items() if code is not None]
    outcome = _outcome(module, where, reached)
    if rest:
        record = mutation_results.record_rest(module, outcome.verdicts)
    else:
        record = mutation_results.record_pass(
            module, outcome.mutants, outcome.verdicts, None, None, stopped=True
        )
    mutation_results.save(record)


def _record(module: str, outcome: Outcome, args: argparse.Namespace) -> None:
    from benchmarks import mutation_results

    if args.rest:
        record = mutation_results.record_rest(module, outcome.verdicts)
    elif args.names:
        record = mutation_results.record_again(module, outcome.verdicts)
    else:
        record = mutation_results.record_pass(
            module, outcome.mutants, outcome.verdicts, args.sample, args.seed if args.sample else None
        )
    mutation_results.save(record)


if __name__ == "__main__":
    main()
