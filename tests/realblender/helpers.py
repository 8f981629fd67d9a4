"""Helpers of the real-Blender tests: run a command in the chroot or with the bpy module."""

import json
import os
import pathlib
import shlex
import subprocess
import sys
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHROOT_SH = ROOT / ".ci" / "blender" / "chroot.sh"
OUT = ROOT / "out" / "realblender"        # under the checkout: /fibrilfit/out/... in the chroot
USER = "/fibrilfit/out/realblender/user"  # BLENDER_USER_RESOURCES: the cached chroot stays clean
VERSION = tomllib.loads((ROOT / "fibrilfit" / "blender_manifest.toml").read_text())["version"]
# `make extension` builds one zip per platform; the chroot is linux-x64
ZIP = ROOT / "dist" / f"fibrilfit-{VERSION}-linux_x64.zip"
BLENDER_VERSION = "4.3.2"


def chroot(command: str, timeout: float = 900) -> subprocess.CompletedProcess:
    """`command` (sh) inside the chroot, at the checkout (/fibrilfit), with the extension's
    user resources under out/realblender/user."""
    env = f"export BLENDER_USER_RESOURCES={USER} LANG=C.UTF-8; "
    return subprocess.run(["sh", str(CHROOT_SH), "run", env + command], capture_output=True,
                          text=True, timeout=timeout)


def module(args: list, timeout: float = 900) -> subprocess.CompletedProcess:
    """headless.py with this venv's bpy module (the reference)."""
    return subprocess.run([sys.executable, str(ROOT / "headless.py"), *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout)


def inside(path: pathlib.Path) -> str:
    """A path under the checkout as the chroot sees it."""
    return "/fibrilfit/" + path.resolve().relative_to(ROOT).as_posix()


def quote(args) -> str:
    return " ".join(shlex.quote(str(a)) for a in args)


def own_lines(stderr: str) -> list:
    """stderr without the lines Blender itself prints (its version banner)."""
    return [ln for ln in stderr.splitlines() if ln.strip() and not ln.startswith("Blender ")]


def read_json(path: pathlib.Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def picture_stamp():
    """tools/picture_stamp.py: stamps an accepted screen with this code's MODEL_VERSION."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("picture_stamp", ROOT / "tools" / "picture_stamp.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
