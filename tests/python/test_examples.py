# The examples run to the end: the script (its figure written) and the notebook (executed by
# nbconvert), each with a short time.
import os
import subprocess
import sys

import numpy as np

import caustica


def test_the_example_script_writes_its_figure(source, tmp_path):
    out = tmp_path / "figure.png"
    run = subprocess.run([sys.executable, str(source / "examples" / "equal_time.py"), "--time", "0.5",
                          "--width", "48", "--height", "48", "-o", str(out)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert "photon: relMSE" in run.stdout and "path: relMSE" in run.stdout
    figure = caustica.read_image(str(out))
    assert figure.shape[0] > 300 and figure.std() > 0.05  # a picture, not a blank page


def test_the_notebook_runs_to_the_end(source, tmp_path):
    env = dict(os.environ, CAUSTICA_EXAMPLE_TIME="0.3", CAUSTICA_EXAMPLE_SIZE="32")
    out = tmp_path / "executed.ipynb"
    run = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                          "--ExecutePreprocessor.timeout=300", "--output", str(out),
                          str(source / "examples" / "equal_time.ipynb")],
                         capture_output=True, text=True, timeout=400, env=env, cwd=source / "examples")
    assert run.returncode == 0, run.stderr[-3000:]
    text = out.read_text()
    assert "caustic photons; bounces" in text and '"output_type": "error"' not in text
