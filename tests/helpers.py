"""Shared test helpers (conftest holds the fixtures)."""
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def snapshot_user(objects) -> dict:
    return {name: (ob.name, tuple(ob.location), ob.data.name, [c.name for c in ob.users_collection])
            for name, ob in objects.items()}


def run_cli(*args, timeout=600):
    """Run headless.py under this interpreter; return the CompletedProcess."""
    return subprocess.run([sys.executable, str(ROOT / "headless.py"), *args], capture_output=True,
                          text=True, timeout=timeout, cwd=ROOT)
