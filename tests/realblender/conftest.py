"""The real Blender (Debian trixie's 4.3.2 in a chroot, .ci/blender/chroot.sh) beside the bpy
module of this venv. `make test-blender` builds the chroot and the zip, then runs these tests
with FIBRILFIT_CHROOT set; without it (`make test`) they are skipped, since they need root and
the chroot. With it set, a chroot that is not ready fails them: never a silent pass."""
import os
import pathlib
import shutil

import pytest

from realblender.helpers import BLENDER_VERSION, OUT, USER, ZIP, chroot, inside


def pytest_collection_modifyitems(config, items):
    here = pathlib.Path(__file__).parent
    for item in items:
        if here in pathlib.Path(item.fspath).parents:
            item.add_marker(pytest.mark.realblender)
            if not os.environ.get("FIBRILFIT_CHROOT"):
                item.add_marker(pytest.mark.skip(
                    reason="needs the trixie chroot with Blender 4.3.2: make test-blender"))


@pytest.fixture(scope="session")
def installed():
    """The zip from `make extension`, installed with Blender's own extension command into a
    fresh user directory. Returns Blender's version line."""
    chroot_dir = pathlib.Path(os.environ["FIBRILFIT_CHROOT"])
    assert (chroot_dir / ".fibrilfit-ready").exists(), f"{chroot_dir} is not a finished chroot"
    assert ZIP.exists(), f"{ZIP} missing: make extension builds it"
    shutil.rmtree(OUT, ignore_errors=True)  # a run again starts from nothing (idempotent)
    OUT.mkdir(parents=True)
    cp = chroot(f"rm -rf {USER} && blender --version && blender -b --factory-startup --command "
                f"extension install-file -r user_default -e {inside(ZIP)}")
    assert cp.returncode == 0, cp.stdout + cp.stderr
    assert 'Installed "fibrilfit"' in cp.stdout, cp.stdout
    assert cp.stdout.startswith(f"Blender {BLENDER_VERSION}"), cp.stdout[:200]
    return cp.stdout.splitlines()[0]
