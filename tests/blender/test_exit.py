"""The buried terminus in a run (docs/model/buried-terminus.md#model): 5OQV's Ala42 spends 5
residues on its exit, the chain simulates the rest from the exit, a linker shorter than the
exit is the answer "no exit" (exit code 0, nothing simulated), and the exit is drawn."""
import json

import bpy
import numpy as np
import pytest
from helpers import ROOT, run_cli

DATA = ROOT / "tests" / "data"
PAIR = ("--fibril", str(DATA / "5oqv_addedH.pdb.gz"), "--domain", str(DATA / "1gfl.pdb.gz"))


def test_5oqv_gfp_at_linker_12_spends_its_exit_and_fits(tmp_path):
    """3 layers, 30 frames, tutorial, seed 0: fits. The exit by the rule
    (docs/model/buried-terminus.md#rule, MODEL_VERSION 8) spends 1 residue, 3.64 Å (5 and
    17.82 Å through the atoms as deposited, until MODEL_VERSION 7)."""
    out = tmp_path / "r.json"
    cp = run_cli("run", *PAIR, "--linker", "12", "--layers", "3", "--frames", "30",
                 "--json", str(out))
    assert cp.returncode == 0, cp.stderr
    r = json.loads(out.read_text())
    assert r["exit"]["residues"] == 1 and r["exit"]["free_linker"] == 11
    assert r["exit"]["length"] == pytest.approx(3.64, abs=0.01)
    assert r["params"]["exit_residues"] == 1 and r["params"]["linker"] == 12
    assert r["answer"] == "fits" and r["accommodated"]
    assert "exit: 1 linker residue(s) spent" in cp.stdout and "by the rule:" in cp.stdout
    assert r["sources"]["exit_residues"].startswith("5oqv_addedH.pdb.gz: measured, a 3.64 Å")
    assert {row["atoms"] for row in r["exit"]["sensitivity"]} == {
        "fixed", "deposited", "deposited, no OXT"}


def test_a_linker_shorter_than_the_exit_is_no_exit_not_an_error(tmp_path):
    """Linker 1 was refused before (`anchor: ... no straight direction ...`, exit 2)."""
    out = tmp_path / "r.json"
    cp = run_cli("run", *PAIR, "--linker", "1", "--layers", "3", "--json", str(out))
    assert cp.returncode == 0, cp.stderr
    assert "Traceback" not in cp.stderr and "error" not in cp.stderr
    r = json.loads(out.read_text())
    assert r["answer"] == r["verdict"] == "no exit" and not r["accommodated"]
    assert r["exit_needs"] == 2 and r["exit"]["residues"] == 1
    assert r["frames_simulated"] == 0 and "bake" not in r["timings_s"]
    assert cp.stdout.strip().splitlines()[-1].startswith("answer: no exit. The exit from the "
                                                         "buried anchor")


def box_exit_params(ff, **more):
    """The tutorial's box core with a made-up exit: 2 residues along a path from (12, 0, 0)."""
    return ff.model.params.make_params(
        layers=3, linker=6, exit_residues=2,
        exit_path=[[12.0, 0.0, 0.0], [16.0, 0.0, 1.0], [20.0, 0.0, 1.0]], **more)


def test_the_exit_is_drawn_along_every_chains_path(scene, ff):
    from fibrilfit import pipeline
    from fibrilfit.builders.exit_path import NAME
    p = box_exit_params(ff, protofilaments=2)
    model = pipeline.build(p, scene)
    ob = bpy.data.objects[NAME]
    assert ob.type == "CURVE" and ob.name in model.root.objects
    assert len(ob.data.splines) == p.chains == 6
    for c, spline in enumerate(ob.data.splines):
        pts = np.array([tuple(q.co)[:3] for q in spline.points])
        layer, pf = divmod(c, 2)
        want = np.array(p.exit_path)
        turn = layer * p.twist + pf * p.pf_angle
        r = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
        want[:, :2] = want[:, :2] @ r.T
        want[:, 2] += layer * p.rise + pf * p.pf_rise
        assert pts == pytest.approx(want, abs=1e-4), c
    # the chain simulated: anchor, linker - exit_residues - 1 beads, the globule
    assert len(model.chain[0]) == p.free_linker + 1 == 5
    pipeline.build(p, scene)  # built again: one exit curve, its old data gone
    assert [o.name for o in bpy.data.objects if o.type == "CURVE"] == [NAME]
    assert len(bpy.data.curves) == 1


def test_a_surface_anchor_draws_no_exit(scene, ff):
    from fibrilfit import pipeline
    pipeline.build(ff.model.params.make_params(layers=2), scene)
    assert not [o for o in bpy.data.objects if o.type == "CURVE"]
