"""Running engines: each in isolation or in kept warm workers (or on Dask), planned in groups,
swept, stopped on request, made into result rows; and trajectories imported from other tools."""
