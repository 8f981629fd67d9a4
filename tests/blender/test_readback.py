"""Bulk placement at build and bulk reads of world matrices equal the object-by-object way."""
import bpy
import numpy as np
import pytest
from mathutils import Matrix

from fibrilfit.model import params as P
from fibrilfit.builders import build_model
from fibrilfit.pipeline import bake
from fibrilfit.builders.readback import MatrixReader


def one_by_one(objects):
    return np.array([np.array(ob.matrix_world) for ob in objects])


def test_build_sets_location_rotation_and_a_matching_world_matrix(scene):
    model = build_model(P.make_params(layers=4, linker=3), scene)
    objects = list(model.root.all_objects)
    before = one_by_one(objects)
    for ob, mat in zip(objects, before):
        expected = Matrix.LocRotScale(ob.location, ob.rotation_euler, ob.scale)
        assert np.allclose(mat, np.array(expected), atol=1e-5), ob.name
    bpy.context.view_layer.update()  # the depsgraph recomputes them from location and rotation
    assert np.allclose(one_by_one(objects), before, atol=1e-5)
    for ob in model.globules:
        assert tuple(ob.color) == pytest.approx((0.7, 0.72, 0.7, 1.0))
    for ob in (b for bonds in model.constraints for b in bonds):
        assert ob.empty_display_size == pytest.approx(1.75)


def test_reader_equals_matrix_world_during_a_bake(scene):
    model = build_model(P.make_params(layers=3, linker=2, frames=8), scene)
    chain = [ob for members in model.chain for ob in members]
    reader = MatrixReader(chain, (scene.rigidbody_world.collection,))
    assert reader.bulk
    start = reader.positions().copy()
    seen = []

    def on_frame(frame, positions):
        assert np.array_equal(reader.matrices(), one_by_one(chain))
        assert np.array_equal(positions.reshape(-1, 3), one_by_one(chain)[:, :3, 3])
        seen.append(frame)

    bake(model, scene, on_frame=on_frame)
    assert seen == list(range(1, 9))
    # after the bake the reader gives where the bodies went, not where they were built: each
    # chain's free end (its globule) moved 2.9-27 Å in 8 frames (bpy 5.0.1); the anchors stay
    end = reader.positions()
    assert np.array_equal(end, one_by_one(chain)[:, :3, 3])
    moved = np.linalg.norm(end - start, axis=1)
    ends = np.cumsum([len(members) for members in model.chain])
    assert (moved[ends - 1] > 1.0).all() and moved.max() > 10.0, moved
    starts = np.concatenate([[0], ends[:-1]])  # each chain's first body: its anchor
    assert np.allclose(moved[starts], 0.0), moved


def test_reader_finds_a_collection_and_follows_its_changes(scene):
    model = build_model(P.make_params(layers=3, linker=2), scene)
    reader = MatrixReader(model.globules)
    assert reader.bulk
    part = next(c for c in model.root.children if c.get("fibrilfit") == "globules")
    extra = bpy.data.objects.new("user thing", None)
    extra.matrix_world = Matrix.Translation((1, 2, 3))
    part.objects.link(extra)
    first = model.globules[0]
    part.objects.unlink(first)  # the same length, but every member moved up one place
    part.objects.link(first)
    part.objects.unlink(extra)
    assert [ob.name for ob in part.objects] != [ob.name for ob in model.globules]
    model.globules[1].matrix_world = Matrix.Translation((5, 6, 7))
    assert np.array_equal(reader.matrices(), one_by_one(model.globules))
    assert reader.bulk


def test_reader_falls_back_when_no_collection_holds_them_all(scene):
    a = bpy.data.objects.new("a", None)
    b = bpy.data.objects.new("b", None)
    for ob, coll in ((a, "one"), (b, "two")):
        c = bpy.data.collections.new(coll)
        scene.collection.children.link(c)
        c.objects.link(ob)
    a.matrix_world = Matrix.Translation((1, 0, 0))
    b.matrix_world = Matrix.Rotation(0.3, 4, "Z")
    reader = MatrixReader([b, a])
    assert not reader.bulk
    assert np.array_equal(reader.matrices(), one_by_one([b, a]))
    assert MatrixReader([]).positions().shape == (0, 3)


def test_reader_reads_several_collections_together(scene):
    model = build_model(P.make_params(layers=3, linker=3), scene)
    chain = [ob for members in model.chain for ob in members]
    reader = MatrixReader(chain, model.root.children)  # anchors, linkers, globules: no one holds all
    assert reader.bulk
    chain[4].matrix_world = Matrix.Translation((3, 2, 1))
    assert np.array_equal(reader.matrices(), one_by_one(chain))
