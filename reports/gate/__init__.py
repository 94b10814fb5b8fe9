"""The gate: a stored run judged against a baseline of cells, and the baselines that ship."""
