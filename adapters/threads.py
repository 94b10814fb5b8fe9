"""One BLAS thread per process: mbxval's linear systems are small (tens to a few hundred unknowns),
where OpenBLAS's threads cost far more in start-up and contention than they save, and each worker
process would multiply them. Parallelism comes from processes instead (`--workers`, Dask). Set
with threadpoolctl, which reaches a library already loaded (an environment variable read at
numpy's import does not); scipy's own OpenBLAS is loaded first so that it is held too. A child
forked after the call inherits the limit.

A library already at the limit is left alone: OpenBLAS starts its thread pool anew on every change
of its count, and the new threads spin for about a tenth of a second before they sleep, CPU that a
worker's clock would count as the run it is timing. The command line sets OPENBLAS_NUM_THREADS
before numpy loads (reports.entry), so that its process never starts a pool at all."""

from __future__ import annotations

BLAS_THREADS = 1
"""BLAS threads per process."""


def one_blas_thread() -> None:
    """Hold every BLAS library of this process (numpy's and scipy's OpenBLAS) to BLAS_THREADS,
    touching none that holds no more already."""
    import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS, so that the limit reaches it)
    from threadpoolctl import threadpool_limits

    if any(threads > BLAS_THREADS for threads in blas_threads().values()):
        threadpool_limits(limits=BLAS_THREADS, user_api="blas")


def blas_threads() -> dict[str, int]:
    """Threads of each loaded BLAS library, by its file (for the tests and benchmarks)."""
    from threadpoolctl import threadpool_info

    return {
        str(info["filepath"]): int(info["num_threads"])
        for info in threadpool_info()
        if info["user_api"] == "blas"
    }
