"""What the viewer's tests share: the package on sys.path, the generated bindings, the venv's
Python for running the program."""

import os
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
VIEWER = REPO / "host" / "viewer"
sys.path.insert(0, str(VIEWER))


def run_env() -> dict:
    """The environment the program runs in: the package importable from the tree."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(VIEWER) + os.pathsep + env.get("PYTHONPATH", "")
    return env


def program() -> list[str]:
    return [sys.executable, "-m", "syncap_view"]
