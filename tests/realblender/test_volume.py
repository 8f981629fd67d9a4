"""`run --ensemble-volume` on the real Blender (docs/model/ensemble.md#volume): the Volume
object made by Geometry Nodes, saved with --blend, opened again by Blender 4.3.2, holds the
"density" grid with as many voxels above the threshold as the run recorded."""
import pytest
from realblender.helpers import OUT, chroot, inside, read_json


def test_the_density_volume_on_the_real_blender():
    OUT.mkdir(parents=True, exist_ok=True)
    run, blend, probe = OUT / "volume-run.json", OUT / "volume.blend", OUT / "volume-probe.json"
    for f in (run, blend, probe):
        f.unlink(missing_ok=True)
    cp = chroot(f"blender -b --factory-startup -P headless.py -- run --layers 6 --ensemble 6 "
                f"--ensemble-replicas 4 --ensemble-burn-in 4 --ensemble-volume --quiet "
                f"--json {inside(run)} --blend {inside(blend)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    volume = read_json(run)["ensemble"]["volume"]
    cp = chroot(f"blender -b {inside(blend)} --factory-startup -P "
                f"tests/realblender/volume_probe.py -- {inside(probe)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    seen = read_json(probe)
    assert seen["blender"].startswith("4.3.2") and seen["volumes"] == 1
    assert seen["grids"] == [["density", "FLOAT"]] and seen["collection_role"] == "density"
    assert seen["threshold"] == pytest.approx(volume["threshold"])  # float32 in Blender
    assert seen["voxels_above_threshold"] == volume["voxels_above_threshold"] > 100
