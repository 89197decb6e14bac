"""Runs the example of docs/python.md as written: it must finish and find phi*."""
import os
import re
import subprocess
import sys

import pytest

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "python.md")


def test_docs_example_runs_and_finds_phi_star(tmp_path):
    pytest.importorskip("matplotlib")  # optional for the core alone (python3-matplotlib); CI has it
    with open(DOC) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert len(blocks) == 1, "docs/python.md should hold exactly one python example"
    script = tmp_path / "example.py"
    script.write_text(blocks[0])
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, check=True, capture_output=True,
                         text=True, env=dict(os.environ, MPLBACKEND="Agg")).stdout
    assert (tmp_path / "python_example.png").stat().st_size > 10000
    m = re.search(r"final phi (\S+), phi\* (\S+), regime (\w+)", out)
    assert m, out
    # Over a 1-s window at 300 s the travel direction equals phi* within 1e-3 rad (physics.md section 5).
    assert abs(float(m.group(1)) - float(m.group(2))) < 1e-3
    assert m.group(3) == "sleeping"
