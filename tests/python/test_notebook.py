"""The README's example and the notebook run as a user runs them."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(os.environ["GRAINSHOCK_SOURCE_DIR"]) / "examples"


def test_readme_example_writes_its_plot_and_frame(tmp_path):
    pytest.importorskip("matplotlib")
    done = subprocess.run([sys.executable, EXAMPLES / "python_example.py"], cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    for name in ("R_t.png", "frame.png"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG"


def test_notebook_executes_and_shows_a_frame(tmp_path):
    if shutil.which("jupyter") is None:
        pytest.skip("no jupyter (Debian: jupyter-nbconvert python3-ipykernel)")
    env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    out = tmp_path / "executed.ipynb"
    done = subprocess.run(["jupyter", "nbconvert", "--to", "notebook", "--execute",
                           "--ExecutePreprocessor.timeout=600", "--output", out,
                           EXAMPLES / "notebook.ipynb"], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    import nbformat
    nb = nbformat.read(out, as_version=4)
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert any("image/png" in o.get("data", {}) for o in outputs)
    assert any("collisions" in o.get("text", "") for o in outputs)
    # Fitted past the crossover (t >= 1000, once the band has formed) the one realisation's R_t
    # grows as t^(1/3), the paper's 2D exponent: seeds 1-4 fit 0.32, 0.33, 0.36, 0.35 there (one
    # realisation each, where the paper averages 100), hence 0.03. The fit that took in the
    # crossover (t = 80-1810) printed 0.39.
    text = next(o["text"] for o in outputs if "collisions" in o.get("text", ""))
    slope = float(re.search(r"t\^([0-9.]+)", text).group(1))
    assert abs(slope - 1 / 3) < 0.03, text
    # The page of every frame, inline (grainshock.view).
    assert any("<iframe" in o.get("data", {}).get("text/html", "") for o in outputs)
