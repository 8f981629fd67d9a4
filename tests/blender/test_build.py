"""The built model: counts, rigid-body setup, geometry per layer, constraint wiring, scene safety."""
import math

import bpy
import numpy as np
import pytest
from helpers import snapshot_user

from fibrilfit.model import params as P
from fibrilfit.builders import build_model, clear_model, find_model


def roles(scene):
    out = {}
    for ob in scene.objects:
        out.setdefault(ob.get("fibrilfit"), []).append(ob)
    return out


def test_counts_types_and_shapes(scene):
    build_model(P.DEFAULTS, scene)
    r = roles(scene)
    assert {k: len(v) for k, v in r.items()} == {
        "slab": 20, "anchor": 20, "residue": 100, "globule": 20, "bond": 120}
    for ob in r["slab"]:
        assert (ob.rigid_body.type, ob.rigid_body.collision_shape) == ("PASSIVE", "BOX")
        assert tuple(ob.dimensions) == pytest.approx((40, 22, 4.8), abs=1e-4)
    for ob in r["anchor"]:
        assert (ob.rigid_body.type, ob.rigid_body.collision_shape) == ("PASSIVE", "SPHERE")
    for ob in r["residue"]:
        assert (ob.rigid_body.type, ob.rigid_body.collision_shape) == ("ACTIVE", "SPHERE")
        assert tuple(ob.dimensions) == pytest.approx((3.5, 3.5, 3.5), abs=1e-4)
    for ob in r["globule"]:
        assert (ob.rigid_body.type, ob.rigid_body.collision_shape) == ("ACTIVE", "SPHERE")
        assert tuple(ob.dimensions) == pytest.approx((30, 30, 30), abs=1e-4)
        assert (len(ob.data.polygons)) == 32 * 16
    for ob in r["bond"]:
        assert ob.rigid_body_constraint.type == "POINT"
    rbw = scene.rigidbody_world
    assert len(rbw.collection.objects) == 160 and len(rbw.constraints.objects) == 120
    # shared meshes: one per kind, not one per object
    assert len({ob.data.name for ob in r["residue"] + r["anchor"]}) == 1
    assert len({ob.data.name for ob in r["globule"]}) == 1


def test_each_layer_is_raised_and_twisted(scene):
    model = build_model(P.make_params(layers=12), scene)
    for k, members in enumerate(model.chain):
        anchor = members[0].matrix_world.translation
        assert math.hypot(anchor.x, anchor.y) == pytest.approx(21.75, abs=1e-4)
        assert anchor.z == pytest.approx(4.8 * k, abs=1e-4)
        assert math.atan2(anchor.y, anchor.x) == pytest.approx(0.034 * k, abs=1e-6)
        slab = model.slabs[k]
        assert slab.matrix_world.to_euler().z == pytest.approx(0.034 * k, abs=1e-6)
        glob = members[-1].matrix_world.translation
        assert math.hypot(glob.x, glob.y) == pytest.approx(21.75 + 5 * 3.5 + 1.75 + 15, abs=1e-4)


def test_constraints_chain_anchor_to_globule(scene):
    model = build_model(P.make_params(layers=3, linker=4), scene)
    for members, bonds in zip(model.chain, model.constraints):
        assert len(bonds) == 4
        pairs = [(b.rigid_body_constraint.object1, b.rigid_body_constraint.object2) for b in bonds]
        assert pairs == list(zip(members, members[1:]))
        assert members[0].get("fibrilfit") == "anchor" and members[-1].get("fibrilfit") == "globule"
        for b, (a, c) in zip(bonds, pairs):  # the pivot lies on the bond, where the two touch
            pa, pb, pv = (np.array(o.matrix_world.translation) for o in (a, c, b))
            assert np.linalg.norm(pv - pa) + np.linalg.norm(pb - pv) == pytest.approx(
                np.linalg.norm(pb - pa), abs=1e-4)


def test_everything_lives_under_the_owned_collection(scene):
    model = build_model(P.make_params(layers=2), scene)
    assert set(scene.objects) == set(model.root.all_objects)
    assert find_model(scene).params == model.params


def test_user_objects_survive_build_rebuild_and_clear(scene, user_objects):
    before = snapshot_user(user_objects)
    build_model(P.make_params(layers=3), scene)
    build_model(P.make_params(layers=4, linker=2), scene)
    assert snapshot_user(user_objects) == before
    assert len([o for o in scene.objects if o.get("fibrilfit") == "globule"]) == 4
    assert len(scene.objects) == 4 + 4 * (2 * 2 + 2)
    clear_model(scene)
    assert snapshot_user(user_objects) == before
    assert set(scene.objects) == set(user_objects.values())
    assert not [d for d in (*bpy.data.meshes, *bpy.data.materials, *bpy.data.collections)
                if d.get("fibrilfit")]
    assert bpy.data.materials.get("user material") and bpy.data.collections.get("globula")


def test_bad_params_leave_the_scene_untouched(scene):
    build_model(P.make_params(layers=2), scene)
    names = sorted(o.name for o in scene.objects)
    with pytest.raises(P.ParamError):
        build_model(P.Params(linker=0), scene)
    assert sorted(o.name for o in scene.objects) == names


def test_find_model_trusts_the_params_it_was_built_with_while_they_are_unchanged(scene):
    """A Params is validated once: looking the model up again does not validate it anew,
    unless the stored values changed (then they are validated from the store)."""
    from fibrilfit.builders.stored import params_of
    from fibrilfit.model import params as P
    p = P.make_params(layers=3, linker=2)
    model = build_model(p, scene)
    assert find_model(scene).params is p
    model.root["params"]["linker"] = 4  # changed behind its back (by hand, or by undo)
    again = params_of(model.root)
    assert again is not p and again == p.replace(linker=4)
