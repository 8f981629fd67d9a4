"""The real Blender (Debian trixie's 4.3.2 in a chroot, .ci/blender/chroot.sh) beside the bpy
module of this venv. `make test-blender` builds the chroot and the zip, then runs these tests
with FIBRILFIT_CHROOT set; without it (`make test`) they are skipped, since they need root and
the chroot. With it set, a chroot that is not ready fails them: never a silent pass."""
import json
import os
import pathlib
import shlex
import subprocess
import sys
import tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHROOT_SH = ROOT / ".ci" / "blender" / "chroot.sh"
OUT = ROOT / "out" / "realblender"        # under the checkout: /fibrilfit/out/... in the chroot
USER = "/fibrilfit/out/realblender/user"  # BLENDER_USER_RESOURCES: the cached chroot stays clean
VERSION = tomllib.loads((ROOT / "fibrilfit" / "blender_manifest.toml").read_text())["version"]
ZIP = ROOT / "dist" / f"fibrilfit-{VERSION}.zip"
BLENDER_VERSION = "4.3.2"


def pytest_collection_modifyitems(config, items):
    here = pathlib.Path(__file__).parent
    for item in items:
        if here in pathlib.Path(item.fspath).parents:
            item.add_marker(pytest.mark.realblender)
            if not os.environ.get("FIBRILFIT_CHROOT"):
                item.add_marker(pytest.mark.skip(
                    reason="needs the trixie chroot with Blender 4.3.2: make test-blender"))


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


@pytest.fixture(scope="session")
def installed():
    """The zip from `make extension`, installed with Blender's own extension command into a
    fresh user directory. Returns Blender's version line."""
    chroot_dir = pathlib.Path(os.environ["FIBRILFIT_CHROOT"])
    assert (chroot_dir / ".fibrilfit-ready").exists(), f"{chroot_dir} is not a finished chroot"
    assert ZIP.exists(), f"{ZIP} missing: make extension builds it"
    OUT.mkdir(parents=True, exist_ok=True)
    cp = chroot(f"rm -rf {USER} && blender --version && blender -b --factory-startup --command "
                f"extension install-file -r user_default -e {inside(ZIP)}")
    assert cp.returncode == 0, cp.stdout + cp.stderr
    assert f'Installed "fibrilfit"' in cp.stdout, cp.stdout
    assert cp.stdout.startswith(f"Blender {BLENDER_VERSION}"), cp.stdout[:200]
    return cp.stdout.splitlines()[0]


def read_json(path: pathlib.Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))
