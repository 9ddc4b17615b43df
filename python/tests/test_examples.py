"""The examples of examples/, in their short forms: they run and draw their figures."""
import os
import subprocess
import sys

import pytest

from conftest import REPO

EXAMPLES = ["restitution.py", "servo_silo.py", "basin_sweep.py", "silo_stress.py",
            "basin_fields.py", "tumbling_clump.py"]


@pytest.mark.parametrize("example", EXAMPLES)
def test_the_example_runs_and_draws_its_figure(example, tmp_path):
    out = tmp_path / (example[:-3] + ".png")
    args = [sys.executable, os.path.join(REPO, "examples", example), "--short", "--out", str(out)]
    if example != "restitution.py":
        args += ["--runs", str(tmp_path / "runs")]
    done = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert out.stat().st_size > 10000


def test_the_complete_example_of_the_guide_runs(tmp_path):
    import re

    guide = open(os.path.join(REPO, "docs", "python.md")).read()
    code = re.search(r"## A complete example.*?```python\n(.*?)```", guide, re.S).group(1)
    script = tmp_path / "example.py"
    script.write_text(code)
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "runs" / "box" / "energies.csv").exists()
