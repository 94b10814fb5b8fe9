"""Helpers shared by the tests: mechanisms outside the catalogue and a fake engine for the runner."""
