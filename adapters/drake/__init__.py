"""The Drake adapter: the scenario built as a discrete MultibodyPlant and run by Drake's Simulator."""

from adapters.drake.adapter import DrakeAdapter

__all__ = ["DrakeAdapter"]
