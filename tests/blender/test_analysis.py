"""Both clash checks on hand-made placements, how they are matched, and bond stretch."""
import bpy
import numpy as np
import pytest
from mathutils import Matrix, Quaternion

from fibrilfit.model import params as P
from fibrilfit.model.answer import free_end_warnings
from fibrilfit.model.param_spec import GLOBULE_RINGS, GLOBULE_SEGMENTS
from fibrilfit import pipeline
from fibrilfit.analysis import StretchLog, bond_stretch, bvh_clashes, check_model, grazing_depth, sphere_clashes
from fibrilfit.builders import meshes


@pytest.fixture
def globule_mesh(scene):
    return meshes.uv_sphere("test globule", 15.0, GLOBULE_SEGMENTS, GLOBULE_RINGS)


def at(*xs, y=0.0):
    return np.array([np.array(Matrix.Translation((x, y, 0.0))) for x in xs])


def test_one_globule_never_intersects_itself(globule_mesh):
    assert bvh_clashes([globule_mesh], at(0.0)) == (0, set())


def test_overlapping_globules_intersect(globule_mesh):
    faces, pairs = bvh_clashes([globule_mesh], at(0.0, 20.0))
    assert faces > 0 and pairs == {(0, 1)}
    assert sphere_clashes(at(0.0, 20.0)[:, :3, 3], 15.0) == [(0, 1, pytest.approx(10.0))]


def test_globules_apart_are_successful(globule_mesh):
    assert bvh_clashes([globule_mesh], at(0.0, 31.0)) == (0, set())
    assert sphere_clashes(at(0.0, 31.0)[:, :3, 3], 15.0) == []


def test_touching_globules_are_not_a_clash(globule_mesh):
    assert sphere_clashes(np.array([[0, 0, 0], [30.0, 0, 0]]), 15.0) == []
    assert bvh_clashes([globule_mesh], at(0.0, 30.0))[1] == set()


def test_chain_of_three_names_only_neighbours(globule_mesh):
    centres = at(0.0, 25.0, 50.0)
    assert bvh_clashes([globule_mesh], centres)[1] == {(0, 1), (1, 2)}
    got = sphere_clashes(centres[:, :3, 3], 15.0)
    assert [(i, j) for i, j, _ in got] == [(0, 1), (1, 2)]
    assert [d for *_, d in got] == pytest.approx([5.0, 5.0])


def _layouts(rng):
    """Point sets that stress a grid: dense, sparse, a fibril-like helix, a line, duplicates,
    negative and far-flung coordinates."""
    k = np.arange(400)
    helix = np.c_[50 * np.cos(0.034 * k), 50 * np.sin(0.034 * k), 4.8 * k]
    yield rng.uniform(0, 150, size=(300, 3))
    yield rng.uniform(-5000, 5000, size=(200, 3))
    yield helix + rng.normal(0, 4, helix.shape)
    yield np.c_[np.arange(50) * 29.9, np.zeros(50), np.zeros(50)]
    yield np.repeat(rng.uniform(0, 40, size=(5, 3)), 3, axis=0)
    yield np.r_[rng.uniform(0, 60, size=(30, 3)), [[1e6, -1e6, 3e5]]]


@pytest.mark.parametrize("n", [0, 1, 2, 10])
def test_sphere_check_on_tiny_inputs(n):
    c = np.random.default_rng(n).uniform(0, 40, size=(n, 3))
    d = np.linalg.norm(c[:, None] - c[None], axis=-1)
    i, j = np.nonzero(np.triu(d < 30 - 1e-3, 1))
    assert [(a, b) for a, b, _ in sphere_clashes(c, 15.0)] == list(zip(i.tolist(), j.tolist()))


@pytest.mark.parametrize("tolerance", [1e-3, 0.287])
def test_sphere_check_equals_all_pairs_on_any_layout(tolerance):
    for c in _layouts(np.random.default_rng(3)):
        d = np.linalg.norm(c[:, None] - c[None], axis=-1)
        i, j = np.nonzero(np.triu(d < 30 - tolerance, 1))
        got = sphere_clashes(c, 15.0, tolerance)
        assert [(a, b) for a, b, _ in got] == list(zip(i.tolist(), j.tolist()))
        assert [x for *_, x in got] == pytest.approx((30 - d[i, j]).tolist())


def test_grazing_depth_is_twice_the_mesh_sag(scene):
    # 32 x 16 UV sphere: faces lie at least 14.8566 Å from the centre of a 15 Å sphere.
    assert grazing_depth(meshes.uv_sphere("g15", 15.0, 32, 16)) == pytest.approx(0.2869, abs=1e-3)
    assert grazing_depth(meshes.uv_sphere("g40", 40.0, 32, 16)) == pytest.approx(0.2869 * 40 / 15,
                                                                                 abs=1e-3)


def _turned_pair(rng, distance):
    """Two globules `distance` apart along a random direction, each turned at random."""
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    mats = []
    for centre in (np.zeros(3), axis * distance):
        q = rng.normal(size=4)
        rot = Quaternion(q / np.linalg.norm(q)).to_matrix().to_4x4()
        mats.append(np.array(Matrix.Translation(centre.tolist()) @ rot))
    return np.array(mats)


def test_grazing_band_bounds_what_the_mesh_can_miss(globule_mesh):
    """Deeper than the band, the BVH finds every pair however the globules are turned; spheres
    apart, it never does; within the band it depends on the turn. This is why the sphere check's
    tolerance is the band and why pairs the BVH alone names inside it count as grazing."""
    band = grazing_depth(globule_mesh)
    rng = np.random.default_rng(11)
    hits = {depth: [bool(bvh_clashes([globule_mesh], _turned_pair(rng, 30.0 - depth))[1])
                    for _ in range(25)] for depth in (band + 0.01, -0.01, band / 2)}
    assert all(hits[band + 0.01]) and not any(hits[-0.01])
    assert 0 < sum(hits[band / 2]) < 25  # turned one way they cross, another way they do not
    assert sphere_clashes(np.array([[0, 0, 0], [30 - band - 0.01, 0, 0]]), 15.0, band) != []
    assert sphere_clashes(np.array([[0, 0, 0], [30 - band + 0.01, 0, 0]]), 15.0, band) == []


def test_bvh_keep_counts_only_pairs_with_a_kept_globule(globule_mesh):
    mats = at(0.0, 25.0, 50.0, 75.0)
    faces_all, pairs_all = bvh_clashes([globule_mesh], mats)
    faces, pairs = bvh_clashes([globule_mesh], mats, keep=np.array([False, False, True, False]))
    assert pairs_all == {(0, 1), (1, 2), (2, 3)} and pairs == {(1, 2), (2, 3)}
    assert 0 < faces < faces_all


def _placed(scene, centres, **kw):
    """A built (unbaked) model with its globules moved by hand to `centres`."""
    p = P.make_params(layers=len(centres), frames=1, **kw)
    model = pipeline.build(p, scene)
    for ob, c in zip(model.globules, centres):
        ob.location = c
    bpy.context.view_layer.update()
    return model


def test_check_model_on_hand_placed_globules(scene):
    far = 1000.0
    band = 0.2869
    centres = [(far, 0, 0), (far + 29.0, 0, 0),            # overlapping by 1 Å
               (far + 60, 0, 0),                            # touching nothing
               (far, 100, 0), (far + 30.0 - band / 3, 100, 0),  # grazing
               (far, 200, 0), (far + 30.0, 200, 0)]         # touching exactly
    r = check_model(_placed(scene, centres))
    assert r["checks_agree"] and r["warnings"] == []
    assert r["sphere_check"]["clashing_pairs"] == [[0, 1, pytest.approx(1.0, abs=1e-3)]]
    assert r["sphere_check"]["tolerance"] == pytest.approx(band, abs=1e-3)
    deep = [p for p in r["clashing_pairs"] if p[:2] == [0, 1]]
    assert deep == [[0, 1, pytest.approx(1.0, abs=1e-3)]] and r["verdict"] == "intersection"
    assert {(i, j) for i, j, _ in r["clashing_pairs"]} - {(0, 1)} == {
        (i, j) for i, j, _ in r["grazing_pairs"]} <= {(3, 4)}
    assert r["layer_clashes"][:3] == [True, True, False] and r["layer_clashes"][5:] == [False, False]
    assert r["max_overlap"] == pytest.approx(1.0, abs=1e-3)


def test_scored_layers_keep_pairs_with_an_interior_globule(scene):
    # A chain of five overlapping globules; the two end layers are not scored.
    centres = [(500 + 25.0 * k, 0, 0) for k in range(5)]
    r = check_model(_placed(scene, centres, score_layers=1))
    assert r["scored_layers"] == [1, 3]
    assert [p[:2] for p in r["clashing_pairs"]] == [[0, 1], [1, 2], [2, 3], [3, 4]]
    assert r["layer_clashes"] == [None, True, True, True, None]
    r = check_model(_placed(scene, [(500, 0, 0), (525, 0, 0), (600, 0, 0), (700, 0, 0),
                                    (725, 0, 0)], score_layers=2))
    # only layer 2 is scored and it is alone: the clashing end pairs do not count
    assert r["verdict"] == "successful" and r["clashing_pairs"] == []
    assert r["layer_clashes"] == [None, None, False, None, None]


def test_bond_stretch():
    pos = np.array([[[0, 0, 0], [3.5, 0, 0], [7.0 * 1.1, 0, 0]]], dtype=float)
    s = bond_stretch(pos, [3.5, 3.5])
    assert s[0] == pytest.approx([0.0, 0.2])


def test_stretch_log_separates_the_push_apart_from_the_rest():
    log = StretchLog([1.0], tolerance=0.05)
    for s in [0.0, 8.0, 2.0, 0.3, 0.04, 0.09, 0.02, 0.01, 0.0]:
        log.add(np.array([[[0, 0, 0], [1 + s, 0, 0]]]))
    got = log.summary()
    assert got["max_bond_stretch_bake"] == pytest.approx(8.0) and got["max_bond_stretch_bake_frame"] == 2
    assert got["push_apart_end_frame"] == 5          # first frame after frame 1 within tolerance
    assert got["max_bond_stretch_after_push"] == pytest.approx(0.09)  # it stretched again later
    assert got["frames_over_tolerance"] == 4 and got["intact_from_frame"] == 7


def test_stretch_log_of_a_linker_that_never_recovers():
    log = StretchLog([1.0], tolerance=0.05, scored=slice(1, 2))
    for s in [0.0, 3.0, 0.5, 0.4]:
        log.add(np.array([[[0, 0, 0], [9.0, 0, 0]], [[0, 0, 0], [1 + s, 0, 0]]]))
    got = log.summary()  # layer 0's huge stretch is not scored
    assert got["max_bond_stretch_bake"] == pytest.approx(3.0)
    assert got["push_apart_end_frame"] is None and got["max_bond_stretch_after_push"] is None
    assert got["frames_over_tolerance"] == 3 and got["intact_from_frame"] is None


# Short linkers leave many shallow contacts: the hardest case for matching the two checks.
@pytest.mark.parametrize("linker,seed", [(3, 0), (4, 1), (4, 3), (5, 1)])
def test_both_checks_name_the_same_pairs_on_baked_models(scene, linker, seed):
    p = P.make_params(layers=12, linker=linker, seed=seed, settle=False)
    r = pipeline.run_model(p, scene)
    band = r["sphere_check"]["tolerance"]
    # nothing but the short fibril's caveat (model/answer.py free_end_warnings)
    assert r["checks_agree"] and r["warnings"] == free_end_warnings(p)
    bvh = {(i, j): d for i, j, d in r["clashing_pairs"]}
    deep = {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}
    assert deep <= set(bvh)  # every pair deeper than the band, the BVH names too
    assert {(i, j) for i, j, _ in r["grazing_pairs"]} == set(bvh) - deep
    assert all(-1e-4 < d <= band for i, j, d in r["grazing_pairs"])
    assert (r["intersecting_faces"] > 0) == bool(bvh) == (r["verdict"] == "intersection")
