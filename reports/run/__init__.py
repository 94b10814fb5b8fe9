"""Running engines: each in isolation or in kept warm workers (or on Dask), planned in groups,
swept, stopped on request, made into result rows; and trajectories imported from other tools."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:
    from reports.run import recording, stop, sweep
    from reports.run.dask_backend import DaskRunner
    from reports.run.engine_facts import engine_packages
    from reports.run.group_runs import RunConfig
    from reports.run.imported import Score, add_to_store, score
    from reports.run.runner import Runner
    from reports.run.trajectory_file import (
        ImportedTrajectory,
        TrajectoryFileError,
        parse_trajectory,
        read_trajectory,
    )

__all__ = [
    "DaskRunner",
    "ImportedTrajectory",
    "RunConfig",
    "Runner",
    "Score",
    "TrajectoryFileError",
    "add_to_store",
    "engine_packages",
    "parse_trajectory",
    "read_trajectory",
    "recording",
    "score",
    "stop",
    "sweep",
]


def __getattr__(name: str) -> object:
    return load(__name__, name)
