"""The buried terminus's exit (docs/model/buried-terminus.md#method): the path finder on cases
known by hand, the count in residues, 5OQV's measured anchor, and the model's free linker."""
import math

import numpy as np
import pytest

from fibrilfit.geom import exit_path as E
from fibrilfit.model import params as P, terminus

from tests.unit.test_structure import DATA

RISE = 4.8
LATTICE = 1.5  # Å between the atoms of the constructed cores: no bead passes between them


def block_core(x=(-11.0, 11.0), y=(-20.0, 0.0), z=(-8.5, 8.5)):
    """A solid core of carbon-sized atoms (1.7 Å) on a 1.5 Å lattice: the box's section is the
    outline, its top face (y = 0) the surface."""
    g = [np.arange(lo, hi + 1e-9, LATTICE) for lo, hi in (x, y, z)]
    atoms = np.stack(np.meshgrid(*g, indexing="ij"), axis=-1).reshape(-1, 3)
    outline = np.array([[x[0], y[0]], [x[1], y[0]], [x[1], y[1]], [x[0], y[1]]])
    return atoms, outline


def find(atoms, start, outline):
    return E.shortest_exit(atoms, np.full(len(atoms), 1.7), np.asarray(start, float), outline,
                           bead_radius=1.75, z_half=RISE)


def test_an_anchor_at_the_bottom_of_a_straight_channel_climbs_it():
    """A channel of radius 4 Å (its axis 4 Å from every atom: a 1.75 Å bead clears 1.7 Å atoms
    by 0.55 Å) straight up from the anchor 8.6 Å below the surface (its bottom 4 Å below the
    anchor): the path is the channel's axis, 8.6 Å to the outline plus at most one 0.25 Å
    voxel to the first point on or outside it."""
    atoms, outline = block_core()
    depth = 8.6
    axis = np.hypot(atoms[:, 0], atoms[:, 2])
    atoms = atoms[~((axis < 4.0) & (atoms[:, 1] > -depth - 4.0))]
    way = find(atoms, [0.0, -depth, 0.0], outline)
    assert way.found
    assert depth <= way.length <= depth + E.STEP  # to the first voxel out: 8.75 Å
    assert way.depth == pytest.approx(depth)
    assert np.abs(way.points[:, [0, 2]]).max() < 1e-9  # straight up the axis
    # 8.6-8.85 Å at 3.5 Å a residue: ceil(2.5) = 3 spacings, the first the anchor's own bead's
    assert E.residues_spent(way.length, 3.5) == 2


def test_a_diagonal_channel_is_pulled_taut():
    """A channel at 45° in the section from the anchor at (-8, -8): the grid's path is some 40
    voxel steps; pulled taut it is a few straight segments, no shorter than the way straight up
    (8 Å) and no longer than the channel's axis to the surface (11.3 Å)."""
    atoms, outline = block_core()
    u = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    start = np.array([-8.0, -8.0, 0.0])
    rel = atoms - start
    along = rel @ u
    off = np.linalg.norm(rel - along[:, None] * u, axis=1)
    atoms = atoms[~((off < 4.0) & (along > -4.0))]
    way = find(atoms, start, outline)
    assert way.found and len(way.points) <= 4
    assert 8.0 <= way.length <= 8 * math.sqrt(2) + 1e-9
    assert way.points[-1][1] >= 0.0  # it ends on the surface


def test_an_anchor_sealed_in_a_cavity_has_no_path():
    """The same core with a 4.5 Å cavity about the anchor and no channel: nothing leaves (the
    search stops at 12 Å here, the cavity's whole inside being reached well before)."""
    atoms, outline = block_core()
    start = np.array([0.0, -8.0, 0.0])
    atoms = atoms[np.linalg.norm(atoms - start, axis=1) >= 4.5]
    way = E.shortest_exit(atoms, np.full(len(atoms), 1.7), start, outline, bead_radius=1.75,
                          z_half=RISE, max_length=12.0)
    assert not way.found and way.length == math.inf and len(way.points) == 0
    assert way.depth == pytest.approx(8.0)  # to the surface, y = 0
    with pytest.raises(ValueError):
        E.residues_spent(way.length, 3.5)


def test_an_anchor_on_the_surface_spends_nothing():
    atoms, outline = block_core()
    way = find(atoms, [0.0, 2.0, 0.0], outline)  # outside the outline
    assert way.found and way.length == 0.0 and way.depth == 0.0
    assert E.residues_spent(way.length, 3.5) == 0


@pytest.mark.parametrize("length, spent", [(0.0, 0), (3.5, 0), (3.6, 1), (7.0, 1), (7.01, 2),
                                           (17.82, 5)])
def test_residues_spent_counts_each_spacing_after_the_anchors_own(length, spent):
    assert E.residues_spent(length, 3.5) == spent


@pytest.fixture(scope="module")
def oqv():
    from fibrilfit import structure
    return (structure.measure_fibril(DATA / "5oqv_addedH.pdb.gz"),
            structure.measure_domain(DATA / "1gfl.pdb.gz"))


@pytest.fixture(scope="module")
def oqv_ae():
    from fibrilfit import structure
    return structure.measure_fibril(DATA / "5oqv_ae.pdb.gz")


def test_5oqv_ala42s_exit_by_the_rule_is_the_same_from_both_copies(oqv, oqv_ae):
    """Issue #50: the two copies of 5OQV (the tests' with hydrogens added, the Amyloid
    Explorer's) share the backbone to 0.03 Å, and as deposited their ways out of Ala42 differ
    (17.82 Å, 11.47 Å without OXT, sealed). By the rule (docs/model/buried-terminus.md#rule:
    side chains cut to Cβ, no OXT, to the Cβ atoms' outline, the shortest of three layers),
    measured 2026-11-27: 3.64 Å and 4.13 Å, one residue spent from both."""
    from fibrilfit.structure import mapping
    fib, _ = oqv
    for g, length in ((fib, 3.64), (oqv_ae, 4.13)):
        way = g.exit
        assert way["found"] and way["length"] == pytest.approx(length, abs=0.01)
        assert mapping.exit_values(g)["exit_residues"] == 1
        fixed = [r for r in way["sensitivity"] if r["atoms"] == "fixed"]
        assert len(fixed) == 3 and all(r["found"] and r["residues"] == 1 for r in fixed)
    # as deposited, the range the rule removes: the tests' copy sealed in one measured layer,
    # 10.02-17.82 Å (2-5 residues) in the others; the Explorer's sealed in two of three
    dep = [r for r in fib.exit["sensitivity"] if r["atoms"] == "deposited"]
    assert sorted(r["residues"] for r in dep if r["found"]) == [2, 5]
    assert sum(not r["found"] for r in dep) == 1
    dep_ae = [r for r in oqv_ae.exit["sensitivity"] if r["atoms"] == "deposited"]
    assert sum(not r["found"] for r in dep_ae) == 2
    no_oxt = [r for r in fib.exit["sensitivity"] if r["atoms"] == "deposited, no OXT"]
    assert sorted(r["length"] for r in no_oxt if r["found"]) == pytest.approx([10.02, 11.47],
                                                                             abs=0.01)


def test_the_rules_path_keeps_its_clearance_and_ends_outside_the_fixed_outline(oqv):
    from fibrilfit.geom import polygons
    from fibrilfit.structure import exit as X, fibril as F, reading
    fib, _ = oqv
    way = fib.exit
    assert way["layer"] == fib.anchors[0]["chain"]  # the reference layer's own way here
    assert way["path"][0] == pytest.approx([*fib.anchors[0]["position"],
                                            fib.anchors[0]["height"]], abs=0.01)
    loaded = reading.load(DATA / "5oqv_addedH.pdb.gz", "--fibril")
    chains = F._stacked_core(loaded, loaded.path.name, "--fibril")[0]
    cut = [X.fixed(c) for c in chains]
    ref = next(c for c in cut if c.name == way["layer"])
    origin, frame = F.layer_frame(fib)
    atoms, radii, _ = X.obstacles(cut, ref, 42, "C", origin, frame)
    assert set(np.concatenate([c.heavy_name for c in cut])) <= set(X.FIXED)
    pts = np.array(way["path"])
    t = np.linspace(0, 1, 40)[1:, None]  # the start (the CA) is not checked: its own
    samples = np.concatenate([a + t * (b - a) for a, b in zip(pts[:-1], pts[1:])])
    gap = np.linalg.norm(samples[:, None] - atoms[None], axis=-1) - radii[None] - 1.75
    assert gap.min() >= -0.01
    layer = [next(c for c in chains if c.name == a["chain"]) for a in fib.anchors]
    surface = X.fixed_outline(layer, fib.core_segments, origin, frame)
    assert not polygons.inside(surface, pts[-1:, :2])[0]  # it ends outside the Cβ outline
    assert polygons.inside(np.array(fib.core_outline), pts[-1:, :2])[0]  # inside the model's


def _one_chain(atoms, names):
    from fibrilfit.structure.reading import ChainAtoms
    n = len(atoms)
    return ChainAtoms("A", np.array([1]), ["GLY"], atoms[:1], atoms, np.ones(n, int),
                      np.full(n, 1.7), heavy_name=np.array(names, dtype=object))


def test_no_exit_needs_the_sealing_to_hold_with_the_movable_atoms_removed():
    """Test 1's straight channel plugged halfway up by one atom: as deposited it is sealed
    either way; by the rule (structure/exit.fixed) a side-chain atom (OE2) is moved aside and
    the way is open, a backbone atom (CA) keeps it sealed (docs/model/buried-terminus.md#rule)."""
    from fibrilfit.structure import exit as X
    atoms, outline = block_core()
    depth = 8.6
    axis = np.hypot(atoms[:, 0], atoms[:, 2])
    atoms = atoms[~((axis < 4.0) & (atoms[:, 1] > -depth - 4.0))]
    start = [0.0, -depth, 0.0]
    plug = np.array([[0.0, -4.0, 0.0]])
    for name, sealed_by_rule in (("OE2", False), ("CA", True)):
        chain = _one_chain(np.concatenate([atoms, plug]), [*["CA"] * len(atoms), name])
        assert not find(chain.heavy, start, outline).found
        assert find(X.fixed(chain).heavy, start, outline).found is not sealed_by_rule


def test_5oqv_gfp_spends_the_exit_and_is_no_exit_below_it(oqv):
    from fibrilfit.structure import from_files
    fib, dom = oqv
    for linker, free in ((12, 11), (14, 13), (7, 6)):
        values, block = from_files.merged(fib, [dom], None, {"linker": linker, "layers": 6})
        p = P.make_params(**values)
        way = terminus.chain_exit(p)
        assert (way.residues, way.left, p.free_linker) == (1, free, free)
        assert way.start == tuple(p.anchor) and not way.no_exit
        assert [d.member for d in p.domains] == [free]
    values, block = from_files.merged(fib, [dom], None, {"linker": 1, "layers": 6})
    p = P.make_params(**values)  # the linker ends inside the core: a verdict, not a refusal
    assert terminus.chain_exit(p).no_exit
    r = terminus.no_exit_result(p)
    assert r["answer"] == "no exit" and r["exit_needs"] == 2 and not r["accommodated"]
    way = from_files.exit_block(p, block)
    assert way["residues"] == 1 and way["length"] == pytest.approx(3.64, abs=0.01)
    assert way["rule"] == fib.exit["rule"] and len(way["sensitivity"]) == 9
    # an explicit anchor takes the measured exit with it: the model is as the option says
    values, block = from_files.merged(fib, [dom], None, {"linker": 12, "anchor": [0.557, 19.11]})
    assert "exit_residues" not in values and "exit_residues" in block["overridden"]


def test_a_surface_anchor_has_no_exit_values():
    """Every other fibril of tests/data: its C-terminal anchor's path is under one spacing
    (2.1-3.0 Å, measured 2026-11-25), so nothing is spent and the model values are as before."""
    from fibrilfit import structure
    from fibrilfit.structure import mapping
    fib = structure.measure_fibril(DATA / "6cu7.pdb.gz")
    assert fib.exit["found"] and fib.exit["length"] == pytest.approx(2.15, abs=0.01)  # rule
    assert [r["length"] for r in fib.exit["sensitivity"] if r["atoms"] == "deposited"][0] == \
        pytest.approx(2.06, abs=0.01)  # as deposited, the reference layer (as measured before)
    assert mapping.exit_values(fib) == {}
    p = P.make_params(**{k: v for k, v in mapping.model_values(fib).items()})
    assert terminus.chain_exit(p) == terminus.ChainExit(0, tuple(p.anchor), p.linker, None)


def test_a_sweeps_summary_counts_no_exit_points_as_runs_without_a_stretch():
    """'no exit' records (model.terminus.no_exit_result) have no stretch: nothing was simulated."""
    from fibrilfit.sweep import summary
    p = P.make_params(linker=3, exit_residues=4, exit_path=[[0.0, 0.0, 0.0], [20.0, 0.0, 0.0]])
    records = [{"params": {**p.to_dict(), "seed": s}, **terminus.no_exit_result(p)}
               for s in (0, 1)]
    (row,) = summary.rows(records)
    assert (row.n, row.accommodated, row.failed, row.median_stretch) == (2, 0, 0, None)


def test_the_free_linkers_beads_are_numbered_after_the_exit():
    """--pdb-atoms: 5OQV's exit spends residues 43-47 (47 is the bead at the exit, the model's
    anchor), so the free linker's beads are 48 on (before it: 43 on)."""
    from fibrilfit.structure.atoms import Sources
    c_side = Sources(None, [], anchor_residue=42, side="C")
    assert c_side.linker_numbers(3, 5).tolist() == [48, 49, 50]
    assert c_side.linker_numbers(3).tolist() == [43, 44, 45]
    assert Sources(None, [], anchor_residue=1, side="N").linker_numbers(2, 1).tolist() == [-1, -2]


def test_a_sealed_room_is_searched_in_one_box_and_a_way_out_past_it_is_still_found(monkeypatch):
    """A cavity whose whole room lies inside the first box (6 Å): the search stops there (a
    larger box holds the same room); a channel leading out past the first box is not cut off
    there (its room touches the box's sides), and is found in the next."""
    boxes = []
    real = E._in_box

    def counted(*a, **k):
        boxes.append(k["box"])
        return real(*a, **k)
    monkeypatch.setattr(E, "_in_box", counted)
    atoms, outline = block_core()
    start = np.array([0.0, -8.0, 0.0])
    cavity = atoms[np.linalg.norm(atoms - start, axis=1) >= 4.5]
    assert not find(cavity, start, outline).found
    assert boxes == [E.BOXES[0]]
    boxes.clear()
    axis = np.hypot(atoms[:, 0], atoms[:, 2])
    channel = atoms[~((axis < 4.0) & (atoms[:, 1] > -12.0))]
    way = find(channel, start, outline)
    assert way.found and 8.0 <= way.length <= 8.0 + E.STEP and boxes == list(E.BOXES[:2])


def _even_odd_each(poly, q):
    """The even-odd rule tested point by point, every edge, as written before the rows."""
    a, b = poly, np.roll(poly, -1, axis=0)
    out = []
    for x, y in q:
        straddles = (a[:, 1] > y) != (b[:, 1] > y)
        dy = np.where(b[:, 1] == a[:, 1], 1.0, b[:, 1] - a[:, 1])
        out.append((straddles & (x < a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / dy)).sum()
                   % 2 == 1)
    return np.array(out)


def test_the_polygon_tests_by_rows_and_near_edges_are_the_tests_point_by_point():
    """even_odd by a grid's rows, inside and inside_by (the boundary's distance only near an
    edge) give what testing every point on every edge gives, on a ragged outline, its
    vertices and edge midpoints (on the boundary: not inside) included."""
    from fibrilfit.geom import polygons as PG
    rng = np.random.default_rng(7)
    ang = np.sort(rng.uniform(0, 2 * np.pi, 60))
    poly = np.round(np.c_[np.cos(ang), np.sin(ang)] * rng.uniform(5, 20, 60)[:, None], 2)
    g = np.arange(-22.0, 22.0, 0.5)
    grid = np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)
    q = np.r_[grid, poly, (poly + np.roll(poly, -1, axis=0)) / 2]
    each = _even_odd_each(poly, q)
    assert (PG.even_odd(poly, q) == each).all()  # by rows: most points share a y
    assert (PG.even_odd(poly, q[::-1][:1]) == each[::-1][:1]).all()  # a single point
    dist = np.array([PG.edge_distance(poly, p[None])[0][0] for p in q])
    assert (PG.edge_distance(poly, q)[0] == dist).all()  # in blocks: the same distances
    assert (PG.inside(poly, q) == (each & (dist > 1e-9))).all()
    assert not PG.inside(poly, poly).any()  # the vertices are on the boundary
    for margin in (0.0, 0.7, 3.0):
        assert (PG.inside_by(poly, q, margin) == (each & (dist >= margin))).all()
