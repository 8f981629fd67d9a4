"""The whole job: result contract, determinism, the CLI's exit codes and outputs."""
import json

import bpy
import numpy as np
import pytest
from helpers import cli_in_process, run_cli

from fibrilfit.model import params as P
from fibrilfit import pipeline

CONTRACT = {"fibrilfit_version", "blender_version", "params", "seed", "gravity", "verdict",
            "intersecting_faces", "clashing_pairs", "max_bond_stretch", "linker_intact",
            "accommodated", "frames_simulated", "timings_s", "bound", "core_entry"}


def test_result_contract(scene):
    r = pipeline.run_model(P.make_params(layers=6, frames=60), scene)
    assert CONTRACT <= set(r)
    assert r["params"]["layers"] == 6 and r["seed"] == 0
    assert r["blender_version"] == bpy.app.version_string
    assert set(r["timings_s"]) == {"build", "bake", "check"}
    # the bracket's proven side (docs/model/bound.md): the default 6-layer model fits at 6 (this
    # run: accommodated, measured 2026-11-27), its bound is 1, and this layout keeps to the
    # bound's core assumption (no linker bead enters the core: core_entry 0.0 of at most 0.5)
    assert r["bound"]["impossible_below"] == 1 and r["bound"]["below"] is False
    assert r["bound"]["linker"] == 6 and r["core_entry"] == 0.0
    assert r["verdict"] == "successful" and r["accommodated"] is True
    assert (r["verdict"] == "intersection") == (r["intersecting_faces"] > 0)
    assert all(i < j for i, j, _ in r["clashing_pairs"])
    assert r["frames_simulated"] == 60
    assert r["accommodated"] == (r["verdict"] == "successful" and r["linker_intact"])
    json.dumps(r)


def test_same_seed_same_result(scene):
    p = P.make_params(layers=10, linker=3, seed=7, frames=120)
    a, b = pipeline.run_model(p, scene), pipeline.run_model(p, scene)
    for key in ("verdict", "gravity", "clashing_pairs", "max_bond_stretch", "globule_centres"):
        assert a[key] == b[key], key
    c = pipeline.run_model(p.replace(seed=8), scene)
    assert c["gravity"] != a["gravity"]


def test_gravity_is_drawn_within_the_bound(scene):
    for seed in range(20):
        g = pipeline.run_model(P.make_params(layers=1, seed=seed, gravity=0.3), scene,
                         stop_after="build")["gravity"]
        assert all(-0.3 <= v <= 0.3 for v in g)


def test_short_linker_stretches_and_is_not_accommodated(scene):
    r = pipeline.run_model(P.make_params(layers=20, linker=2), scene)
    assert r["max_bond_stretch"] > 0.05 and not r["linker_intact"] and not r["accommodated"]


def test_cli_default_run_writes_json_and_a_scrubbable_blend(tmp_path):
    out = run_cli("run", "--json", str(tmp_path / "r.json"), "--blend", str(tmp_path / "m.blend"))
    assert out.returncode == 0, out.stderr
    assert "verdict:" in out.stdout
    assert "Dependency cycle" not in out.stdout + out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    assert CONTRACT <= set(r) and r["params"]["layers"] == 20

    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "m.blend"))
    obs = bpy.data.objects
    by_role = {}
    for ob in obs:
        by_role.setdefault(ob.get("fibrilfit"), []).append(ob)
    assert len(by_role["slab"]) == 20 and len(by_role["anchor"]) == 20
    assert len(by_role["residue"]) == 100 and len(by_role["globule"]) == 20
    assert all(ob.rigid_body.type == "PASSIVE" for ob in by_role["slab"] + by_role["anchor"])
    assert all(ob.rigid_body.type == "ACTIVE" for ob in by_role["residue"] + by_role["globule"])
    assert {tuple(round(d, 3) for d in ob.dimensions) for ob in by_role["slab"]} == {(40, 22, 4.8)}
    assert {round(ob.dimensions.x / 2, 3) for ob in by_role["globule"]} == {15.0}
    bonds = [ob for ob in by_role["bond"] if ob.rigid_body_constraint.type == "POINT"]
    assert len(bonds) == 120
    scene = bpy.context.scene
    assert scene.rigidbody_world.point_cache.is_baked
    scene.frame_set(250)
    glob = sorted(by_role["globule"], key=lambda o: o["fibrilfit_layer"])
    got = np.array([ob.matrix_world.translation for ob in glob])
    assert np.abs(got - np.array(r["globule_centres"])).max() < 1e-3
    bpy.ops.wm.read_factory_settings(use_empty=True)


@pytest.mark.parametrize("args,name", [
    (["--linker", "0"], "linker"),
    (["--globule-diameter", "nan"], "globule_diameter"),
    (["--layers", "many"], "layers"),
    (["--frames", "0"], "frames"),
    (["--gravity", "-1"], "gravity"),
    (["--slab", "40", "22", "0"], "slab"),
    (["--bogus", "1"], "unrecognized arguments"),
])
def test_cli_bad_input_exits_2_with_one_line(args, name, tmp_path):
    out = run_cli("run", *args, "--json", str(tmp_path / "r.json"))
    assert out.returncode == 2
    assert out.stderr.strip().count("\n") == 0 and name in out.stderr
    assert "Traceback" not in out.stderr + out.stdout
    assert not (tmp_path / "r.json").exists()


def test_cli_fail_on_intersection(tmp_path):
    out = run_cli("run", "--layers", "12", "--linker", "1", "--frames", "60",
                  "--fail-on-intersection", "--json", str(tmp_path / "r.json"))
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["verdict"] == "intersection"
    assert out.returncode == 1


def test_cli_unwritable_output_refused_before_work(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    out = run_cli("run", "--json", str(blocker / "r.json"))
    assert out.returncode == 2 and "--json" in out.stderr and "Traceback" not in out.stderr


def test_cli_names_the_first_bad_output_path_in_the_check_order(tmp_path):
    """Paths are checked in exports.writers.CHECK_ORDER: --blend before --pdb, --movie before
    --save-case, whatever order the writers run in."""
    for given, named in ((["--pdb", "p.txt", "--blend", "b.txt"], "--blend"),
                         (["--save-case", "c.txt", "--movie", "m.avi"], "--movie")):
        out = cli_in_process("run", *given, "--json", str(tmp_path / "r.json"))
        assert out.returncode == 2 and out.stderr.startswith(f"fibrilfit: error: {named}: ")
        assert not (tmp_path / "r.json").exists()
