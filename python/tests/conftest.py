"""Shared fixtures: the source tree, the legwork CLI and a sample accentuation database.

Run from the build tree: PYTHONPATH=build/python LEGWORK_CLI=build/apps/legwork/legwork \
    /usr/bin/python3 -m pytest python/tests   (CTest's python_tests does this)."""
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("LEGWORK_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
TRIAL = SOURCE / "data/cmu/bvh/walking/07_02.bvh"
HELD_OUT = "bvh/walking/07_02.bvh"


def cli_path():
    return pathlib.Path(os.environ.get("LEGWORK_CLI", SOURCE / "build/apps/legwork/legwork"))


@pytest.fixture(scope="session")
def cli():
    """Runs the legwork command line; returns its stdout (skips when the CLI is not built)."""
    exe = cli_path()
    if not exe.exists():
        pytest.skip(f"legwork CLI not found at {exe} (set LEGWORK_CLI)")

    def run(*args):
        done = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, f"legwork {' '.join(map(str, args))} failed: {done.stderr}"
        return done.stdout

    return run


@pytest.fixture(scope="session")
def db_path(cli, tmp_path_factory):
    """The sample database of the C and C# examples: data/cmu without the trial we drive."""
    path = tmp_path_factory.mktemp("db") / "sample.lwdb"
    cli("accent", "build", "--data", SOURCE / "data/cmu", "--exclude", HELD_OUT, "--out", path)
    return path


@pytest.fixture(scope="session")
def db(db_path):
    import legwork

    return legwork.accent.load_database(str(db_path))
