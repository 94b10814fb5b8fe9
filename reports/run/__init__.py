"""Running engines: each in isolation or in kept warm workers (or on Dask), planned in groups,
swept, stopped on request, made into result rows; and trajectories imported from other tools."""

from typing import TYPE_CHECKING

from reports.face import load

if TYPE_CHECKING:  # the face: what the package offers, each loaded on first use (reports.face)
    from reports.run import recording as recording
    from reports.run import scratch as scratch
    from reports.run import stop as stop
    from reports.run import sweep as sweep
    from reports.run.dask_backend import DaskRunner as DaskRunner
    from reports.run.engine_facts import engine_packages as engine_packages
    from reports.run.group_runs import RunConfig as RunConfig
    from reports.run.imported import Score as Score
    from reports.run.imported import add_to_store as add_to_store
    from reports.run.imported import score as score
    from reports.run.planning import NOT_INSTALLED as NOT_INSTALLED
    from reports.run.runner import Runner as Runner
    from reports.run.trajectory_file import ImportedTrajectory as ImportedTrajectory
    from reports.run.trajectory_file import TrajectoryFileError as TrajectoryFileError
    from reports.run.trajectory_file import parse_trajectory as parse_trajectory
    from reports.run.trajectory_file import read_trajectory as read_trajectory


def __getattr__(name: str) -> object:
    return load(__name__, name)
