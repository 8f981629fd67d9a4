"""An outline's core is solid: a bead pushed into it comes back out (docs/model/protofilaments.md#stretched-linkers); the verdict names any chain member left inside a core."""
import bpy
import numpy as np
import pytest

from fibrilfit.geom import polygons
from fibrilfit.model.chain import rest_lengths
from fibrilfit.model import params as P
from fibrilfit import pipeline
from fibrilfit.analysis.leaks import members_inside_core
from fibrilfit.builders import build_model, meshes

U_CORE = [[-20, -11], [20, -11], [20, 11], [8, 11], [8, -3], [-8, -3], [-8, 11], [-20, 11]]


@pytest.mark.parametrize("outline", [U_CORE, U_CORE[::-1],
                                     [[0, 0], [10, 0], [10, 10], [5, 2], [0, 10]]])
def test_convex_pieces_cover_the_outline_exactly_with_convex_polygons(outline):
    pieces = meshes.convex_pieces(outline)
    assert 1 < len(pieces) < len(outline) - 1  # merged beyond the triangles
    for q in pieces:
        assert polygons.signed_area(q) > 0
        assert polygons.is_convex(q)
    assert sum(polygons.signed_area(q) for q in pieces) == pytest.approx(
        abs(polygons.signed_area(outline)))
    # a grid of points: inside the outline <=> inside exactly one piece
    g = np.stack(np.meshgrid(np.linspace(-21, 21, 43) + 0.31, np.linspace(-12, 12, 25) + 0.17),
                 -1).reshape(-1, 2)
    hits = sum(polygons.inside(q, g).astype(int) for q in pieces)
    assert np.array_equal(hits, polygons.inside(outline, g).astype(int))


def _free_bead(scene, xyz):
    """An extra active bead (not part of the model) in the rigid-body world."""
    ob = bpy.data.objects.new("probe bead", meshes.uv_sphere("probe", 1.75, 8, 4))
    ob.location = xyz
    scene.collection.objects.link(ob)
    scene.rigidbody_world.collection.objects.link(ob)
    ob.rigid_body.collision_shape = "SPHERE"
    return ob


def test_a_bead_pushed_into_an_outline_core_is_pushed_back_out(scene):
    """Found on 6CU7 + ubiquitin: during the push-apart a bead went through the wall of a
    triangle-mesh core (a hollow surface) and stayed inside, holding its linker 15-50 % long."""
    p = P.make_params(layers=3, linker=3, globule_diameter=10, core_outline=U_CORE,
                      anchor=(0, -1), frames=30, settle=False, gravity=0.0)
    model = build_model(p, scene)
    assert model.slabs[1].rigid_body.collision_shape == "COMPOUND"
    bead = _free_bead(scene, (0.0, -10.0, p.rise))  # layer 1, 1 Å inside its outer face
    pipeline.bake(model, scene)
    xyz = np.array(bead.matrix_world.translation)
    assert not polygons.inside(U_CORE, xyz[None, :2])[0], xyz
    assert xyz[1] < -11 - 1.75 + 0.1  # out through the face it went in by, resting on it
    assert members_inside_core(p, np.array([[xyz]])) == []


def test_members_inside_core_follows_each_layers_turn_and_height():
    p = P.make_params(layers=3, core_outline=U_CORE, anchor=(0, -1), twist=0.5,
                      force=True)  # a 28.6° twist: beyond ±0.2 rad needs force
    k = 2
    c, s = np.cos(k * p.twist), np.sin(k * p.twist)
    inner, outer = (0.0, -8.0), (0.0, -12.0)  # in the layer's frame: inside, outside
    turned = [(c * x - s * y, s * x + c * y) for x, y in (inner, outer)]
    pos = np.array([[[*turned[0], k * p.rise + 2.0], [*turned[1], k * p.rise],
                     [19.0, -10.0, k * p.rise],  # inside the unturned outline, not the turned one
                     [*turned[0], 3 * p.rise]]])        # above the top layer
    assert members_inside_core(p, pos) == [[0, 0]]


@pytest.mark.parametrize("layer, pf", [(0, 1), (3, 1), (3, 2), (1, 0)])
def test_the_linker_check_covers_every_chain_of_every_protofilament(scene, layer, pf):
    """A bond pulled 2 Å long in any one chain shows in the verdict's worst stretch."""
    from fibrilfit.analysis import check_model
    p = P.make_params(layers=4, linker=3, globule_diameter=10, protofilaments=3,
                      core_outline=U_CORE, anchor=(0, -25), pf_rise=1.0)
    model = build_model(p, scene)
    assert check_model(model)["max_bond_stretch"] == pytest.approx(0.0, abs=1e-5)
    globule = model.chain[layer * p.protofilaments + pf][-1]
    anchor_to_globule = np.array(globule.matrix_world.translation) - np.array(
        model.chain[layer * p.protofilaments + pf][-2].matrix_world.translation)
    out = 2.0 * anchor_to_globule / np.linalg.norm(anchor_to_globule)
    mw = globule.matrix_world.copy()
    mw.translation = mw.translation + type(mw.translation)(out.tolist())
    globule.matrix_world = mw
    result = check_model(model)
    assert result["max_bond_stretch"] == pytest.approx(2.0 / rest_lengths(p)[-1], rel=1e-3)
    assert not result["linker_intact"]
    assert result["inside_core"] == []


def test_a_periodic_cells_core_images_carry_the_solid_pieces_too(scene):
    """An image of a COMPOUND core without the pieces would collide with nothing."""
    from fibrilfit.builders.scene import TAG
    p = P.make_params(layers=4, periodic=4, linker=3, globule_diameter=10, core_outline=U_CORE,
                      anchor=(0, -1))
    model = build_model(p, scene)
    pieces = len(meshes.convex_pieces(U_CORE))
    images = [ob for coll in model.root.children for ob in coll.objects
              if ob.get(TAG) == "image_static" and ob.rigid_body.collision_shape == "COMPOUND"]
    assert images
    for image in images:
        kids = [c for c in image.children if c.get(TAG) == "core_piece"]
        assert len(kids) == pieces
        assert all(c.rigid_body.collision_shape == "CONVEX_HULL" for c in kids)
        assert all(c.name in scene.rigidbody_world.collection.objects for c in kids)
