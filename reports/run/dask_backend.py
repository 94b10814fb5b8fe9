"""Running the groups on a Dask cluster: `--workers N` starts a local one of N single-threaded worker
processes (one BLAS thread each, adapters.threads: the parallelism is the processes'), `--cluster
tcp://HOST:PORT` uses an existing scheduler.

One task is one scenario x engine group (reports.run.runner.run_group, run on the worker exactly
as the serial runner runs it: each setting in a forked child with its time limit); the truth of each
scenario is one task more, whose result the groups of that scenario receive. The client alone writes
the store, after each batch of finished groups (as_completed), so an interrupted run resumes with no
row lost or duplicated. A task's exception or a dead worker (KilledWorker) costs that group only:
its rows are stored `failed` with the reason, and the next run retries them. Tasks have no retries
(retries=0); the local cluster's scheduler gives up on a task at the first worker death it causes
(allowed-failures 0) and hands each worker one task at a time (worker-saturation 1), so that a dying
worker holds no other group. An external scheduler's own settings decide that for --cluster.
Each worker warms once (WarmWorker: the native kernels loaded when it starts); each task thread keeps
its engines' warm workers and a truth worker from task to task (reports.run.kept_workers: forked
once, not once per group and truth), warming a scenario before a fork, so that a run's child starts
ready, as in the serial runner.

Dask is imported here only: the serial runner does not import it.
"""

from __future__ import annotations

import contextlib
from collections import Counter
from collections.abc import Iterator, Sequence
from typing import Any

import reports.run.kept_workers as kept_workers
from adapters.base import Setting
from reports.run.group_runs import RunConfig, Stored, failure, run_group
from reports.run.planning import Group
from reports.run.runner import Loader, Runner, Truth, progress_bar, truth_named
from reports.run.scratch import scratch
from reports.scoring import NamedTruth, Residual
from scenarios import Scenario

LOCAL_CONFIG = {
    "distributed.scheduler.allowed-failures": 0,
    "distributed.scheduler.worker-saturation": 1.0,
    "distributed.worker.profile.enabled": False,  # no sampling thread beside the forked runs
    "distributed.worker.daemon": False,  # the workers fork their runs (isolation.run_isolated)
}


@contextlib.contextmanager
def local_cluster(workers: int) -> Iterator[Any]:
    """A LocalCluster of `workers` single-threaded processes on the loopback address, no dashboard;
    its scratch space (the workers' spill and lock files) in a private temporary directory removed
    when the cluster closes, even by Ctrl-C or SIGTERM, and by the next local cluster's start when
    a kill -9 left it (reports.run.scratch)."""
    import dask
    from distributed import LocalCluster

    with (
        scratch("dask") as directory,
        dask.config.set({**LOCAL_CONFIG, "temporary-directory": directory}),
        LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            local_directory=directory,
        ) as cluster,
    ):
        yield cluster


@contextlib.contextmanager
def connect(workers: int | None, address: str | None) -> Iterator[Any]:
    """A client of the scheduler at `address`, or of a local cluster of `workers` processes."""
    from distributed import Client

    if address is not None:
        with Client(address, timeout="10s") as client:
            yield client
        return
    assert workers is not None
    with local_cluster(workers) as cluster, Client(cluster) as client:
        yield client


def warm_plugin() -> Any:
    """A worker plugin: each worker process loads the native kernels once, when it starts (or joins
    the run), rather than in the forked child of every run (reports.run.warm)."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class WarmWorker(WorkerPlugin):
        idempotent = True  # registered again by a later run on the same cluster: kept, not rerun

        def setup(self, worker: Any) -> None:
            from adapters.threads import one_blas_thread
            from reports.run.warm import warm_kernels

            one_blas_thread()  # parallelism is the workers'; each holds one BLAS thread
            warm_kernels()

        def teardown(self, worker: Any) -> None:
            kept_workers.release_all()

    return WarmWorker()


def truth_task(truth: Truth, scenario: Scenario, timeout: float) -> NamedTruth | str:
    """The scenario's truth, solved on a worker in the thread's kept truth worker (a forked child,
    with the time limit; reports.run.kept_workers)."""
    return truth_named(kept_workers.truth_worker(truth).call(scenario, timeout))


def group_task(
    loader: Loader,
    group: Group,
    jobs: list[tuple[Setting, bool]],
    truth: NamedTruth | str,
    config: RunConfig,
    residual: Residual | None,
) -> list[Stored]:
    """One group's rows, made on a worker with the engine loaded there once, in the thread's kept
    warm workers (reports.run.kept_workers), as the serial runner makes them."""
    group.adapter, workers = kept_workers.group_workers(loader, group.engine, config, residual)
    return run_group(group, jobs, truth, config, residual, workers=workers)


class DaskRunner(Runner):
    """The Runner with its groups run as tasks on a Dask cluster (see the module's docstring)."""

    def __init__(self, *args: Any, workers: int | None = None, cluster: str | None = None, **kw: Any) -> None:
        super().__init__(*args, **kw)
        self.local_workers, self.address = workers, cluster
        self.client: Any = None

    def run(self, scenario_names: Sequence[str]) -> None:
        """Connect first (a bad address fails before anything is written), then run as the Runner."""
        with connect(self.local_workers, self.address) as client:
            self.client = client
            client.register_plugin(warm_plugin(), name="mbxval-warm")
            self.workers = sum(client.nthreads().values()) or 1
            super().run(scenario_names)

    def _execute(self, groups: list[tuple[Group, list[tuple[Setting, bool]]]]) -> None:
        todo = [(g, jobs) for g, jobs in groups if g.reason_row is None and jobs]
        for group, _ in groups:
            self._reconcile(group)
            if group.reason_row is not None:
                self._add(group.reason_row)
        self._save()
        truths, futures = self._submit(self.client, todo)
        try:
            self._gather(futures, truths, sum(g.reason_row is not None for g, _ in groups))
        finally:
            left = [f for f, _, _ in futures.values()] + [f for f in truths.values() if f is not None]
            self.client.cancel(left)

    def _submit(self, client: Any, todo: list[tuple[Group, list[tuple[Setting, bool]]]]) -> tuple[Any, Any]:
        """One truth task per scenario, one task per group that takes its scenario's truth."""
        truths: dict[str, Any] = {}
        futures: dict[str, tuple[Any, Group, list[tuple[Setting, bool]]]] = {}
        timeout = self.config.truth_timeout
        for group, jobs in todo:
            name = group.scenario.name
            if name not in truths:
                truths[name] = client.submit(
                    truth_task, self.truth, group.scenario, timeout, pure=False, retries=0
                )
            shipped = Group(group.scenario, group.engine, None, group.version)  # the adapter loads there
            future = client.submit(
                group_task, self.loader, shipped, jobs, truths[name], self.config, self.residual,
                pure=False, retries=0,
            )  # fmt: skip
            futures[future.key] = (future, group, jobs)
        return truths, futures

    def _gather(self, futures: dict[str, Any], truths: dict[str, Any], made: int) -> None:
        """Store each group's rows as it finishes, saving after each batch of finished groups. The
        client drops its reference to a finished group's result, and to a scenario's truth once its
        last group is in, so the workers release them: a long sweep holds only what still runs.
        The bar starts at the `made` rows stored already (the reasons an engine does not run)."""
        from distributed import as_completed

        waiting = Counter(group.scenario.name for _, group, _ in futures.values())
        runs = sum(len(jobs) for _, _, jobs in futures.values())
        with progress_bar(runs + made, self.progress, "run") as bar:
            bar.update(made)
            for batch in as_completed([f for f, _, _ in futures.values()]).batches():
                for future in batch:
                    _, group, jobs = futures.pop(future.key)
                    for row, trajectory in self._outcome(future, group, jobs):
                        self._add(row, trajectory)
                    name = group.scenario.name
                    truth = truths.get(name)
                    if truth is not None and truth.status == "finished":
                        self._put_truth(group.scenario, truth.result())
                        truths[name] = None  # stored once; no longer held for the client
                    waiting[name] -= 1
                    if not waiting[name]:
                        truths.pop(name, None)  # its last group is in: nothing holds the truth now
                    bar.set_description(f"{name} {group.engine}", refresh=False)
                    bar.update(len(jobs))
                self._save()

    def _outcome(self, future: Any, group: Group, jobs: list[tuple[Setting, bool]]) -> list[Stored]:
        """The group's rows, or each of its runs `failed` with why the task gave none."""
        from distributed import KilledWorker

        try:
            return list(future.result())
        except KilledWorker as error:
            message = f"the Dask worker running this group died ({error})"
        except Exception as error:  # the task raised, or was cancelled
            message = f"the Dask task failed: {type(error).__name__}: {error}"
        return [
            (failure(group, setting, is_default, "failed", message), None) for setting, is_default in jobs
        ]
