"""The fast BVH check (broad phase + numpy-built tree) gives the tutorial's join's faces and pairs.

`reference` below is the straightforward procedure: every globule joined into one BVHTree, the
self-overlap at epsilon 1e-5, faces of one globule never counted against each other.
"""
import numpy as np
import pytest
from mathutils import Euler, Matrix
from mathutils.bvhtree import BVHTree

from fibrilfit.model import params as P
from fibrilfit.model.param_spec import GLOBULE_RINGS, GLOBULE_SEGMENTS
from fibrilfit.analysis import bvh_clashes
from fibrilfit.analysis.clashes import candidate_pairs, facing_faces, mesh_arrays
from fibrilfit.builders import meshes
from fibrilfit.model.start_layout import rest_positions as chain_positions
from fibrilfit.model.helix import layer_transforms


def reference(mesh, matrices):
    verts, starts, loops = mesh_arrays(mesh)
    world = np.einsum("nij,vj->nvi", matrices[:, :3, :3], verts) + matrices[:, None, :3, 3]
    bounds = np.append(starts, len(loops))
    polys = [loops[a:b] for a, b in zip(bounds[:-1], bounds[1:])]
    joined = [(poly + g * len(verts)).tolist() for g in range(len(matrices)) for poly in polys]
    tree = BVHTree.FromPolygons(world.reshape(-1, 3).tolist(), joined, epsilon=1e-5)
    overlap = np.array(tree.overlap(tree), dtype=np.int64).reshape(-1, 2)
    owner = overlap // len(polys)
    between = owner[:, 0] != owner[:, 1]
    pairs = {(int(min(a, b)), int(max(a, b))) for a, b in owner[between]}
    return int(np.unique(overlap[between]).size), pairs


@pytest.fixture
def globule_mesh(scene):
    return meshes.uv_sphere("test globule", 15.0, GLOBULE_SEGMENTS, GLOBULE_RINGS)


def placed(centres, rng, scale=1.0):
    out = []
    for c in centres:
        rot = Euler(rng.uniform(-np.pi, np.pi, 3)).to_matrix().to_4x4()
        out.append(np.array(Matrix.Translation(c) @ rot @ Matrix.Scale(scale, 4)))
    return np.array(out)


@pytest.mark.parametrize("seed", range(6))
def test_random_clouds_match_the_joined_tree(globule_mesh, seed):
    rng = np.random.default_rng(seed)
    mats = placed(rng.uniform(0, 70, size=(14, 3)), rng)
    got, want = bvh_clashes([globule_mesh], mats), reference(globule_mesh, mats)
    assert got == want
    assert want[0] > 0  # the cloud is dense enough to test something


@pytest.mark.parametrize("distance", [29.0, 29.6, 29.9, 29.99, 30.0, 30.001, 30.5])
def test_grazing_pairs_match_the_joined_tree(globule_mesh, distance):
    """Near contact, where the inscribed 32x16 mesh decides, in several orientations."""
    rng = np.random.default_rng(int(distance * 1000))
    centres = [(x * 40.0, 0.0, 0.0) for x in range(8)]
    second = [(c[0] + distance * u[0], distance * u[1], distance * u[2])
              for c, u in zip(centres, [v / np.linalg.norm(v) for v in rng.normal(size=(8, 3))])]
    mats = np.concatenate([placed(centres, rng), placed(second, rng)])
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)


def test_poles_touching_end_to_end_match(globule_mesh):
    """Unrotated globules stacked 30 Å apart touch pole to pole: the bounding spheres just meet."""
    mats = np.array([np.array(Matrix.Translation((0, 0, 30.0 * k))) for k in range(4)])
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)


def test_as_built_fibril_matches(globule_mesh):
    """Every globule overlaps its neighbours: the broad phase keeps all of them."""
    p = P.make_params(layers=8)
    angle, _ = layer_transforms(p)
    centres = chain_positions(p)[:, -1]
    mats = np.array([np.array(Matrix.Translation(c) @ Matrix.Rotation(a, 4, "Z"))
                     for c, a in zip(centres, angle)])
    got = bvh_clashes([globule_mesh], mats)
    assert got == reference(globule_mesh, mats)
    assert {(i, j) for i in range(8) for j in range(i + 1, min(i + 6, 8))} <= got[1]


def test_scaled_globules_match(globule_mesh):
    rng = np.random.default_rng(11)
    mats = placed(rng.uniform(0, 90, size=(10, 3)), rng, scale=1.6)
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)


def test_broad_phase_keeps_every_overlapping_pair(globule_mesh):
    rng = np.random.default_rng(5)
    mats = placed(rng.uniform(0, 80, size=(30, 3)), rng)
    candidates = {tuple(c) for c in candidate_pairs([globule_mesh], mats).tolist()}
    assert reference(globule_mesh, mats)[1] <= candidates
    far = np.linalg.norm(mats[:, None, :3, 3] - mats[None, :, :3, 3], axis=-1) > 30.01
    assert not any(far[i, j] for i, j in candidates)


def test_stretched_and_sheared_globules_match(globule_mesh):
    rng = np.random.default_rng(23)
    mats = placed(rng.uniform(0, 80, size=(12, 3)), rng)
    for m in mats:
        m[:3, :3] = m[:3, :3] @ np.array([[1.3, 0.2, 0.0], [0.0, 0.8, 0.0], [0.1, 0.0, 1.1]])
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)


def test_only_faces_facing_a_partner_go_into_the_trees(globule_mesh):
    mats = np.array([np.array(Matrix.Translation((28.0 * k, 0, 0))) for k in range(3)])
    keep = facing_faces(globule_mesh, mats, np.array([[0, 1], [1, 2]]))
    assert 0 < keep[0].sum() < keep[1].sum() < len(globule_mesh.polygons) / 2
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)


def test_a_flattened_globule_matches(globule_mesh):
    """A matrix with no inverse (scale 0 on one axis): all its faces are kept."""
    mats = np.array([np.eye(4), np.eye(4), np.eye(4)])
    mats[0, 2, 2] = 0.0
    mats[1, 0, 3], mats[2, 0, 3] = 20.0, 45.0
    assert bvh_clashes([globule_mesh], mats) == reference(globule_mesh, mats)
