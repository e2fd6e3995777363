"""Shared fixtures: the repository's data and the command line the package is compared with."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "data"


def _cli():
    """The `biscara` binary: $BISCARA_BIN (set by the Rust test that runs this suite), else the
    debug build of this checkout, else one on PATH."""
    given = os.environ.get("BISCARA_BIN")
    if given:
        return given
    built = ROOT / "target" / "debug" / "biscara"
    if built.is_file():
        return str(built)
    return shutil.which("biscara")


@pytest.fixture(scope="session")
def cli():
    """Runs the command line: `cli(*args)` → CompletedProcess (text), in the repository root."""
    binary = _cli()
    if binary is None:
        if os.environ.get("CI") == "true":
            pytest.fail("the biscara binary is missing (set BISCARA_BIN)")
        pytest.skip("the biscara binary is missing (set BISCARA_BIN or build it)")

    def run(*args, check=True):
        done = subprocess.run(
            [binary, *map(str, args)], cwd=ROOT, capture_output=True, text=True
        )
        if check and done.returncode != 0:
            raise AssertionError(f"biscara {' '.join(map(str, args))}: {done.stderr}")
        return done

    return run


@pytest.fixture(scope="session")
def data():
    return DATA
