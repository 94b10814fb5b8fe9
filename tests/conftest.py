"""Shared test setup: the closed forms module lives beside the tests."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
