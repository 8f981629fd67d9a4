"""Real fibril geometry (issue #14): protofilaments, a core outline, anchors anywhere."""
import importlib.util
import json
import math

import numpy as np
import pytest
from helpers import ROOT, run_cli

from fibrilfit.geom import polygons
from fibrilfit.model.chain import chain_radii, chain_x
from fibrilfit.model import helix, params as P
from fibrilfit.model.param_checks import estimated_objects
from fibrilfit import pipeline
from fibrilfit.builders import build_model, find_model
from fibrilfit.builders.stored import stored_params
from fibrilfit.model.start_layout import rest_positions as chain_positions

# The tutorial's parameters as they were before this issue: the default must keep every one.
OLD_DEFAULTS = {
    "slab": [40.0, 22.0, 4.8], "residue_radius": 1.75, "residue_spacing": 3.5, "linker": 6,
    "globule_diameter": 30.0, "layers": 20, "rise": 4.8, "twist": 0.034, "gravity": 0.5,
    "seed": 0, "time_scale": 2.0, "frames": 250, "substeps": 10, "solver_iterations": 10,
    "stretch_tolerance": 0.05, "settle": True, "settle_speed": 0.3, "settle_frames": 20,
    "score_layers": 0}
# A U-shaped core (40 × 22 Å, a 16 Å wide notch 14 Å deep opening towards +Y), anchor in the notch.
U_CORE = [[-20, -11], [20, -11], [20, 11], [8, 11], [8, -3], [-8, -3], [-8, 11], [-20, 11]]
TWO_ONE = {"protofilaments": 2, "pf_rotation": 3.1294, "pf_rise": 2.34}  # 179.30°, 2.34 Å


def test_default_only_gains_keys_and_keeps_the_tutorials_chain():
    d = P.Params().to_dict()
    assert {k: d[k] for k in OLD_DEFAULTS} == OLD_DEFAULTS
    assert list(d)[:len(OLD_DEFAULTS)] == list(OLD_DEFAULTS)  # old keys first, in their order
    geometry = {"protofilaments": 1, "pf_rotation": None, "pf_rise": 0.0, "core_outline": None,
                "anchor": None}  # other issues add keys of their own beside these
    assert {k: d[k] for k in geometry} == geometry
    p = P.DEFAULTS
    assert (p.anchor_xy, p.pf_angle, p.chains) == ((21.75, 0.0), 2 * math.pi, 20)
    assert p.chain_layout.rule == "radial"
    # the rest layout, float for float, is the tutorial's formula
    angle, height, x = np.arange(20) * 0.034, np.arange(20) * 4.8, np.asarray(chain_x(p))
    pos = chain_positions(p)
    assert np.array_equal(pos[..., 0], np.cos(angle)[:, None] * x)
    assert np.array_equal(pos[..., 1], np.sin(angle)[:, None] * x)
    assert np.array_equal(pos[..., 2], np.broadcast_to(height[:, None], pos.shape[:2]))


@pytest.mark.parametrize("values", [{}, TWO_ONE, {"protofilaments": 3, "pf_rise": -1.5},
                                    {"core_outline": U_CORE, "anchor": (0, -1)},
                                    {"anchor": (-30, 5), "protofilaments": 2}])
def test_parameters_round_trip_through_dict_json_and_the_scene(values):
    p = P.make_params(**values)
    assert P.make_params(**p.to_dict()) == p
    assert P.make_params(**json.loads(json.dumps(p.to_dict()))) == p
    assert P.make_params(**stored_params(p)) == p  # the ID property leaves out None
    assert None not in stored_params(p).values()


def test_two_protofilaments_build_two_chains_per_layer_179_3_deg_and_2_34_A_apart(scene):
    p = P.make_params(layers=5, linker=3, **TWO_ONE)
    model = build_model(p, scene)
    assert len(model.chain) == 10 and len(model.slabs) == 5 and len(model.constraints) == 10
    assert model.slabs[0].rigid_body.collision_shape == "BOX"
    layer, pf = helix.chain_layers(p)
    for c, members in enumerate(model.chain):
        assert len(members) == 4
        assert {ob["fibrilfit_layer"] for ob in members} == {layer[c]}
        assert {ob["fibrilfit_protofilament"] for ob in members} == {pf[c]}
    for k in range(5):
        a0, a1 = (np.array(model.chain[2 * k + j][0].matrix_world.translation) for j in (0, 1))
        turn = math.degrees(math.atan2(a1[1], a1[0]) - math.atan2(a0[1], a0[0])) % 360
        assert turn == pytest.approx(179.30, abs=0.01)
        assert a1[2] - a0[2] == pytest.approx(2.34, abs=1e-4)
        assert a0[2] == pytest.approx(4.8 * k, abs=1e-4)
        assert math.hypot(*a1[:2]) == pytest.approx(21.75, abs=1e-4)
    again = find_model(scene)
    assert [[ob.name for ob in c] for c in again.chain] == [[ob.name for ob in c]
                                                            for c in model.chain]
    assert again.params == p
    assert len(scene.objects) == estimated_objects(p) == 5 * (1 + 2 * 7)


def _layer_frame(p, xyz):
    """Positions (n, 3) turned back into the frame of the layer at their height, and whether
    that height lies within the fibril's core stack."""
    k = np.rint(xyz[:, 2] / p.rise)
    within = (k >= 0) & (k <= p.layers - 1)
    k = np.clip(k, 0, p.layers - 1)
    return polygons.rotate(xyz[:, :2], 0.0) if p.twist == 0 else np.stack(
        [polygons.rotate(q, -kk * p.twist) for q, kk in zip(xyz[:, :2], k)]), within


def test_a_concave_core_starts_and_ends_with_every_bead_outside(scene):
    p = P.make_params(layers=4, linker=4, globule_diameter=10, core_outline=U_CORE,
                      anchor=(0, -1), frames=80, settle=False, gravity=3.0, seed=2)
    assert p.chain_layout.rule == "edge normal"  # radial (down) points into the notch's floor
    model = build_model(p, scene)
    slab = model.slabs[0]
    assert (slab.rigid_body.type, slab.rigid_body.collision_shape) == ("PASSIVE", "COMPOUND")
    assert tuple(slab.dimensions) == pytest.approx((40, 22, 4.8), abs=1e-4)
    radii = np.array(chain_radii(p))
    start = chain_positions(p)
    for chain in start:
        xy, _ = _layer_frame(p, chain)
        assert not polygons.blocked(U_CORE, xy[1:], radii[1:]).any()
        assert not polygons.inside(U_CORE, xy[:1]).any()
    result = pipeline.run_model(p, scene)
    end = np.array([[ob.matrix_world.translation for ob in c] for c in find_model(scene).chain])
    assert np.abs(end - start).max() > 1.0  # they did move
    for chain in end:
        xy, within = _layer_frame(p, chain)
        assert not (polygons.inside(U_CORE, xy) & within).any()
    assert result["linker_intact"]


def test_k2_clashes_name_both_globules_by_layer_and_protofilament(scene):
    # Frame 1 of a 3-layer model: 30 Å globules 4.8 Å apart all overlap.
    p = P.make_params(layers=3, linker=2, frames=1, **TWO_ONE)
    r = pipeline.run_model(p, scene)
    assert r["verdict"] == "intersection" and r["clashing_pairs"]
    layer, pf = helix.chain_layers(p)
    assert r["clashing_chains"] == [[[int(layer[i]), int(pf[i])], [int(layer[j]), int(pf[j])], d]
                                    for i, j, d in r["clashing_pairs"]]
    hit = {c for i, j, _ in r["clashing_pairs"] for c in (i, j)}
    assert r["chain_clashes"] == [c in hit for c in range(6)]
    assert r["layer_clashes"] == [any(c in hit for c in (2 * k, 2 * k + 1)) for k in range(3)]
    assert len(r["globule_centres"]) == 6
    one = pipeline.run_model(p.replace(protofilaments=1, pf_rotation=None, pf_rise=0), scene)
    assert "clashing_chains" not in one and "chain_clashes" not in one


@pytest.mark.parametrize("outline,args,name", [
    ([[0, 0], [10, 0]], [], "core_outline"),
    ([[0, 0], [10, 10], [10, 0], [0, 10]], [], "core_outline"),
    ("not json [", [], "core_outline"),
    (None, ["--anchor", "0", "5"], "anchor"),
    (None, ["--protofilaments", "7"], "protofilaments"),
    (None, ["--protofilaments", "2", "--pf-rotation", "0"], "pf_rotation"),
], ids=["two-points", "bow-tie", "unreadable", "anchor-inside", "k7", "anchors-on-top"])
def test_cli_refuses_bad_geometry_with_exit_2_and_writes_nothing(outline, args, name, tmp_path):
    if outline is not None:
        path = tmp_path / "in" / "outline.json"
        path.parent.mkdir()
        path.write_text(outline if isinstance(outline, str) else json.dumps(outline))
        args = [*args, "--core-outline", str(path)]
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    out = run_cli("run", *args, "--json", str(out_dir / "r.json"), "--pdb", str(out_dir / "r.pdb"))
    assert out.returncode == 2, out.stderr
    assert out.stderr.strip().startswith(f"fibrilfit: error: {name}: ")
    assert "\n" not in out.stderr.strip() and "Traceback" not in out.stderr
    assert list(out_dir.iterdir()) == []


def test_cli_reads_an_outline_file_into_the_result(tmp_path):
    (tmp_path / "u.json").write_text(json.dumps(U_CORE))
    out = run_cli("run", "--core-outline", str(tmp_path / "u.json"), "--anchor", "0", "-1",
                  "--layers", "2", "--linker", "6", "--protofilaments", "1",
                  "--stop-after", "build", "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["params"]["core_outline"] == [[float(x), float(y)] for x, y in U_CORE]
    assert r["params"]["anchor"] == [0.0, -1.0]
    assert P.make_params(**r["params"]).core_outline == tuple(map(tuple, r["params"]["core_outline"]))


def _bench(name):
    spec = importlib.util.spec_from_file_location(f"bench_{name}", ROOT / "bench" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("case", ["notch floor", "notch corner", "floor at a layer seam",
                                  "falls into the notch from outside"])
def test_a_bead_rests_in_the_notch_of_a_concave_mesh_core(scene, case):
    """Bullet's MESH shape (what an outline's core used before its convex pieces) holds a bead
    pushed into a concave notch:
    it neither sinks in nor falls through (bench/concave_core.py measures CONVEX_HULL too)."""
    probe = _bench("concave_core").probe
    r = probe("MESH", case, frames=60)
    assert not r["ever_inside"] and r["worst_gap"] > -0.05, r
    assert r["end"] == "resting on the core", r
    assert r["end_xyz"][1] == pytest.approx(-3 + 1.75, abs=0.05)  # on the notch's floor


def test_a_convex_hull_would_fill_the_notch(scene):
    r = _bench("concave_core").probe("CONVEX_HULL", "falls into the notch from outside", frames=60)
    assert r["end_xyz"][1] > 11  # held on the hull's lid over the notch: why cores use MESH


def test_protofilaments_have_their_own_colours_and_clashes_turn_red(scene):
    from fibrilfit.builders.colours import CLASH_COLOR, colour_globules, part_colour
    model = build_model(P.make_params(layers=2, linker=2, **TWO_ONE), scene)
    globules = [tuple(round(v, 4) for v in ob.color) for ob in model.globules]
    beads = [tuple(round(v, 4) for v in c[1].color) for c in model.chain]
    assert globules[0] == globules[2] != globules[1] == globules[3]
    assert beads[0] == beads[2] != beads[1] == beads[3]
    assert part_colour("globule", 0) == (0.7, 0.72, 0.7, 1.0)  # protofilament 0: the tutorial's
    assert colour_globules(model, [1]) == [1]
    shown = [tuple(ob.color) for ob in model.globules]
    assert shown[1] == pytest.approx(CLASH_COLOR)
    assert [s == pytest.approx(part_colour("globule", c % 2)) for c, s in enumerate(shown)] == [
        True, False, True, True]


def test_k2_scores_every_protofilament_of_the_scored_layers(scene):
    p = P.make_params(layers=4, linker=2, frames=1, score_layers=1, **TWO_ONE)
    r = pipeline.run_model(p, scene)
    assert r["scored_layers"] == [1, 2]
    assert [v is None for v in r["layer_clashes"]] == [True, False, False, True]
    assert [v is None for v in r["chain_clashes"]] == [True, True, False, False, False, False,
                                                       True, True]
    layer, _ = helix.chain_layers(p)
    assert all(1 <= layer[i] <= 2 or 1 <= layer[j] <= 2 for i, j, _ in r["clashing_pairs"])
    assert r["clashing_pairs"]  # frame 1: the overlapping start
