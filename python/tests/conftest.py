"""Shared fixtures: the `haff` command (the reference every number is compared with)."""

import csv
import io
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def haff_bin() -> Path:
    """The haff binary of this checkout (HAFF_BIN, else target/release/haff, built if
    missing)."""
    path = Path(os.environ.get("HAFF_BIN", ROOT / "target" / "release" / "haff"))
    if not path.exists():
        subprocess.run(["cargo", "build", "--release", "-p", "haff-cli"], cwd=ROOT, check=True)
    return path


@pytest.fixture(scope="session")
def cli(haff_bin):
    """Runs `haff ARGS...`; returns stdout (fails the test on a non-zero exit)."""

    def run(*args: str, cwd=None) -> str:
        done = subprocess.run([str(haff_bin), *args], capture_output=True, text=True, cwd=cwd)
        assert done.returncode == 0, f"haff {' '.join(args)}: {done.stderr}"
        return done.stdout

    return run


def read_csv(text: str):
    """CSV text -> (header, rows of strings)."""
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[1:]


def column(text: str, name: str, kind=float):
    header, rows = read_csv(text)
    i = header.index(name)
    return [kind(r[i]) if r[i] != "" else float("nan") for r in rows]
