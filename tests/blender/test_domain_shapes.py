"""Real domain shapes in Blender (issue #24): the hull mesh holds every atom, both clash checks
find hulls pushed into each other, and an accommodated hull model keeps the atoms apart."""
import numpy as np
import pytest
from helpers import ROOT
from hull_distance import hull_distance_qhull

from fibrilfit.model.chain import chain_x, rest_lengths

DATA = ROOT / "tests" / "data"


def _hull_params(ff, name, shape="hull", **values):
    from fibrilfit.structure import measure_domain, model_values
    dom = measure_domain(DATA / f"{name}.pdb.gz")
    return ff.model.params.make_params(domain_shape=shape,
                                       **model_values(None, dom, shape=shape), **values)


def _atoms(name):
    from fibrilfit.structure import body_frame, reading
    c = reading.load(DATA / f"{name}.pdb.gz", "--domain").chains[0]
    return body_frame(c.heavy)[1], c.heavy_radius


@pytest.mark.parametrize("name", ["1gfl", "1ubq"])
def test_the_hull_mesh_holds_every_heavy_atom_with_its_radius(scene, ff, name):
    from fibrilfit.analysis.clashes import mesh_arrays
    from fibrilfit.builders.layers import globule_mesh
    mesh = globule_mesh(_hull_params(ff, name))
    verts, starts, loops = mesh_arrays(mesh)
    normals = np.empty(len(mesh.polygons) * 3, np.float32)
    mesh.polygons.foreach_get("normal", normals)
    normals = normals.reshape(-1, 3).astype(float)
    offset = (normals * verts[loops[starts]]).sum(1)  # each face's plane: n·x = offset
    local, radii = _atoms(name)
    inside = offset[None] - local @ normals.T  # (atoms, faces): depth below each face's plane
    assert (inside.min(axis=1) >= radii - 1e-3).all()  # float32 vertices
    # and it is the atoms' hull: no face farther out than the grown points reach
    assert (inside.min(axis=0) <= radii.max() + 0.15).all()


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_shapes_pushed_into_each_other_are_found_by_both_checks(scene, ff, shape):
    from fibrilfit.analysis.clashes import bvh_clashes, float_tolerance, sphere_band
    from fibrilfit.analysis.exact import hull_clashes, spheres_clashes
    from fibrilfit.builders.layers import globule_mesh
    p = _hull_params(ff, "1ubq", shape)
    mesh = globule_mesh(p)
    turn = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])  # the second one turned 90° about Z
    found = []
    for x in np.linspace(20.0, 45.0, 26):
        m = np.tile(np.eye(4), (2, 1, 1))
        m[1, :3, :3], m[1, 0, 3] = turn, x
        if shape == "hull":  # the same faces: only rounding between the checks
            band = slack = float_tolerance(m[:, :3, 3])
            analytic, depth = hull_clashes([mesh], m, band)
        else:  # the spheres' meshes are faceted: grazing contacts up to the band
            band, slack = sphere_band(max(r for *_, r in p.domain_spheres)), 1e-4
            analytic, depth = spheres_clashes([p.domain_spheres], m, band)
        faces, pairs = bvh_clashes([mesh], m)
        d = depth(0, 1)
        if d > band:  # overlapping beyond the mesh's resolution: both find it
            assert analytic and pairs, (x, d)
        elif d < -slack:  # apart: neither does
            assert not analytic and not pairs, (x, d)
        found.append(d)
    assert max(found) > 1.0 and min(found) < -1.0  # deep overlaps and clear gaps both tested


def test_gjk_distance_of_two_boxes(ff):
    from fibrilfit.analysis.exact import hull_distance
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    assert hull_distance(cube, cube + [3.0, 0, 0]) == pytest.approx(2.0, abs=1e-5)
    assert hull_distance(cube, cube + [2.0, 2.0, 0]) == pytest.approx(np.sqrt(2.0), abs=1e-5)
    assert hull_distance(cube, cube + [0.5, 0.5, 0.5]) == 0.0
    rng = np.random.default_rng(46)  # against qhull's Minkowski difference (tests/hull_distance.py)
    met = 0
    for _ in range(200):
        a = rng.normal(size=(rng.integers(4, 60), 3)) * rng.uniform(1, 10, 3)
        b = rng.normal(size=(rng.integers(4, 60), 3)) * rng.uniform(1, 10, 3) + rng.uniform(-25, 25, 3)
        truth = hull_distance_qhull(a, b)
        met += truth == 0.0
        assert hull_distance(a, b) == pytest.approx(truth, abs=1e-4)
    assert 20 <= met <= 180, met  # both meeting and apart pairs were tested


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_an_accommodated_model_keeps_the_domains_atoms_apart(scene, ff, shape):
    """The closest heavy atoms of two domains are at least two radii apart, less the resting
    overlap (0.05 Å): the shape holds the atoms (a hull's mesh with HULL_MARGIN around it for
    Bullet; spheres each holding their atoms). Spheres start spread (model.start_layout.spread_layout):
    from the tutorial's layout, deeply interpenetrated compounds locked
    (docs/model/domain-shapes.md#spheres-start)."""
    p = _hull_params(ff, "1ubq", shape, layers=4, linker=10, frames=120)
    model = ff.pipeline.build(p, scene)
    want = {"hull": "CONVEX_HULL", "spheres": "COMPOUND"}[shape]
    assert model.globules[0].rigid_body.collision_shape == want
    ff.pipeline.bake(model, scene)
    r = ff.pipeline.check(model, scene)
    assert r["accommodated"] and r["checks_agree"], r["warnings"]
    local, radii = _atoms("1ubq")
    placed = []
    for ob in model.globules:
        m = np.array(ob.matrix_world)
        placed.append(local @ m[:3, :3].T + m[:3, 3])
    closest = np.inf
    for i in range(len(placed)):
        for j in range(i + 1, len(placed)):
            d = np.linalg.norm(placed[i][:, None] - placed[j][None], axis=-1)
            closest = min(closest, float((d - radii[:, None] - radii[None]).min()))
    assert closest >= -0.05
    # the joint sits on its bond's pivot: the last bead one residue spacing from the CA
    joint = np.asarray(p.domain_joint, float).reshape(3)
    for members in model.chain:
        m = np.array(members[-1].matrix_world)
        ca = m[:3, :3] @ joint + m[:3, 3]
        bead = np.array(members[-2].matrix_world)[:3, 3]
        assert np.linalg.norm(ca - bead) == pytest.approx(p.residue_spacing, abs=0.05)


@pytest.mark.parametrize("shape, protocol", [("hull", "tutorial"), ("hull", "inflate"),
                                             ("spheres", "tutorial")])
def test_the_joint_starts_one_residue_spacing_from_the_last_bead(scene, ff, shape, protocol):
    """Every start layout puts the last bond's pivot at the domain's terminal CA, one residue
    spacing from the last linker bead, on the surface side facing the linker."""
    p = _hull_params(ff, "1ubq", shape, layers=3, linker=6, protocol=protocol)
    model = ff.pipeline.build(p, scene)
    joint = np.asarray(p.domain_joint, float).reshape(3)
    for members, bonds in zip(model.chain, model.constraints):
        m = np.array(members[-1].matrix_world)
        ca = m[:3, :3] @ joint + m[:3, 3]
        bead = np.array(members[-2].matrix_world)[:3, 3]
        assert np.linalg.norm(ca - bead) == pytest.approx(p.residue_spacing, abs=1e-3)
        assert np.allclose(np.array(bonds[-1].matrix_world)[:3, 3], ca, atol=1e-3)


@pytest.mark.parametrize("args, message", [
    (["--domain-shape", "hull"], "domain_shape: hull needs a domain structure (--domain FILE)"),
    (["--domain-shape", "cube"], "invalid choice: 'cube'"),
])
def test_cli_refuses_a_shape_it_cannot_build_in_one_line(tmp_path, args, message):
    from helpers import run_cli
    out = tmp_path / "r.json"
    r = run_cli("run", "--layers", "2", "--json", str(out), *args)
    assert r.returncode == 2 and message in r.stderr and not out.exists()
    assert len(r.stderr.strip().splitlines()) <= 3  # argparse's usage lines, or one line


def _sweep_hits(scene, probe, spheres, centre, directions, far=300.0):
    """Bullet's first contact of `probe` swept from centre + far·d towards centre, for each d,
    beside the contact a union of spheres [x, y, z, r] (world) gives: the probe's centre (Å)."""
    rp = probe.dimensions[0] / 2.0
    got, want = [], []
    for d in directions:
        start = centre + far * d
        r = scene.rigidbody_world.convex_sweep_test(probe, tuple(start), tuple(centre))
        assert r[3], d
        got.append(np.array(r[0]))
        # the sweep's earliest t with |start - t·d - c| = r + rp, over the spheres
        rel = start[None] - spheres[:, :3]
        b = rel @ d
        disc = b * b - (rel * rel).sum(1) + (spheres[:, 3] + rp) ** 2
        t = np.where(disc >= 0, b - np.sqrt(np.maximum(disc, 0)), np.inf)
        want.append(start - t.min() * d)
    return np.array(got), np.array(want)


def test_spheres_grow_under_inflate_to_their_covering_geometry(scene, ff):
    """Mid-growth (scale about 0.6) and once grown, Bullet's compound is the covering spheres
    at the globule's scale, where the globule is: a probe swept onto it stops where the
    spheres say (docs/model/domain-shapes.md#compound-growth)."""
    import bpy
    from fibrilfit.geom.shape import directions
    p = _hull_params(ff, "1ubq", "spheres", layers=1, linker=6, protocol="inflate",
                     grow_frames=20, grow_start=0.3, regrow_cycles=0, hold_frames=5,
                     gravity=100.0)  # strong: the globule swings far from where it started
    model = ff.pipeline.build(p, scene)
    probe = _probe(scene)
    s = np.array(p.domain_spheres, float)
    seen = []

    def look(frame, positions):
        g = model.globules[0]
        m = np.array(g.matrix_world)
        scale = float(np.cbrt(np.linalg.det(m[:3, :3])))
        if frame not in (12, 22):  # mid-growth, and grown (from frame 21)
            return False
        world = np.column_stack([s[:, :3] @ m[:3, :3].T + m[:3, 3], s[:, 3] * scale])
        centre = m[:3, 3]
        out = np.array([centre[0], centre[1], 0.0])
        out /= np.linalg.norm(out)
        dirs = [out] + [d for d in directions(60) if d @ out > 0.6]  # away from the core
        got, want = _sweep_hits(scene, probe, world, centre, dirs)
        seen.append((frame, scale, float(np.abs(got - want).max())))
        return frame == 22

    ff.pipeline.bake(model, scene, on_frame=look)
    assert [f for f, *_ in seen] == [12, 22], seen
    (_, mid, err_mid), (_, grown, err_grown) = seen
    assert 0.4 < mid < 0.8 and grown == pytest.approx(1.0)
    assert err_mid < 0.02 and err_grown < 0.02, seen



def _overlap(p, mesh, a, b) -> float:
    """How deep two globules with world matrices a, b overlap (Å; negative: apart): the hulls'
    distance (qhull's Minkowski difference, not the checker's GJK), or the deepest overlap of two
    covering spheres."""
    from fibrilfit.analysis.clashes import mesh_arrays
    if p.domain_shape == "hull":
        v = mesh_arrays(mesh)[0]
        gap = hull_distance_qhull(v @ a[:3, :3].T + a[:3, 3], v @ b[:3, :3].T + b[:3, 3])
        return -gap if gap > 0 else 1.0  # (meeting: deeper than any tolerance, tested apart)
    s = np.asarray(p.domain_spheres, float)
    ca, cb = s[:, :3] @ a[:3, :3].T + a[:3, 3], s[:, :3] @ b[:3, :3].T + b[:3, 3]
    d = np.linalg.norm(ca[:, None] - cb[None], axis=-1)
    return float((s[:, 3][:, None] + s[:, 3][None] - d).max())


def _cell(ff, shape="hull", **values):
    """A screw-periodic cell of ubiquitin globules of `shape` on the tutorial's slab."""
    return _hull_params(ff, "1ubq", shape, periodic="auto", linker=8, frames=40, **values)


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_a_cells_images_carry_the_whole_turn(scene, ff, shape):
    """The images of a hull (spheres) cell are S^m of their originals' whole transform (turn
    included), in the objects and in Bullet: a probe swept onto an image stops its radius from
    the image's body (the hull plus HULL_MARGIN, or the spheres), or from a body in its way
    (docs/model/domain-shapes.md#periodic)."""
    import bpy
    from fibrilfit.analysis.clashes import mesh_arrays
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.model.domains import HULL_MARGIN
    from fibrilfit.builders.periodic import CELL, ImageFollower, image_collection
    from fibrilfit.model import helix
    from fibrilfit.geom.shape import directions
    p = _cell(ff, shape)
    model = ff.pipeline.build(p, scene)
    images = [ob for ob in image_collection(model).objects
              if ob["fibrilfit_index"] == p.linker]  # the globules' images
    want = {"hull": "CONVEX_HULL", "spheres": "COMPOUND"}[shape]
    assert images and images[0].rigid_body.collision_shape == want
    probe = _probe(scene)
    verts = mesh_arrays(images[0].data)[0]
    spheres = np.asarray(p.domain_spheres, float) if shape == "spheres" else None

    def gap(point, m):  # from a point to a globule's body at world matrix m (Å)
        if shape == "hull":
            return hull_distance_qhull(verts @ m[:3, :3].T + m[:3, 3], point[None]) - HULL_MARGIN
        c = spheres[:, :3] @ m[:3, :3].T + m[:3, 3]
        return float((np.linalg.norm(c - point, axis=1) - spheres[:, 3]).min())

    baking = ff.pipeline.Baking(model, scene)
    follower = next(h for h in baking.hooks if isinstance(h, ImageFollower))
    targets, others, gaps = None, None, []
    while (stepped := baking.step()) is not None:
        if targets is not None:  # Bullet holds the images where the last frame left them
            others += [np.array(g.matrix_world) for g in model.globules]
            for m in targets:
                centre = m[:3, 3]
                out = np.array([centre[0], centre[1], 0.0]) / np.hypot(*centre[:2])
                for d in [out] + [d for d in directions(30) if d @ out > 0.7]:
                    r = scene.rigidbody_world.convex_sweep_test(probe, tuple(centre + 200 * d),
                                                               tuple(centre))
                    if r[3]:
                        hit = np.array(r[0])
                        gaps.append((gap(hit, m), min(gap(hit, q) for q in others)))
            break
        if stepped[0] == 10:  # where the images near the cell should be now: S^m of originals
            near = [k for k in np.flatnonzero(follower.near_now) if follower.objects[k] in images]
            assert near
            targets = [helix.apply_matrices(p, follower.objects[k][CELL], np.array(
                model.chain[follower.objects[k]["fibrilfit_chain"]][p.linker].matrix_world
            )[None])[0] for k in near[:3]]
            others = [np.array(ob.matrix_world) for ob in images if ob not in
                      [follower.objects[k] for k in near[:3]]]
    gaps = np.array(gaps)
    # each stop touches the image's true body, or a body in the way, at the probe's radius
    assert len(gaps) >= 3 and (gaps[:, 0] > 0.48).all(), gaps  # never inside the image
    assert (np.abs(gaps[:, 0] - 0.5) < 0.02).sum() >= 3, gaps  # stopped by the image itself
    if shape == "hull":  # every stop explained (with spheres some stop short of every body
        # the test knows of: docs/model/domain-shapes.md#periodic)
        assert np.abs(gaps.min(axis=1) - 0.5).max() < 0.02, gaps
    # every image is S^m of its original's whole matrix once placed
    follower.place(chain_positions(model))
    for ob in images:
        m, c, i = ob[CELL], ob["fibrilfit_chain"], ob["fibrilfit_index"]
        want = helix.apply_matrices(p, m, np.array(model.chain[c][i].matrix_world)[None])[0]
        assert np.allclose(np.array(ob.matrix_world), want, atol=1e-3)


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_an_original_pushed_into_an_image_is_found_by_both_checks(scene, ff, shape):
    """A cell's top globule pushed into the image of globule 0 one cell up (original against
    image, across the cell's end), turned 90° to it: beyond the tolerance both checks name the
    pair, apart neither does. Before that, the baked cell is judged with both checks agreeing."""
    from mathutils import Matrix
    from fibrilfit.model import helix
    p = _cell(ff, shape)
    model = ff.pipeline.build(p, scene)
    ff.pipeline.bake(model, scene)
    r = ff.pipeline.check(model, scene)
    assert r["periodic"]["cell_layers"] == p.periodic and r["checks_agree"], r["warnings"]
    assert r["sphere_check"]["shape"] == shape
    n = len(model.globules)
    top = model.globules[-1]
    image = helix.apply_matrices(p, 1, np.array(model.globules[0].matrix_world)[None])[0]
    turn = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    out = image[:3, 3] * [1, 1, 0] / np.hypot(*image[:2, 3])
    seen = []
    for x in np.linspace(15.0, 60.0, 16):
        m = image.copy()
        m[:3, :3] = image[:3, :3] @ turn
        m[:3, 3] = image[:3, 3] + x * out  # pushed in along the radial direction
        top.matrix_world = Matrix(m.tolist())
        r = ff.pipeline.check(model, scene)
        pair = [n - 1, n]  # the top globule and globule 0's image (index 0 + n)
        bvh = any([i, j] == pair for i, j, *_ in r["clashing_pairs"])
        analytic = any([i, j] == pair for i, j, *_ in r["sphere_check"]["clashing_pairs"])
        seen.append((x, bvh, analytic))
        truth = _overlap(p, model.globules[0].data, m, image)  # computed here, independently
        if truth > 0.3:
            assert bvh and analytic, (x, truth)
        elif truth < -0.3:
            assert not bvh and not analytic, (x, truth)
        if bvh != analytic:  # only a grazing pair may differ: within the tolerance
            assert [n - 1, n] in [[i, j] for i, j, _ in r["grazing_pairs"]], (x, r["warnings"])
        assert r["checks_agree"], (x, r["warnings"])
    assert seen[0][1] and seen[0][2] and not seen[-1][1] and not seen[-1][2], seen


def test_spheres_from_the_tutorial_start_do_not_start_overlapping(scene, ff):
    """The 4-layer ubiquitin model at the tutorial's 4.8 Å rise: its rest layout put the
    compounds 13.8 Å into each other; spread, none overlaps, every bond at rest and every bead
    clear of the core (docs/model/domain-shapes.md#spheres-start)."""
    from fibrilfit.analysis.exact import spheres_clashes
    p = _hull_params(ff, "1ubq", "spheres", layers=4, linker=10)
    model = ff.pipeline.build(p, scene)
    mats = np.array([np.array(g.matrix_world) for g in model.globules])
    assert spheres_clashes([p.domain_spheres], mats, 0.0)[0] == []
    rest = np.asarray(rest_lengths(p))
    for members in model.chain:
        pos = np.array([np.array(ob.matrix_world)[:3, 3] for ob in members])
        assert np.allclose(np.linalg.norm(np.diff(pos[:-1], axis=0), axis=1), rest[:-1],
                           atol=1e-3)
        assert (np.abs(pos[1:, 0]) > p.slab[0] / 2 + p.residue_radius - 1e-3).all()
    # the sphere's tutorial start is not spread: its globules stand on the rest layout
    q = ff.model.params.make_params(layers=4, linker=10)
    sphere = ff.pipeline.build(q, scene)
    x = np.array([np.array(g.matrix_world)[:3, 3] for g in sphere.globules])
    assert np.allclose(np.hypot(x[:, 0], x[:, 1]), chain_x(q)[-1], atol=1e-3)


def _probe(scene):
    """A 0.5 Å ball, a kinematic rigid body parked far away, for convex_sweep_test probes."""
    import bpy
    from fibrilfit.geom.shape import directions
    mesh = bpy.data.meshes.new("probe")
    mesh.from_pydata([(0.5 * x, 0.5 * y, 0.5 * z) for x, y, z in directions(200)], [], [])
    probe = bpy.data.objects.new("probe", mesh)
    scene.collection.objects.link(probe)
    scene.rigidbody_world.collection.objects.link(probe)
    probe.rigid_body.type, probe.rigid_body.kinematic = "PASSIVE", True
    probe.rigid_body.collision_shape = "SPHERE"
    probe.location = (0.0, 0.0, 5000.0)
    return probe
