"""The Exudyn adapter: the scenario built as a Exudyn model and run by Exudyn itself."""

from adapters.exudyn.adapter import ExudynAdapter

__all__ = ["ExudynAdapter"]
