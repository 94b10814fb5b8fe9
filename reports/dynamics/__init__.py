"""The dynamics suite: engines in forward dynamics against the native truth, its stability map."""
