"""Every engine's accuracy knobs (adapters.knobs) are classified and true to its ladder: every option
it declares is a knob; a knob said swept takes two values or more in some scene's ladder (with the
untuned point); one said fixed or not applicable takes at most one value in each scene's ladder."""

from __future__ import annotations

import dataclasses

import pytest

import adapters
import scenarios
from adapters.base import Adapter, Setting
from adapters.knobs import NOT_APPLICABLE, SWEPT, TREATMENTS, Knob
from scenarios import Polynomial, catalogue, load
from scenarios.scenario import Scenario


def engine(name: str) -> type[Adapter]:
    """The engine's adapter class, or a skip where it is not installed here (drake's pydrake)."""
    try:
        return adapters.adapter_class(name)
    except adapters.EngineUnavailable as error:
        pytest.skip(str(error))


def polynomial_drive() -> Scenario:
    """The slider-crank driven by a quadratic law, the scene where MuJoCo's `polynomial` matters."""
    base = scenarios.build("slider_crank", overrides={"steps": 50})
    drive = base.drivers[0]
    motion = Polynomial((drive.motion.start, 20.0, 400.0))  # type: ignore[union-attr]
    return dataclasses.replace(base, drivers=(dataclasses.replace(drive, motion=motion),), t_end=0.125)


def scenes() -> list[Scenario]:
    return [*(load(name) for name in catalogue(include_dynamic=True)), polynomial_drive()]


def ladders(adapter: Adapter) -> list[list[Setting]]:
    """Each scene's settings the engine runs: its ladder, default and untuned point."""
    found = []
    for scene in scenes():
        if adapter.supports(scene) is not None or (scene.analysis == "dynamic" and not adapter.dynamics):
            continue
        untuned = adapter.untuned_setting(scene)
        found.append(
            [*adapter.ladder(scene), adapter.default_setting(scene), *([untuned] if untuned else [])]
        )
    return found


@pytest.mark.parametrize("name", list(adapters.ENGINES))
def test_every_option_is_a_knob(name: str) -> None:
    kind = engine(name)
    knobs = [knob.name for knob in kind.knobs]
    assert len(knobs) == len(set(knobs)), f"{name}: a knob is declared twice"
    unclassified = {option.name for option in kind.options} - set(knobs)
    assert not unclassified, f"{name}: options without a knob: {sorted(unclassified)}"
    assert all(knob.treatment in TREATMENTS and knob.why for knob in kind.knobs)


@pytest.mark.parametrize("name", list(adapters.ENGINES))
def test_the_treatments_are_what_the_ladder_does(name: str) -> None:
    kind = engine(name)
    adapter = adapters.load(name)
    runs = ladders(adapter)
    assert runs, f"{name} runs no scene of the catalogue"
    options = {option.name for option in kind.options}
    for knob in (k for k in kind.knobs if k.name in options):
        per_scene = [{s.get(knob.name) for s in settings} for settings in runs]
        if knob.treatment == SWEPT:
            assert any(len(values) > 1 for values in per_scene), (
                f"{name} {knob.name}: said swept, never varied"
            )
        else:
            held = [
                {s.get(knob.name) for s in settings if s.mode != adapters.base.UNTUNED} - {None}
                for settings in runs
            ]
            assert all(len(values) <= 1 for values in held), (
                f"{name} {knob.name}: said {knob.treatment}, varied"
            )


def test_a_knob_must_say_its_treatment_and_why() -> None:
    with pytest.raises(ValueError, match="treatment must be one of"):
        Knob("dt", "tuned", "a step")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="says no why"):
        Knob("dt", NOT_APPLICABLE, " ")


def test_an_engine_without_knobs_declares_none() -> None:
    assert Adapter.knobs == ()
