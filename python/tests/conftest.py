"""Shared fixtures: the repository's paths and the `hertz` command line to compare against."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def hertz_cli():
    """The `hertz` binary (HERTZ_BIN, else the workspace's release build, built if missing)."""
    path = os.environ.get("HERTZ_BIN")
    if path:
        return pathlib.Path(path)
    path = ROOT / "target" / "release" / "hertz"
    if not path.exists():
        subprocess.run(["cargo", "build", "--release", "--bin", "hertz"], cwd=ROOT, check=True)
    return path
