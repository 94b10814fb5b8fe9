"""A compiled MuJoCo model of a scenario: the model, its consistent start and what the outputs need."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import mujoco
import numpy as np

from adapters.mujoco.forces import ForceMap
from adapters.mujoco.kinematics import KinematicSolver
from adapters.mujoco.laws import Clock
from adapters.mujoco.loads import Loads
from adapters.mujoco.pairs import PairTable
from adapters.mujoco.tree import Affine
from scenarios.scenario import Scenario


@dataclass
class Model:
    """A compiled MuJoCo model with its consistent start and what the outputs need."""

    write: Callable[[], str]
    """Writes the model's MJCF text with its start as the key 'start' (`xml`): only an export reads
    it, so the build leaves it unwritten (two texts of over 1000 elements on a faceted cam)."""
    model: mujoco.MjModel
    qpos0: np.ndarray
    qvel0: np.ndarray
    dt: float
    solref: tuple[float, float]
    """The equalities' solref (adapters.mujoco.mjcf.Physics)."""
    contact_solref: tuple[float, float]
    """The cam contacts' solref."""
    bodies: tuple[str, ...]
    sites: list[int]
    theta: list[Affine]
    joint_ids: dict[str, int]
    clocks: dict[int, Clock]
    preload: float = 0.0
    """The cam followers' preload (N); 0 without cams."""
    pairs: PairTable | None = None
    """The contact pairs' groups and geoms (adapters.mujoco.pairs), read at every output time."""
    hops: dict[int, float] = field(default_factory=dict)
    """Per faceted cam (pair group): the gap its follower may show at a grid time (its sagitta)."""
    kinematic: KinematicSolver | None = None
    """The solver of the kinematic mode (None: MuJoCo's integrator)."""
    loads: Loads = field(default_factory=Loads)
    """The dynamic scene's loads, whose motors' controls simulate sets."""
    angles: Scenario | None = None
    """The scenario whose angle outputs the trajectory carries (None: none)."""
    forces: ForceMap = field(default_factory=lambda: ForceMap((), ()))
    """Where the drivers' forces and the joints' reactions are read (adapters.mujoco.forces)."""

    @cached_property
    def xml(self) -> str:
        """The MJCF text of the model at its start (written on first use)."""
        return self.write()


def evaluate(form: Affine, model: Model, qpos: np.ndarray) -> float:
    return form.const + sum(c * float(qpos[model.joint_ids[j]]) for j, c in form.coefs.items())
