"""The native engine's default on a scene with singular passages (IFToMM A02, n_four_bar): ALI3-P at
the settings rule's step, which passes them, said by `mbxval list`; elsewhere the partitioned method
as before. The family declares its passages as data (Family.singular_passages)."""

from __future__ import annotations

import math

import pytest

import adapters
import scenarios
from adapters.base import Setting
from reports.cli.main import main
from reports.dynamics import cases
from scenarios.families.n_four_bar_reference import HIGH_PRECISION, criterion


def test_a_scene_with_passages_defaults_to_ali3p_at_a_thousandth_of_its_gravity_period() -> None:
    engine = adapters.load("reference")
    scenario = scenarios.build("n_four_bar")
    # the shortest period is the chain's gravity mode, 2 pi / (2 sqrt(N g / l)) with N = 5 bodies of 1 m
    period = 2 * math.pi / (2 * math.sqrt(5 * 9.81 / 1.0))
    setting = engine.default_setting(scenario)
    assert setting.mode == "ali3p" and setting["dt"] == pytest.approx(period / 1000, rel=1e-12)
    assert "C_q loses N ranks" in engine.default_reason(scenario)
    spec = engine.default_setting(scenarios.build("n_four_bar/spec"))  # 81 bodies: a shorter period
    assert spec["dt"] == pytest.approx(2 * math.pi / (2 * math.sqrt(81 * 9.81)) / 1000, rel=1e-12)


@pytest.mark.parametrize("name", ["four_bar_gravity", "compound_pendulum", "four_bar"])
def test_scenes_without_passages_keep_their_defaults(name: str) -> None:
    engine = adapters.load("reference")
    scenario = scenarios.build(name)
    assert engine.default_setting(scenario).mode in ("DOP853", "newton")
    assert engine.default_reason(scenario) == ""


def test_list_says_why_the_default_differs(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    lines = [line for line in out.splitlines() if line.startswith("  reference on n_four_bar")]
    assert len(lines) == 2 and all("ali3p by default" in line for line in lines)
    assert "reference on four_bar_gravity" not in out


def test_a02_over_ten_seconds_passes_on_the_default_path_within_the_specification() -> None:
    """The issue's failing command, `mbxval solve n_four_bar --set t_end=10`: its default run is ok,
    and B0 meets the specification's high-precision limit at the benchmark's 400 outputs."""
    scenario = scenarios.build("n_four_bar", overrides={"t_end": 10.0, "steps": 400})
    result = adapters.load("reference").run(scenario)
    assert result.status == "ok" and result.trajectory is not None, result.message
    figures = criterion(scenario, result.trajectory)
    assert figures["benchmark_error"] < HIGH_PRECISION and figures["invariant_error"] < 1e-10


def test_the_dynamics_suite_runs_the_fixed_step_default_as_it_is() -> None:
    """The suite keeps the native engine no tighter than ten times its truth, by rtol; ALI3-P's
    default has no rtol and runs at its own step."""
    engine = adapters.load("reference")
    scenario = scenarios.build("n_four_bar")
    chosen = cases.settings(scenario, engine)
    assert chosen is not None and chosen[0] == engine.default_setting(scenario)
    assert Setting.of("DOP853", rtol=1e-11) in chosen and Setting.of("DOP853", rtol=1e-12) not in chosen
    assert cases.SINGULAR_PASSAGES == {"n_four_bar": 1e-12}
