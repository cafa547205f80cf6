"""The README's example and the notebook run as a user runs them."""
import os
import pathlib
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
    # The page of every frame, inline (grainshock.view).
    assert any("<iframe" in o.get("data", {}).get("text/html", "") for o in outputs)
