"""Both clash checks on hand-made placements, and bond stretch."""
import numpy as np
import pytest
from mathutils import Matrix

from fibrilfit import params as P
from fibrilfit.analysis import bond_stretch, bvh_clashes, sphere_clashes
from fibrilfit.builders import meshes


@pytest.fixture
def globule_mesh(scene):
    return meshes.uv_sphere("test globule", 15.0, P.GLOBULE_SEGMENTS, P.GLOBULE_RINGS)


def at(*xs, y=0.0):
    return np.array([np.array(Matrix.Translation((x, y, 0.0))) for x in xs])


def test_one_globule_never_intersects_itself(globule_mesh):
    assert bvh_clashes(globule_mesh, at(0.0)) == (0, set())


def test_overlapping_globules_intersect(globule_mesh):
    faces, pairs = bvh_clashes(globule_mesh, at(0.0, 20.0))
    assert faces > 0 and pairs == {(0, 1)}
    assert sphere_clashes(at(0.0, 20.0)[:, :3, 3], 15.0) == [(0, 1, pytest.approx(10.0))]


def test_globules_apart_are_successful(globule_mesh):
    assert bvh_clashes(globule_mesh, at(0.0, 31.0)) == (0, set())
    assert sphere_clashes(at(0.0, 31.0)[:, :3, 3], 15.0) == []


def test_touching_globules_are_not_a_clash(globule_mesh):
    assert sphere_clashes(np.array([[0, 0, 0], [30.0, 0, 0]]), 15.0) == []
    assert bvh_clashes(globule_mesh, at(0.0, 30.0))[1] == set()


def test_chain_of_three_names_only_neighbours(globule_mesh):
    centres = at(0.0, 25.0, 50.0)
    assert bvh_clashes(globule_mesh, centres)[1] == {(0, 1), (1, 2)}
    got = sphere_clashes(centres[:, :3, 3], 15.0)
    assert [(i, j) for i, j, _ in got] == [(0, 1), (1, 2)]
    assert [d for *_, d in got] == pytest.approx([5.0, 5.0])


def test_sphere_check_equals_all_pairs_on_random_clouds():
    rng = np.random.default_rng(3)
    for n in (2, 10, 300):
        c = rng.uniform(0, 150, size=(n, 3))
        d = np.linalg.norm(c[:, None] - c[None], axis=-1)
        i, j = np.nonzero(np.triu(d < 30 - 1e-3, 1))
        assert [(a, b) for a, b, _ in sphere_clashes(c, 15.0)] == list(zip(i.tolist(), j.tolist()))


def test_bond_stretch():
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0 * 1.1, 0, 0]]], dtype=float)
    s = bond_stretch(pos, [3.5, 3.5])
    assert s[0] == pytest.approx([0.0, 0.2])
