"""The Pinocchio adapter: the scenario built as a Pinocchio model and run by Pinocchio itself."""

from adapters.pinocchio.adapter import PinocchioAdapter

__all__ = ["PinocchioAdapter"]
