"""Materials, camera, light and the rendered picture; the CLI's --render/--pdb outputs."""
import json

import bpy
import gemmi
import numpy as np
import pytest
from bpy_extras.object_utils import world_to_camera_view
from helpers import cli_in_process, run_cli

from fibrilfit import exits as ff_exits, pipeline
from fibrilfit.cli import commands as cli
from fibrilfit.model import params as P
from fibrilfit.analysis import clash_kinds, clashing_layers
from fibrilfit.analysis.verdict import chain_positions
from fibrilfit.builders import clear_model
from fibrilfit.builders.colours import CLASH_COLOR, COLORS, GRAZE_COLOR, colour_globules
from fibrilfit.exports import dressing, render


def pixels(path) -> np.ndarray:
    """RGB in 0..1, shape (height, width, 3), row 0 at the bottom (as Blender's camera view)."""
    img = bpy.data.images.load(str(path), check_existing=False)
    try:
        w, h = img.size
        flat = np.empty(w * h * 4, dtype=np.float32)
        img.pixels.foreach_get(flat)
        return flat.reshape(h, w, 4)[..., :3]
    finally:
        bpy.data.images.remove(img)


def red(rgb: np.ndarray) -> np.ndarray:
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return (r > 0.5) & (g < 0.4) & (b < 0.4) & (r > 2 * g)


def build(scene, **kw):
    pipeline.run_model(P.make_params(**kw), scene, stop_after="build")
    return pipeline.current_model(scene)


def ours(kind) -> list:
    return [d for d in kind if d.get("fibrilfit") is not None]


def test_colour_globules_reds_only_the_clashing_and_keeps_the_bake(scene):
    pipeline.run_model(P.make_params(layers=4, linker=3, seed=1, frames=60), scene)
    model = pipeline.current_model(scene)
    final = chain_positions(model)
    assert colour_globules(model, [2, 0], scene) == [0, 2]
    colours = [tuple(round(c, 3) for c in ob.color) for ob in model.globules]
    red_, grey = tuple(round(c, 3) for c in CLASH_COLOR), tuple(
        round(c, 3) for c in COLORS["globule"])
    assert colours == [red_, grey, red_, grey]
    assert tuple(model.chain[0][1].color) == pytest.approx(COLORS["residue"])  # linker untouched
    # A recolour must not throw away the bake: scrubbing back and forth gives the same end.
    scene.frame_set(1)
    scene.frame_set(60)
    assert np.abs(chain_positions(model) - final).max() < 1e-6
    pairs = [[1, 3, 0.2], [0, 3, 1.0]]
    assert clashing_layers({"verdict": "intersection", "clashing_pairs": pairs}) == [
        0, 1, 3]
    # Grazing sphere-only contacts under a successful verdict are not painted red.
    assert clashing_layers({"verdict": "successful", "clashing_pairs": pairs}) == []
    assert clashing_layers({}) == []


def test_dressing_is_tagged_reused_and_cleared_without_touching_the_user(scene, user_objects):
    user_cam = bpy.data.objects.new("My camera", bpy.data.cameras.new("My camera"))
    scene.collection.objects.link(user_cam)
    scene.camera = user_cam
    user_world = scene.world = bpy.data.worlds.new("My world")
    model = build(scene, layers=3, linker=2)
    d = dressing.dress(scene, model, [1])
    assert scene.camera == user_cam and scene.world == user_world  # theirs stay in charge
    assert d.camera.get("fibrilfit") == "camera" and d.light.get("fibrilfit") == "light"
    assert d.camera.data.get("fibrilfit") and d.light.data.get("fibrilfit")
    assert d.camera.name in model.root.all_objects and d.light.name in model.root.all_objects
    assert set(d.materials) == {"slab", "bead", "globule"}
    for mat in d.materials.values():
        assert mat.get("fibrilfit") == "material"
        kinds = {n.bl_idname for n in mat.node_tree.nodes}
        assert "ShaderNodeObjectInfo" in kinds  # colour comes from the object
    assert model.globules[0].data.materials[0] == d.materials["globule"]
    assert model.chain[0][0].data.materials[0] == d.materials["bead"]
    # Dressing again reuses everything.
    before = (len(bpy.data.materials), len(bpy.data.cameras), len(bpy.data.lights))
    dressing.dress(scene, model, [])
    assert (len(bpy.data.materials), len(bpy.data.cameras), len(bpy.data.lights)) == before
    clear_model(scene)
    for kind in (bpy.data.objects, bpy.data.materials, bpy.data.cameras, bpy.data.lights,
                 bpy.data.worlds, bpy.data.meshes, bpy.data.collections):
        assert ours(kind) == [], kind
    assert "user material" in bpy.data.materials and scene.world == user_world
    assert scene.camera == user_cam
    assert all(ob.name in scene.objects for ob in user_objects.values())


def test_an_empty_scene_gets_the_camera_and_a_world_that_clear_model_removes(scene):
    scene.world = None
    model = build(scene, layers=2, linker=1)
    d = dressing.dress(scene, model)
    assert scene.camera == d.camera and scene.world.get("fibrilfit") == "world"
    clear_model(scene)
    assert scene.camera is None and scene.world is None and ours(bpy.data.worlds) == []


@pytest.mark.parametrize("layers,aspect", [(3, 16 / 9), (60, 16 / 9), (20, 0.6)])
def test_camera_frames_every_object(scene, layers, aspect):
    model = build(scene, layers=layers, linker=4)
    w = 400
    scene.render.resolution_x, scene.render.resolution_y = w, round(w / aspect)
    d = dressing.dress(scene, model, aspect=scene.render.resolution_x / scene.render.resolution_y)
    points = dressing.model_points(model)
    from mathutils import Vector
    uv = np.array([world_to_camera_view(scene, d.camera, Vector(p)) for p in points])
    cam = d.camera.data
    assert (uv[:, 2] > cam.clip_start).all() and (uv[:, 2] < cam.clip_end).all()
    assert uv[:, :2].min() >= 0.0 and uv[:, :2].max() <= 1.0  # all inside the frame
    span = uv[:, :2].max(axis=0) - uv[:, :2].min(axis=0)
    assert span.max() > 0.8  # and the model fills it along one side


def test_render_shows_red_only_where_globules_clash(scene, tmp_path):
    model = build(scene, layers=3, linker=3)
    size = (128, 72)
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.filepath = "//mine_"
    # (the model's own colours: the legend, which has a red swatch, is tested on its own)
    calm = render.render_png(scene, tmp_path / "calm.png", clashing=[], size=size, samples=2,
                             with_legend=False)
    assert calm["engine"] == "cycles" and calm["width"] == 128 and calm["seconds"] > 0
    rgb = pixels(tmp_path / "calm.png")
    assert rgb.shape == (72, 128, 3)
    assert rgb.std() > 0.05 and not red(rgb).any()  # a picture, and nothing red in it
    render.render_png(scene, tmp_path / "clash.png", clashing=[2], size=size, samples=2,
                      with_legend=False)
    rgb = pixels(tmp_path / "clash.png")
    assert red(rgb).sum() > 100
    # The top globule (layer 2) is the red one: its centre's pixel is red.
    cam = next(ob for ob in scene.objects if ob.get("fibrilfit") == "camera")
    u, v, _ = world_to_camera_view(scene, cam, model.globules[2].matrix_world.translation)
    assert red(rgb[int(v * size[1]), int(u * size[0])])
    # The scene's own render settings came back.
    assert scene.render.engine == "BLENDER_WORKBENCH" and scene.render.filepath == "//mine_"
    assert not list(tmp_path.glob(".*part*"))  # no temporary file left behind


def test_render_refuses_bad_requests_with_one_line(scene, tmp_path):
    with pytest.raises(render.RenderError, match="no FibrilFit model"):
        render.render_png(scene, tmp_path / "x.png")
    build(scene, layers=1)
    with pytest.raises(render.RenderError, match="size"):
        render.render_png(scene, tmp_path / "x.png", size=(8, 8))
    with pytest.raises(render.RenderError, match="engine"):
        render.render_png(scene, tmp_path / "x.png", engine="eevee")
    assert not (tmp_path / "x.png").exists()


def test_workbench_renders_headless(tmp_path):
    out = run_cli("run", "--layers", "2", "--linker", "2", "--frames", "5", "--render",
                  str(tmp_path / "w.png"), "--render-engine", "workbench", "--render-size", "64x36",
                  "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["render"]["engine"] == "workbench" and r["render"]["samples"] is None
    bpy.ops.wm.read_factory_settings(use_empty=True)
    assert pixels(tmp_path / "w.png").shape == (36, 64, 3)


def test_a_failed_render_keeps_the_other_outputs(tmp_path, monkeypatch, capsys):
    def broken(scene, tmp):
        raise render.RenderError("no memory for tiles")
    monkeypatch.setattr(render, "render_frame", broken)
    # Cycles probes its devices once a process, printing "CUEW initialization failed" without
    # CUDA, which the failure would quote as Blender's last words: probe first, as any earlier
    # test that renders did (alone, this test failed on it: make test-alone).
    with render.captured_output():
        bpy.context.preferences.addons["cycles"].preferences.refresh_devices()
    code = cli.main(["run", "--layers", "2", "--linker", "2", "--frames", "5",
                     "--json", str(tmp_path / "r.json"), "--pdb", str(tmp_path / "m.pdb"),
                     "--pdb-frames", "all", "--blend", str(tmp_path / "m.blend"), "--render", str(tmp_path / "m.png")])
    err = capsys.readouterr().err
    bpy.ops.wm.read_factory_settings(use_empty=True)
    assert code == ff_exits.EXIT_OUTPUT_FAILED == 3
    assert err.strip().splitlines() == ["fibrilfit: error: --render failed: no memory for tiles"]
    assert not (tmp_path / "m.png").exists() and not list(tmp_path.glob(".*part*"))
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["render"] == {"error": "no memory for tiles"} and r["verdict"]
    assert (tmp_path / "m.blend").stat().st_size > 0
    st = gemmi.read_structure(str(tmp_path / "m.pdb"))  # frames 1 and 5
    assert len(st) == 2 and [m.count_atom_sites() for m in st] == [6, 6]
    assert r["pdb"]["frames"] == [1, 5]


@pytest.mark.parametrize("args,needle", [
    (["--render", "x.jpg"], "--render"),
    (["--render", "x.png", "--render-size", "10x10"], "--render-size"),
    (["--render", "x.png", "--render-size", "wide"], "--render-size"),
    (["--render", "x.png", "--render-samples", "0"], "--render-samples"),
    (["--render", "x.png", "--render-engine", "eevee"], "--render-engine"),
    (["--pdb", "x.cif"], "--pdb"),
    (["--pdb", "x.pdb", "--pdb-frames", "some"], "--pdb-frames"),
    (["--pdb", "x.pdb", "--layers", "3000", "--linker", "1"], "--pdb"),
])
def test_bad_output_options_exit_2_before_any_work(args, needle, tmp_path):
    args = [str(tmp_path / a) if a.startswith("x.") else a for a in args]
    out = cli_in_process("run", *args, "--json", str(tmp_path / "r.json"))
    assert out.returncode == 2, out.stderr
    assert out.stderr.strip().count("\n") == 0 and needle in out.stderr
    assert "Traceback" not in out.stderr and not list(tmp_path.iterdir())


def test_blend_opens_dressed_and_scrubbable(tmp_path):
    out = run_cli("run", "--layers", "6", "--linker", "2", "--frames", "40", "--seed", "1",
                  "--blend", str(tmp_path / "m.blend"), "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "m.blend"))
    try:
        scene = bpy.context.scene
        assert scene.camera is not None and scene.camera.get("fibrilfit") == "camera"
        assert any(ob.get("fibrilfit") == "light" for ob in scene.objects)
        assert scene.world.get("fibrilfit") == "world"
        globules = sorted((ob for ob in scene.objects if ob.get("fibrilfit") == "globule"),
                          key=lambda ob: ob["fibrilfit_layer"])
        assert all(ob.data.materials[0].get("fibrilfit") == "material" for ob in globules)
        deep, grazing = clash_kinds(r)  # deep clashes red, grazes pale red
        assert sorted(deep + grazing) == clashing_layers(r)
        for k, ob in enumerate(globules):
            want = (CLASH_COLOR if k in deep else GRAZE_COLOR if k in grazing
                    else COLORS["globule"])
            assert tuple(ob.color) == pytest.approx(want)
        scene.frame_set(1)
        scene.frame_set(40)
        got = np.array([ob.matrix_world.translation for ob in globules])
        assert np.abs(got - np.array(r["globule_centres"])).max() < 1e-3
    finally:
        bpy.ops.wm.read_factory_settings(use_empty=True)


def test_done_when_pdb_and_picture_of_the_20_layer_model(tmp_path):
    """The issue's check: --layers 20 --linker 3 --seed 1 --pdb m.pdb --render m.png."""
    out = run_cli("run", "--layers", "20", "--linker", "3", "--seed", "1",
                  "--pdb", str(tmp_path / "m.pdb"), "--render", str(tmp_path / "m.png"),
                  "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    st = gemmi.read_structure(str(tmp_path / "m.pdb"))
    assert len(st) == 1 and st[0].count_atom_sites() == 80 and len(st[0]) == 20
    glb = np.array([[res[0].pos.x, res[0].pos.y, res[0].pos.z]
                    for ch in st[0] for res in ch if res.name == "GLB"])
    assert np.abs(glb - np.array(r["globule_centres"])).max() < 0.01

    assert r["render"]["width"] >= 640 and r["render"]["height"] >= 360
    rgb = pixels(tmp_path / "m.png")
    assert rgb.shape == (360, 640, 3) and rgb.std() > 0.05
    assert r["verdict"] == "intersection" and r["clashing_pairs"]
    assert red(rgb).mean() > 0.05  # the clashing globules are red
    r_, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    assert ((b > r_ + 0.03) & (b > 0.4)).any()  # blue-grey slabs
    assert ((r_ > 0.5) & (g > 0.4) & (b < 0.25)).any()  # yellow linker beads
