"""The results store: the declared columns, the rows and trajectories on disk, written whole or not
at all under one writer's lock, with their provenance, repair and the scenarios' identities."""
