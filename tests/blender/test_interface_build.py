"""Interface termini built (docs/guide/structures.md#interface-termini): 6ZRR's protofilament 1
starts at its own Thr47's way out, not at protofilament 0's chain turned onto it (which lay
9.2 Å inside the core), and each protofilament's own exit path is drawn."""
import bpy
import numpy as np
import pytest
from helpers import ROOT

DATA = ROOT / "tests" / "data"


def test_6zrr_each_protofilament_starts_where_its_own_terminus_leaves(scene, ff):
    from fibrilfit import pipeline
    from fibrilfit.api import model as M
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.builders.exit_path import NAME
    from fibrilfit.geom import polygons
    from fibrilfit.model import helix
    plan = make_plan(RunPlan, {"fibril": str(DATA / "6zrr.pdb.gz"), "layers": 3, "linker": 6,
                               "globule_diameter": 20.0})[0]
    p = M.resolve(plan).p
    assert p.protofilaments == 3 and np.asarray(p.pf_anchors)[:, 2].tolist() == [0, 2, 0]
    model = pipeline.build(p, scene)
    bpy.context.view_layer.update()
    own = np.asarray(p.pf_anchors)[:, :2]
    outline = p.outline()
    k, j = helix.chain_layers(p)
    assert len(model.chain) == p.chains == 9
    for c, members in enumerate(model.chain):
        assert len(members) == p.free_linker + 1 == 5  # the smallest free linker: 6 - 2, + globule
        first = np.array(members[0].matrix_world.translation)
        back = helix.turn_xy(first[0], first[1], -k[c] * p.twist)
        assert back == pytest.approx(own[j[c]], abs=1e-4), c  # its own terminus's anchor
        dist = polygons.edge_distance(outline, back[None])[0][0]
        assert not polygons.inside(outline, back[None])[0] and dist >= p.residue_radius - 0.01
        assert first[2] == pytest.approx(k[c] * p.rise + p.pf_offsets()[1][j[c]], abs=1e-4)
    # protofilament 1's own path, once per layer (0 and 2 are on the surface: none drawn)
    splines = bpy.data.objects[NAME].data.splines
    assert len(splines) == p.layers
    path = np.asarray(p.pf_exit_paths)[:, 1:]
    for layer, spline in enumerate(splines):
        pts = np.array([tuple(q.co)[:3] for q in spline.points])
        back = helix.turn_xy(pts[:, 0], pts[:, 1], -layer * p.twist)
        assert back == pytest.approx(path[:, :2], abs=1e-4)
