"""The MuJoCo adapter: the scenario built as a MuJoCo model and run by MuJoCo itself."""

from adapters.mujoco.adapter import MujocoAdapter

__all__ = ["MujocoAdapter"]
