"""The example notebook runs from top to bottom (executed with nbclient)."""

import os
import re
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "haff_quickstart.ipynb"


def test_the_example_notebook_runs(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(EXAMPLE, as_version=4)
    os.environ["HAFF_QUICK"] = "1"
    try:
        nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                                resources={"metadata": {"path": str(tmp_path)}}).execute()
    finally:
        del os.environ["HAFF_QUICK"]
    outputs = "".join(o.get("text", "") for cell in notebook.cells
                      for o in cell.get("outputs", []))
    assert "a2 at the end:" in outputs
    # Haff's law with the Enskog rate, no fit: T of N = 2000 particles in 3D has a relative
    # statistical error sqrt(2 / (3 N)) = 1.8 %; 5 of it plus 3 % for a2 and the Enskog
    # contact value at phi = 0.05 bound |T/T_Haff - 1|.
    ratio = float(re.search(r"T/T_Haff at the end: ([0-9.]+)", outputs).group(1))
    assert abs(ratio - 1) < 5 * (2 / (3 * 2000)) ** 0.5 + 0.03, ratio
