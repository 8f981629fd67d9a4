"""Bare tails in a periodic cell (issue #44 item 1): the undecorated subunits' tails get images
across the cell's ends like the linkers' beads, and the check counts a tail bead against every
globule of the infinite fibril (docs/model/occupancy.md#bare-tails)."""
import math

import numpy as np
import pytest

from fibrilfit.builders.periodic import CELL, CHAIN, STATIC, TAIL, image_collection
from fibrilfit.builders.scene import INDEX, LAYER, PROTOFILAMENT
from fibrilfit.model import helix, occupancy


def _centre(ob) -> np.ndarray:
    return np.array(ob.matrix_world.translation, dtype=float)


@pytest.mark.one_bpy
def test_bare_tails_in_a_cell_have_images_bake_and_are_judged(scene, ff):
    """A 14-layer cell at occupancy 0.5 with bare_tail 10: each undecorated subunit has a tail
    of 10 members (a passive anchor, 9 beads), each bead with an image, images above and below
    the cell; the tails at the cell's end layers have an image of every member (anchor too)
    across the end they touch; every image stands at S^m of its source; a short bake stays
    finite; and a tail bead moved onto the image of a globule from the other end of the cell is
    named by the check (with its layer in the infinite fibril) and makes the run not fit."""
    from mathutils import Matrix
    p = ff.model.params.make_params(periodic=14, occupancy=0.5, bare_tail=10, seed=0, frames=20)
    model = ff.builders.build_model(p, scene)
    mask = occupancy.decorated(p)
    M = p.periodic
    assert len(model.chain) == 7 and len(model.tails) == 7
    assert all(len(t) == 10 and t[0].rigid_body.type == "PASSIVE" for t in model.tails)
    assert all(not mask[t[0][LAYER], t[0][PROTOFILAMENT]] for t in model.tails)

    moving = [ob for ob in image_collection(model).objects if ob.get(TAIL)]
    static = [ob for ob in image_collection(model, STATIC).objects if ob.get(TAIL)]
    imaged = {(ob[CHAIN], ob[INDEX], ob[CELL]) for ob in moving}
    anchors = {(ob[CHAIN], ob[CELL]) for ob in static}
    ends = [(t, 1 if tail[0][LAYER] == 0 else -1) for t, tail in enumerate(model.tails)
            if tail[0][LAYER] in (0, M - 1)]
    assert ends, "the pattern should leave an end layer undecorated (seed 0: ...AAAA.AA..A.)"
    for t, m in ends:  # layer 0's image sits above the top (m = +1), layer M-1's below
        assert {(t, i, m) for i in range(1, 10)} <= imaged, (t, m)
        assert (t, m) in anchors
    # a tail reaches ~45 Å and the cell is 67 Å tall: every bead of every tail has an image,
    # and every tail has images above and below the cell
    for t in range(len(model.tails)):
        assert {i for u, i, _ in imaged if u == t} == set(range(1, 10)), t
        assert {m for u, _, m in imaged if u == t} >= {-1, 1}, t
    for ob in moving:  # each at S^m of its source (the follower placed them at build)
        source = model.tails[ob[CHAIN]][ob[INDEX]]
        want = helix.apply_points(p, ob[CELL], _centre(source)[None])[0]
        assert np.allclose(_centre(ob), want, atol=1e-3)
        assert ob.rigid_body.kinematic and ob.rigid_body.type == "PASSIVE"

    baked = ff.pipeline.bake(model, scene)
    assert baked["frames_simulated"] > 0
    tails = np.array([[_centre(ob) for ob in t] for t in model.tails])
    chains = ff.analysis.verdict.chain_positions(model)
    assert np.isfinite(tails).all() and np.isfinite(chains).all()
    assert np.abs(tails[..., 2]).max() < 10 * M * p.rise  # nothing flew off
    for ob in moving:  # the images just across the ends followed their sources to the end
        if (ob[CHAIN], ob[CELL]) in {(t, m) for t, m in ends}:
            source = model.tails[ob[CHAIN]][ob[INDEX]]
            want = helix.apply_points(p, ob[CELL], _centre(source)[None])[0]
            assert np.allclose(_centre(ob), want, atol=1e-3)

    checked = ff.analysis.check_model(model)
    block = checked["tail_clashes"]
    assert block["beads"] == 7 * 10 and block["cells"] >= 1
    assert all(math.isfinite(d) for *_, d in block["pairs"])
    # a bead of the lowest undecorated tail onto S^-1 of the highest globule, and one of the
    # highest tail onto S^+1 of the lowest globule: both pairs cross the cell's ends (the
    # globule against the bead's image S^+1, layer k + M, and S^-1, layer k - M)
    def order(members):  # indices, lowest layer first
        return sorted(range(len(members)), key=lambda c: members[c][0][LAYER])
    want = []
    for t, g, m in ((order(model.tails)[0], order(model.chain)[-1], -1),
                    (order(model.tails)[-1], order(model.chain)[0], +1)):
        where = helix.apply_points(p, m, _centre(model.chain[g][-1])[None])[0]
        model.tails[t][5].matrix_world = Matrix.Translation(where.tolist())
        tail = model.tails[t][0]
        want.append([g, [tail[LAYER] - m * M, tail[PROTOFILAMENT], 5],
                     pytest.approx(p.globule_radius + p.residue_radius, abs=1e-3)])
    hit = ff.analysis.check_model(model)
    for pair in want:
        assert pair in hit["tail_clashes"]["pairs"]
    assert not hit["accommodated"] and hit["answer"] != "fits"
