"""Several real-shaped domains per chain (issue #24): ubiquitin then GFP on one chain, each
with its own hull (spheres), its joint at its incoming terminal CA and the next linker leaving
from its other terminal CA (docs/guide/atoms-and-domains.md#shapes-of-several-domains)."""
import functools

import numpy as np
import pytest
from helpers import ROOT
from hull_distance import hull_distance_qhull
from fibrilfit.model.chain import rest_lengths

DATA = ROOT / "tests" / "data"
INFLATE = dict(protocol="inflate", grow_frames=15, hold_frames=15, regrow_cycles=0,
               near_cycles=0)


@functools.lru_cache(maxsize=None)
def _measured(gfp_first=False):
    from fibrilfit.structure import measure_domain
    ubq = measure_domain(DATA / "1ubq.pdb.gz", outgoing=not gfp_first)  # domain 0 has an exit
    gfp = measure_domain(DATA / "1gfl.pdb.gz", outgoing=gfp_first)
    return (gfp, ubq) if gfp_first else (ubq, gfp)


def _params(ff, shape, gfp_first=False, **values):
    from fibrilfit.structure import model_values
    ubq, gfp = _measured(gfp_first)
    given = {"linker": 6, "domain_linker": [6], "layers": 3, "frames": 20, **values}
    given = {k: v for k, v in given.items() if v is not None}
    return ff.model.params.make_params(domain_shape=shape, **{
        **model_values(None, ubq, more_domains=[gfp], shape=shape), **given})


def _world(m, local):
    return local @ m[:3, :3].T + m[:3, 3]


def _body(ob, p, shape):
    """A globule's body in the world from its domain's own rows (not from the scene's mesh):
    ("points", its hull points) or ("spheres", [x, y, z, r])."""
    from fibrilfit.geom.shape import hull_points
    m = np.array(ob.matrix_world)
    rows = next(d.rows for d in p.domains if d.member == ob["fibrilfit_index"])
    if shape == "hull":
        return "points", _world(m, hull_points(rows))
    return "spheres", np.column_stack([_world(m, rows[:, :3]), rows[:, 3]])


def _gap(a, b) -> float:
    """Distance (Å) between two bodies, ("points", convex hull points) or ("spheres", rows):
    qhull's Minkowski difference (tests/hull_distance.py, not the checker's GJK); zero or
    less: they meet."""
    (ka, a), (kb, b) = sorted([a, b], key=lambda x: x[0])
    if ka == kb == "points":
        return hull_distance_qhull(a, b)
    if ka == "points":  # a hull (or the core's box) and balls
        return min(hull_distance_qhull(a, s[None, :3]) - s[3] for s in b)
    d = np.linalg.norm(a[:, None, :3] - b[None, :, :3], axis=-1)
    return float((d - a[:, None, 3] - b[None, :, 3]).min())


def _bound(body):
    kind, x = body
    r = x[:, 3] if kind == "spheres" else 0.0
    centre = x[:, :3].mean(axis=0)
    return centre, float((np.linalg.norm(x[:, :3] - centre, axis=1) + r).max())


def _overlaps_at_frame_1(model, p, shape, chains):
    """Every pair of bodies of the built model that overlap (closer than 1e-3 Å) and that
    Bullet collides: the cores (boxes) against the chains' members, the members of `chains`
    against each other (bonded neighbours left out: their collisions are off), each domain from
    its own atoms. The anchor rests on the core, as in the tutorial: left out against it."""
    box = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * 0.5 \
        * np.array(p.slab)
    cores = [("points", _world(np.array(s.matrix_world), box)) for s in model.slabs]
    members, bodies = [d.member for d in p.domains], []
    for c in chains:
        for i, ob in enumerate(model.chain[c]):
            if i in members:
                bodies.append(((c, i), _body(ob, p, shape)))
            else:
                centre = np.array(ob.matrix_world)[:3, 3]
                bodies.append(((c, i), ("spheres", np.array([[*centre, p.residue_radius]]))))
    pairs = [((c, i), core, body) for (c, i), body in bodies if i > 0 for core in cores]
    pairs += [(bodies[a][0] + bodies[b][0], bodies[a][1], bodies[b][1])
              for a in range(len(bodies)) for b in range(a + 1, len(bodies))
              if not (bodies[a][0][0] == bodies[b][0][0]
                      and abs(bodies[a][0][1] - bodies[b][0][1]) <= 1)]
    bad = []
    for name, x, y in pairs:
        (cx, rx), (cy, ry) = _bound(x), _bound(y)
        if np.linalg.norm(cx - cy) > rx + ry:
            continue
        gap = _gap(x, y)
        if gap <= 1e-3:
            bad.append((name, round(gap, 3)))
    return bad


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_a_chain_of_ubiquitin_and_gfp_builds_bakes_and_is_judged(scene, ff, shape):
    """Each globule carries its own domain's mesh (ubiquitin's, then GFP's), the run is judged
    by both checks on those meshes, and the JSON names domains as for spheres."""
    from fibrilfit.builders.layers import globule_mesh
    from fibrilfit.geom.shape import hull_points
    # the hulls get 80 frames: at 20 they are still relaxing, and whether the worst stretch is
    # under the 5 % tolerance depended on the machine (4.8 % where this was first measured, 6.2 %
    # on an AVX-512 Xeon, bpy 5.0.1; 3.5 % at 40 frames, 0.2 % at 80 there)
    p = _params(ff, shape, frames=80 if shape == "hull" else 20)
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    # both shapes fit at linkers 6, 6 on 3 layers (no clash; worst stretch 0.2 % for the hulls
    # at 80 frames, 0.003 % for the spheres at 20)
    assert r["verdict"] == "successful" and r["accommodated"], r["clashing_pairs"]
    assert r["checks_agree"], r["warnings"]
    assert r["sphere_check"]["shape"] == shape and "clashing_domains" in r
    assert [e["n"] for e in r["domain_envelopes"]] == [3, 3]
    want = {"hull": "CONVEX_HULL", "spheres": "COMPOUND"}[shape]
    assert len(model.globules) == 6
    for g, ob in enumerate(model.globules):
        k = g % 2
        assert ob.rigid_body.collision_shape == want
        assert ob.matrix_world.to_scale()[:] == pytest.approx((1, 1, 1), abs=1e-5)  # own size
        own = globule_mesh(p, k)
        assert len(ob.data.vertices) == len(own.vertices)
        v = np.array([x.co[:] for x in ob.data.vertices])
        rows = p.domains[k].rows
        if shape == "hull":  # the mesh is the hull of this domain's grown atoms
            pts = hull_points(rows)
            assert np.ptp(v, axis=0) == pytest.approx(np.ptp(pts, axis=0), abs=0.2)
        else:
            assert len(ob.children) == len(rows)
            assert sorted(round(c.dimensions[0] / 2, 2) for c in ob.children) == \
                pytest.approx(sorted(rows[:, 3].round(2)), abs=0.02)
    assert model.globules[0].data != model.globules[1].data
    assert model.globules[0].data == model.globules[2].data  # each domain's mesh is shared
    # GFP's hull is its 24 x 42 Å barrel, ubiquitin's a 30 Å ball: the meshes' extents differ
    e0 = np.ptp([x.co[:] for x in model.globules[0].data.vertices], axis=0)
    e1 = np.ptp([x.co[:] for x in model.globules[1].data.vertices], axis=0)
    assert e1.max() > e0.max() + 10
    # every domain's mesh takes the globules' material (renders read the object's colour)
    from fibrilfit.exports.dressing import ensure_materials
    mat = ensure_materials(model)["globule"]
    assert all(ob.data.materials[:] == [mat] for ob in model.globules)
    # the sidebar's joined copy (for Mesh Analysis) is each globule's own mesh, placed
    from fibrilfit.ui.joined import join_globules
    joined = join_globules(model).data
    assert len(joined.vertices) == sum(len(ob.data.vertices) for ob in model.globules)
    co = np.array([v.co[:] for v in joined.vertices])
    n0 = len(model.globules[0].data.vertices)
    first = _world(np.array(model.globules[1].matrix_world),
                   np.array([v.co[:] for v in model.globules[1].data.vertices]))
    assert np.allclose(co[n0:n0 + len(first)], first, atol=1e-3)


@pytest.mark.parametrize("shape, protocol", [("hull", "tutorial"), ("spheres", "tutorial"),
                                             ("hull", "inflate"), ("spheres", "inflate")])
def test_a_built_chain_starts_with_no_body_overlapping_another(scene, ff, shape, protocol):
    """Frame 1, before any step: no two bodies that Bullet collides overlap (a single chain,
    so the tutorial's overlap of neighbouring layers, which Bullet pushes apart by design, is
    not in it): each domain turned with its joint facing back along its bond, the next linker
    leaving from its exit. With several layers under inflate, no chain starts inside itself.
    The joints sit one residue spacing on from their beads, the exits one spacing before."""
    values = dict(layers=1) if protocol == "tutorial" else dict(layers=4, **INFLATE)
    p = _params(ff, shape, **values)
    model = ff.pipeline.build(p, scene)
    assert _overlaps_at_frame_1(model, p, shape, chains=[0]) == []
    (first, second) = p.domains
    joints, exits = [first.joint, second.joint], p.domain_exits
    g0, g1 = first.member, second.member
    for chain, bonds in zip(model.chain, model.constraints):
        m0, m1 = (np.array(chain[i].matrix_world) for i in (g0, g1))
        bead = lambda i: np.array(chain[i].matrix_world)[:3, 3]  # noqa: E731
        joint0, exit0 = _world(m0, joints[0][None])[0], _world(m0, np.array(exits)[:1])[0]
        joint1 = _world(m1, joints[1][None])[0]
        assert np.linalg.norm(joint0 - bead(g0 - 1)) == pytest.approx(p.residue_spacing, abs=1e-3)
        assert np.linalg.norm(exit0 - bead(g0 + 1)) == pytest.approx(p.residue_spacing, abs=1e-3)
        assert np.linalg.norm(joint1 - bead(g1 - 1)) == pytest.approx(p.residue_spacing, abs=1e-3)
        for i, at in ((g0 - 1, joint0), (g0, exit0), (g1 - 1, joint1)):  # the bonds' pivots
            assert np.allclose(np.array(bonds[i].matrix_world)[:3, 3], at, atol=1e-3)
        # no bond starts stretched (beads at their rest length; a domain's centre at most
        # the joint's distance plus one spacing from its neighbour bead)
        pos = np.array([np.array(ob.matrix_world)[:3, 3] for ob in chain])
        length = np.linalg.norm(np.diff(pos, axis=0), axis=1)
        rest = np.array(rest_lengths(p))
        beads = [i for i in range(len(rest)) if i not in (g0 - 1, g0, g1 - 1)]
        assert np.allclose(length[beads], rest[beads], atol=1e-3)
        assert (length <= rest + 1e-3).all()
    if protocol == "inflate":
        for c in range(1, len(model.chain)):
            assert _overlaps_at_frame_1(model, p, shape, chains=[c]) == [], c
        # and the globules of different chains apart at the scale they start at
        from fibrilfit.builders.growth import start_scale
        centres = np.array([ob.matrix_world.translation[:] for ob in model.globules])
        s = start_scale(p, centres)
        assert 0.01 <= s <= p.grow_start
        small = []
        for ob in model.globules:
            kind, x = _body(ob, p, shape)
            x = x.copy()
            x[:, :3] = centres[len(small)] + s * (x[:, :3] - centres[len(small)])
            if kind == "spheres":
                x[:, 3] *= s
            small.append((kind, x))
        for a in range(len(small)):
            for b in range(a + 1, len(small)):
                if a // 2 != b // 2:
                    assert _gap(small[a], small[b]) > 0, (a, b)


def test_a_forced_overlap_of_two_domains_is_found_by_both_checks_and_named(scene, ff):
    """GFP (domain 1) of chain 2 pushed into ubiquitin (domain 0) of chain 0 in steps: both
    checks name the pair exactly when the distance of the two domains' own hull points (qhull's
    Minkowski difference, tests/hull_distance.py, not the checker's GJK) says they overlap, and
    the JSON names which domain of which chain. With one mesh for both (the sphere's way of
    several domains) the checks would test ubiquitin's hull at GFP's place."""
    import bpy
    from mathutils import Matrix
    from mathutils.bvhtree import BVHTree
    from fibrilfit.analysis.verdict import check_model
    from fibrilfit.geom.shape import hull_points
    p = _params(ff, "hull", layers=3)
    model = ff.pipeline.build(p, scene)
    g = model.globules  # chain-major: globule 2c + k is domain k of chain c
    for n, ob in enumerate(g):  # every other globule far apart
        if n not in (0, 5):
            ob.matrix_world = Matrix.Translation((500.0 * (n + 1), 0.0, 0.0))
    a = np.array(g[0].matrix_world)
    a[:3, :3] = np.eye(3)
    g[0].matrix_world = Matrix(a.tolist())
    turn = np.array([[0.0, 0, 1], [0, 1, 0], [-1, 0, 0]])  # GFP's barrel axis across X
    ubq, gfp = hull_points(p.domains[0].rows), hull_points(p.domains[1].rows)
    seen = {"apart": 0, "clash": 0}
    for x in np.linspace(55.0, 15.0, 11):
        m = np.eye(4)
        m[:3, :3], m[:3, 3] = turn, a[:3, 3] + np.array([x, 0.0, 0.0])
        g[5].matrix_world = Matrix(m.tolist())
        bpy.context.view_layer.update()
        r = check_model(model)
        truth = hull_distance_qhull(_world(a, ubq), _world(m, gfp))
        # the BVH on each globule's own whole mesh, every pair, one tree each (no pruning)
        trees = []
        for ob in g:
            w = np.array(ob.matrix_world)
            verts = _world(w, np.array([v.co[:] for v in ob.data.vertices]))
            trees.append(BVHTree.FromPolygons(verts.tolist(),
                                              [list(f.vertices) for f in ob.data.polygons],
                                              epsilon=1e-5))
        brute = sorted([i, j] for i in range(len(g)) for j in range(i + 1, len(g))
                       if trees[i].overlap(trees[j]))
        pairs = [q[:2] for q in r["clashing_pairs"]]
        analytic = [q[:2] for q in r["sphere_check"]["clashing_pairs"]]
        assert pairs == brute
        assert r["checks_agree"], r["warnings"]
        if truth > 0.01:  # apart: neither check names them
            assert pairs == [] and analytic == [], (x, truth, pairs, analytic)
            seen["apart"] += 1
        elif truth == 0.0 and r["sphere_check"]["clashing_pairs"][0][2] > 0.01:
            assert pairs == [[0, 5]] and analytic == [[0, 5]], (x, pairs, analytic)
            named = r["clashing_domains"][0]
            assert named[0] == {"chain": 0, "layer": 0, "protofilament": 0, "domain": 0}
            assert named[1] == {"chain": 2, "layer": 2, "protofilament": 0, "domain": 1}
            seen["clash"] += 1
    assert seen["apart"] >= 2 and seen["clash"] >= 3, seen


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_a_cell_of_two_real_domains_images_each_with_its_own_shape(scene, ff, shape):
    """In a screw-periodic cell every image of a globule carries its own domain's mesh (and,
    for spheres, its own child spheres) and S^m of its original's whole transform; the cell is
    baked and judged by both checks."""
    from fibrilfit.builders.periodic import CELL, CHAIN, image_collection
    from fibrilfit.model import helix
    p = _params(ff, shape, layers=None, periodic="auto", linker=4, domain_linker=[3], frames=4)
    model = ff.pipeline.build(p, scene)
    ff.pipeline.bake(model, scene)
    r = ff.pipeline.check(model, scene)
    assert r["checks_agree"], r["warnings"]
    assert r["periodic"]["cell_layers"] == p.periodic and r["sphere_check"]["shape"] == shape
    members = [d.member for d in p.domains]
    images = [ob for ob in image_collection(model).objects if ob["fibrilfit_index"] in members]
    seen = set()
    for ob in images:
        source = model.chain[ob[CHAIN]][ob["fibrilfit_index"]]
        assert ob.data == source.data  # its own domain's mesh
        k = members.index(ob["fibrilfit_index"])
        seen.add(k)
        if shape == "spheres":
            assert len(ob.children) == len(p.domains[k].rows)
    assert seen == {0, 1}
    # the images stand where the follower last put them: S^m of the originals' whole
    # transforms at the last frame they were moved, i.e. as the check computes them now
    moved = 0
    for ob in images:
        source = model.chain[ob[CHAIN]][ob["fibrilfit_index"]]
        want = helix.apply_matrices(p, ob[CELL], np.array(source.matrix_world)[None])[0]
        got = np.array(ob.matrix_world)
        if np.allclose(got[:3, 3], want[:3, 3], atol=0.05):
            assert np.allclose(got[:3, :3], want[:3, :3], atol=1e-3)
            moved += 1
    # measured 2026-11-27: of the 182 images, 158 (hull) and 153 (spheres) were moved at the last
    # frame on bpy 4.2.0 and 5.0.1, 156 (hull) and 153 on 5.2.3 (its Bullet bakes this cell a
    # little differently); the rest stand where an earlier frame left them
    import bpy
    want = {"hull": 156 if bpy.app.version >= (5, 2) else 158, "spheres": 153}[shape]
    assert len(images) == 182 and moved == want


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_inflate_grows_each_real_domain_to_its_own_full_size(scene, ff, shape):
    """Under inflate every globule starts at the start scale of its own mesh and ends at its
    own full size (scale 1: each domain has its own mesh, none is another's scaled)."""
    from fibrilfit.builders import growth
    p = _params(ff, shape, layers=4, **INFLATE)
    model = ff.pipeline.build(p, scene)
    hook = growth.Inflate(model, scene)
    hook._set_scale(0.5)
    assert all(ob.scale[:] == pytest.approx((0.5,) * 3) for ob in model.globules)
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    assert r["inflate"]["cycles"] and 0.01 <= r["inflate"]["start_scale"] <= p.grow_start
    assert all(ob.matrix_world.to_scale()[:] == pytest.approx((1, 1, 1), abs=1e-4)
               for ob in model.globules)
    assert r["checks_agree"], r["warnings"]


def test_spheres_of_several_domains_start_spread_under_the_tutorial_protocol(scene, ff):
    """Full-size compounds started inside each other lock (measured: a 10-layer chain of
    ubiquitin then GFP ended with two compounds 14.3 Å deep); spread, the 4-layer model starts
    with no body overlapping another, across chains too (its bent straight layout put
    covering spheres of neighbouring layers 19.4 Å into each other)."""
    p = _params(ff, "spheres", layers=4, linker=10, domain_linker=[4])
    model = ff.pipeline.build(p, scene)
    assert _overlaps_at_frame_1(model, p, "spheres", chains=range(4)) == []


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_a_short_linker_after_gfp_starts_clear_of_itself(scene, ff, shape):
    """GFP's exit faces back towards its joint (their normals 44° apart): with 2 residues to
    ubiquitin a linker turning outward swung ubiquitin into GFP (0.1-1.8 Å at every turn of
    the domains); the layout then runs the linker straight along the exit's normal, and the
    chain starts clear of itself and of the core."""
    p = _params(ff, shape, gfp_first=True, layers=1, linker=3, domain_linker=[2])
    model = ff.pipeline.build(p, scene)
    assert _overlaps_at_frame_1(model, p, shape, chains=[0]) == []



def _turned_about_centre(ob, radians: float, axis):
    """The object turned about its own centre (its centre does not move)."""
    from mathutils import Matrix
    m = np.array(ob.matrix_world)
    m[:3, :3] = np.array(Matrix.Rotation(radians, 3, axis)) @ m[:3, :3]
    ob.matrix_world = Matrix(m.tolist())


@pytest.mark.parametrize("which", ["joint", "exit"])
def test_a_domain_turned_about_its_centre_stretches_the_bond_at_its_terminal_ca(scene, ff, which):
    """docs/model/domain-shapes.md#joint-stretch: a real domain is held by its terminal CAs, so
    the bond into it is measured to its joint and the bond out of it from its exit, against one
    residue spacing. Turning ubiquitin about its own centre leaves every centre where it was
    (a centre-to-centre measure reads no stretch) but pulls a CA away from its bead; the
    verdict's stretch is the CA-to-bead distance over 3.5 Å, computed here independently."""
    import bpy
    from fibrilfit.analysis.verdict import check_model
    p = _params(ff, "hull", layers=3)
    model = ff.pipeline.build(p, scene)
    assert check_model(model)["max_bond_stretch"] == pytest.approx(0.0, abs=1e-4)
    members = model.chain[1]
    g = p.domains[0].member  # ubiquitin: a joint from the bead before, an exit to the next
    ob = members[g]
    points = {"joint": (p.domains[0].joint, g - 1),
              "exit": (np.asarray(p.domain_exits[0], float), g + 1)}

    def pulled(m, name):  # a terminal CA's bond: its distance to its bead over 3.5 Å, minus 1
        point, bead = points[name]
        ca = m[:3, :3] @ point + m[:3, 3]
        return float(np.linalg.norm(ca - np.array(members[bead].matrix_world)[:3, 3])
                     / p.residue_spacing - 1.0)

    m0 = np.array(ob.matrix_world)
    lever = m0[:3, :3] @ points[which][0]
    bond = np.array(members[points[which][1]].matrix_world)[:3, 3] - (lever + m0[:3, 3])
    axis = np.cross(lever, bond)
    axis = axis / np.linalg.norm(axis)  # turns the CA in the plane of its lever and its bond
    best = max((0.12, -0.12), key=lambda a: (_turned_about_centre(ob, a, axis),
                                             pulled(np.array(ob.matrix_world), which),
                                             _turned_about_centre(ob, -a, axis))[1])
    _turned_about_centre(ob, best, axis)  # 7°: the CA, ~15 Å out, moves ~1.8 Å
    bpy.context.view_layer.update()
    m = np.array(ob.matrix_world)
    assert np.allclose(m[:3, 3], m0[:3, 3])
    assert pulled(m, which) > 0.1
    r = check_model(model)
    assert r["max_bond_stretch"] == pytest.approx(max(pulled(m, "joint"), pulled(m, "exit")),
                                                  abs=1e-4)
    assert not r["linker_intact"] and not r["accommodated"]
    centres = np.array([np.array(o.matrix_world)[:3, 3] for o in members])
    centre_stretch = (np.linalg.norm(np.diff(centres, axis=0), axis=1)
                      / np.asarray(rest_lengths(p)) - 1.0).max()
    assert centre_stretch < 0.05  # the centres alone would have said: intact
