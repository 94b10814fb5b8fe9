"""Drake adapter: the mechanism as a discrete MultibodyPlant in relative joint coordinates.

The plant's joints are the spanning tree (revolute about z, prismatic in the plane); revolute loop
closures are ball constraints and gear pairs coupler constraints, both solved by SAP, the only
discrete solver that takes them (adapters.drake.tree). The driver is a PD actuator on its joint fed
by a TrajectorySource (adapters.drake.model); in free dynamics gravity, spring-dampers and applied
loads move the bodies from the scenario's start (adapters.drake.loads). One mode, `sap`; its knobs
and the rule in adapters.drake.settings; the reading of velocities in adapters.drake.simulation.
Drake writes no model file (it reads URDF, SDFormat and MJCF, and writes none of them), so the
adapter has no `export`.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib.metadata import version
from typing import Any

import numpy as np

from adapters.base import Adapter, Option, Setting, Unsupported
from adapters.drake.forces import ForceReader
from adapters.drake.knobs import KNOBS
from adapters.drake.model import Diagram, Knobs, assemble, build_diagram
from adapters.drake.settings import SAP, STEPS_PER_PERIOD, ladder, rule_setting, untuned
from adapters.drake.simulation import CENTRAL, RUN_IN, STATE, run
from adapters.drake.tree import Plan, PlanError, plan
from adapters.lattice import outputs_on_steps
from adapters.modes import ENGINE, Mode
from scenarios.scenario import Scenario
from scenarios.trajectory import Trajectory


@dataclass
class Built:
    """What `build` hands to `simulate`."""

    scenario: Scenario
    plan: Plan
    diagram: Diagram
    velocity: str
    start: tuple[float, np.ndarray, np.ndarray]
    forces: ForceReader | None


class DrakeAdapter(Adapter):
    name = "drake"
    colour = "#9467bd"
    packages = ("drake",)
    dynamics = True
    rule = f"SAP at 1/{STEPS_PER_PERIOD} of the shortest period; a driven scenario's PD drive targets t + h"
    measured = (
        Mode(
            SAP,
            ENGINE,
            "Drake's discrete MultibodyPlant with SAP: loops as ball constraints, gears as couplers, the "
            "driver a PD actuator (free dynamics: gravity, LinearSpringDamper and applied spatial "
            "forces), stepped by Drake's Simulator (velocities the central difference of Drake's "
            "steps; accelerations from the step velocities)",
        ),
    )
    knobs = KNOBS
    options = (
        Option("dt", float, 0.0, 1.0, low_open=True, unit="s", help="the plant's time step"),
        Option("kp", float, 0.0, 1e15, help="PD drive's stiffness"),
        Option("kd", float, 0.0, 1e15, help="PD drive's damping"),
        Option("lead", float, 0.0, 1.0, help="drive target sampled at t + lead * dt"),
        Option("velocity", str, choices=(CENTRAL, STATE), help="velocity read centred or as the state"),
    )

    def version(self) -> str:
        return version("drake")

    def supports(self, scenario: Scenario) -> str | None:
        try:
            plan(scenario)
        except PlanError as reason:
            return str(reason)
        return None

    def default_setting(self, scenario: Scenario) -> Setting:
        return rule_setting(scenario)

    def untuned_setting(self, scenario: Scenario) -> Setting | None:
        return untuned(scenario)

    def ladder(self, scenario: Scenario) -> list[Setting]:
        return ladder(scenario)

    def build(self, scenario: Scenario, setting: Setting) -> Built:
        try:
            planned = plan(scenario)
        except PlanError as reason:
            raise Unsupported(str(reason)) from None
        default = rule_setting(scenario)
        knob = {name: float(setting.get(name, default.get(name))) for name in ("dt", "kp", "kd", "lead")}
        knob["dt"] = outputs_on_steps(np.asarray(scenario.times()), knob["dt"])
        t0 = float(scenario.times()[0])
        t_start = t0 - (RUN_IN * knob["dt"] if planned.driver is not None else 0.0)
        diagram = build_diagram(scenario, planned, Knobs(**knob), (t_start, scenario.t_end))
        context = diagram.plant.CreateDefaultContext()
        assemble(diagram, scenario, planned, context, t_start)
        start = (
            t_start,
            diagram.plant.GetPositions(context).copy(),
            diagram.plant.GetVelocities(context).copy(),
        )
        velocity = str(setting.get("velocity", CENTRAL))
        # a driven scene's loads are not in the plant (it moves as driven): its forces would lack them
        forces = (
            None
            if scenario.forces and planned.driver is not None
            else ForceReader(diagram, planned, scenario)
        )
        return Built(scenario, planned, diagram, velocity, start, forces)

    def simulate(self, model: Any, times: np.ndarray) -> Trajectory:
        built: Built = model
        scenario = built.scenario
        bodies = scenario.output_bodies
        guesses = np.array([scenario.body(b).guess[2] for b in bodies])
        trajectory, steps = run(
            built.diagram, built.start, times, bodies, built.velocity, guesses, built.forces
        )
        self.count_steps(steps)
        return trajectory
