"""The type information of the package is right: the modules pass `mypy --strict` (the
configuration in python/pyproject.toml) and the stubs of the extension, haff/_haff.pyi,
match the compiled module (mypy's stubtest: every function, class, method and argument of
the stub exists at run time with the same signature, and the other way round)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

PYTHON = Path(__file__).resolve().parents[1]


def mypy(*args: str, cwd: Path, env=None) -> subprocess.CompletedProcess:
    pytest.importorskip("mypy")
    return subprocess.run([sys.executable, "-m", *args], cwd=cwd, env=env,
                          capture_output=True, text=True)


def test_the_package_passes_mypy_strict():
    done = mypy("mypy", cwd=PYTHON)
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_stubs_match_the_extension(tmp_path):
    """The stub of this checkout (MYPYPATH) against the installed extension (imported from
    a scratch directory, not from the sources, which hold no compiled module). stubtest
    analyses without mypy's cache (numpy's stubs included): 20 to 40 s here."""
    env = dict(os.environ, MYPYPATH=str(PYTHON))
    done = mypy("mypy.stubtest", "haff._haff", "--mypy-config-file",
                str(PYTHON / "pyproject.toml"), cwd=tmp_path, env=env)
    assert done.returncode == 0, done.stdout + done.stderr
