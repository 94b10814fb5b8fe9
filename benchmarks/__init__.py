"""Benchmarks run on demand (not tests): `python -m benchmarks.solver_speed` and
`python -m benchmarks.chain_scaling` from the repository root."""
