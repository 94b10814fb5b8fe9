"""One BLAS thread per process: mbxval's linear systems are small (tens to a few hundred unknowns),
where OpenBLAS's threads cost far more in start-up and contention than they save, and each worker
process would multiply them. Parallelism comes from processes instead (`--workers`, Dask). Set
with threadpoolctl, which reaches a library already loaded (an environment variable read at
numpy's import does not); scipy's own OpenBLAS is loaded first so that it is held too. A child
forked after the call inherits the limit."""

from __future__ import annotations

BLAS_THREADS = 1
"""BLAS threads per process."""


def one_blas_thread() -> None:
    """Hold every BLAS library of this process (numpy's and scipy's OpenBLAS) to BLAS_THREADS."""
    import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS, so that the limit reaches it)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=BLAS_THREADS, user_api="blas")


def blas_threads() -> dict[str, int]:
    """Threads of each loaded BLAS library, by its file (for the tests and benchmarks)."""
    from threadpoolctl import threadpool_info

    return {
        str(info["filepath"]): int(info["num_threads"])
        for info in threadpool_info()
        if info["user_api"] == "blas"
    }
