"""The VirtualHome reference simulator in a side venv, for benchmarks and differential tests.

``virtualhome==2.3.0`` is installed (with numpy only, ``--no-deps``) into
``$HOMESIM_DATA/refvenv`` the first time it is needed; it is never a dependency of
homesim. `run_reference` runs `_ref_runner.py` in that venv and returns its JSON.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from homesim.knowledge.fetch import data_root

RUNNER = Path(__file__).with_name("_ref_runner.py")


def reference_python() -> Path:
    """The side venv's interpreter, creating the venv if needed."""
    venv = data_root() / "refvenv"
    python = venv / "bin" / "python"
    marker = venv / ".virtualhome-2.3.0"
    if not marker.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--no-deps",
                        "virtualhome==2.3.0", "numpy"], check=True)
        marker.touch()
    return python


def run_reference(dataset: Path, *args: str) -> dict:
    """Run the reference runner on the data set and return the JSON it prints."""
    proc = subprocess.run([str(reference_python()), str(RUNNER), str(dataset), *args],
                          capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"reference runner failed:\n{proc.stderr[-2000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])
