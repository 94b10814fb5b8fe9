"""mbxval from Python: solve a scenario with any engine, run the harness, score a trajectory.

A thin facade over the packages that do the work (scenarios, reference_solver, adapters, reports),
taking the same inputs and checking them the same way as the command line (`python -m mbxval`)::

    import mbxval

    frame = mbxval.solve("slider_crank", engine="mujoco", steps=100, offset=0.05)
    results = mbxval.run(scenarios=["four_bar"], engines=["reference", "exudyn"], out="results")
    scored = mbxval.compare("slider_crank", frame)

Bad input raises ArgumentError or ScenarioError (both ValueError) with the command line's message.
"""

from mbxval.api import ArgumentError, compare, load_scenario, read_results, run, solve
from reports.store import provenance as _provenance
from scenarios import Scenario, ScenarioError

__version__ = _provenance.version()

__all__ = [
    "ArgumentError",
    "Scenario",
    "ScenarioError",
    "__version__",
    "compare",
    "load_scenario",
    "read_results",
    "run",
    "solve",
]
