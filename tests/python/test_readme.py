"""python.readme: the Python example of README.md runs with the package and
prints exactly what the README says it prints."""
import os
import subprocess
import sys

import meshtopo
from readme_blocks import local_example


def test_readme_python_example_runs_and_prints_what_it_says():
    code, printed = local_example()
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.dirname(os.path.dirname(meshtopo.__file__))
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout == printed
