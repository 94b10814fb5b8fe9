"""Where and with what results were made: machine, Python, packages, git revision, date. The
engines' packages are the caller's to name (reports.run.engine_facts.engine_packages): this
module knows no engine."""

from __future__ import annotations

import datetime
import os
import platform
import subprocess
from collections.abc import Sequence
from importlib import metadata
from pathlib import Path
from typing import Any

OWN_PACKAGES = ("numpy", "scipy", "pandas")
"""The distributions every run rests on, whichever engines it runs; the engines' follow them."""


def machine() -> dict[str, Any]:
    return {
        "system": platform.system(),
        "release": platform.release(),
        "machine": platform.machine(),
        "processor": _cpu_model() or platform.processor(),
        "cpus": os.cpu_count(),
    }


def packages(engine_packages: Sequence[str]) -> dict[str, str]:
    """The installed version of our own packages, then of `engine_packages` ('not installed')."""
    versions = {}
    for name in (*OWN_PACKAGES, *engine_packages):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def version() -> str:
    """mbxval's own version, from the installed package's metadata ('unknown' when not installed)."""
    try:
        return metadata.version("mbxval")
    except metadata.PackageNotFoundError:
        return "unknown"


def version_text(engine_packages: Sequence[str]) -> str:
    """What `mbxval --version` prints: our version, then Python's and each package's we run on
    (the engines' `engine_packages` among them), one per line."""
    lines = [f"mbxval {version()}", f"python {platform.python_version()}"]
    return "\n".join(lines + [f"{name} {v}" for name, v in packages(engine_packages).items()])


def git_revision() -> str:
    """HEAD of the checkout this code runs from, with `-dirty` for local changes; 'unknown' without git."""
    root = Path(__file__).resolve().parent.parent
    try:
        head = _git(root, "rev-parse", "HEAD")
        dirty = _git(root, "status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def now() -> str:
    return datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")


def describe(engine_packages: Sequence[str]) -> dict[str, Any]:
    """The sidecar's description of where and with what (`engine_packages`: the engines') a run was made."""
    return {
        "machine": machine(),
        "python": platform.python_version(),
        "packages": packages(engine_packages),
        "git_revision": git_revision(),
        "date": now(),
    }


def _git(root: Path, *args: str) -> str:
    done = subprocess.run(["git", *args], cwd=root, capture_output=True, text=True, timeout=10, check=True)
    return done.stdout.strip()


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return ""
