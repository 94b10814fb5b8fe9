"""Fixtures shared by the adapters' timing tests."""

from tests.support.fake_clock import clock

__all__ = ["clock"]
