"""Issue #23 (an answer a biologist can trust at first read), the parts with no scene: angles
with units, the twist guard, the answer word and its sentence, the sources and warnings of a
structure, a fibril refused as a domain, honest sweep words, the command line's small things."""
import argparse
import math
import os
import subprocess
import sys

import pytest
from helpers import ROOT

from fibrilfit.exits import UsageError
from fibrilfit.model import cases, params as P
from fibrilfit.model.param_spec import MAX_TWIST

DATA = ROOT / "tests" / "data"


# ---- 1. angles with units ------------------------------------------------------------------

@pytest.mark.parametrize("text", ["-0.961deg", "-0.961°", "-0.961 deg", "-0.961DEG",
                                  "-0.961degrees"])
def test_degrees_with_a_unit_are_converted(text):
    assert P.make_params(twist=text).twist == pytest.approx(-0.016773, abs=1e-6)


@pytest.mark.parametrize("value", ["-0.01678rad", "-0.01678", -0.01678])
def test_radians_bare_or_with_a_unit(value):
    assert P.make_params(twist=value).twist == pytest.approx(-0.01678, abs=1e-12)


def test_degrees_typed_as_radians_are_refused_with_the_degree_reading():
    with pytest.raises(P.ParamError) as err:
        P.make_params(twist="-0.961")
    text = str(err.value)
    assert err.value.param == "twist" and "\n" not in text
    assert "-0.961 rad is -55.1° per layer" in text and "write -0.961deg" in text
    assert "--force" in text
    with pytest.raises(P.ParamError, match="-55deg is"):
        P.make_params(twist="-55deg")


def test_force_builds_a_large_twist_and_its_copies_stay_forced():
    p = P.make_params(twist=-0.961, force=True)
    assert p.twist == -0.961 and p.replace(seed=3).twist == -0.961


def test_twist_at_the_limit_is_accepted():
    assert P.make_params(twist=MAX_TWIST).twist == MAX_TWIST
    assert P.make_params(twist="-11.4deg").twist == pytest.approx(math.radians(-11.4))


def test_every_angle_takes_a_unit():
    angles = [f.name for f in P.fields() if P.is_angle(f.name)]
    assert set(angles) == {"twist", "pf_rotation"}
    p = P.make_params(protofilaments=2, pf_rotation="179.3deg")
    assert p.pf_rotation == pytest.approx(math.radians(179.3))


@pytest.mark.parametrize("bad", ["abcdeg", "1.2.3rad", "deg", "5 grad"])
def test_a_bad_angle_names_the_units(bad):
    with pytest.raises(P.ParamError, match=r"twist: must be an angle .*1\.95deg"):
        P.make_params(twist=bad)


def test_case_files_take_angles_with_units(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('[params]\ntwist = "-0.961deg"\nprotofilaments = 2\n'
                    'pf_rotation = "179.3°"\n', encoding="utf-8")
    p = cases.load(path).make_params()
    assert p.twist == pytest.approx(-0.016773, abs=1e-6)
    assert p.pf_rotation == pytest.approx(math.radians(179.3))
    path.write_text('[params]\ntwist = "-0.961"\n', encoding="utf-8")
    case = cases.load(path)  # the case alone loads (under force, like the object limit) ...
    with pytest.raises(P.ParamError, match="write -0.961deg"):
        case.make_params()  # ... and its run is refused without --force


def test_sweep_ranges_of_angles_take_units():
    from fibrilfit.sweep import grid
    assert grid.parse_spec("twist", "0.5:1.5:0.5deg") == ["0.5deg", "1deg", "1.5deg"]
    assert grid.parse_spec("twist", "0.5deg:1deg:0.5deg,2°") == ["0.5deg", "1deg", "2°"]
    points = grid.build({"twist": grid.parse_spec("twist", "1:2:1deg")}, ["0"])
    assert [pt.params["twist"] for pt in points] == pytest.approx(
        [math.radians(1), math.radians(2)])
    with pytest.raises(P.ParamError, match="mixes units"):
        grid.parse_spec("twist", "1deg:0.05rad")


def test_help_texts_say_one_unit_and_mean_it():
    from fibrilfit.cli import build_parser
    parser = build_parser()
    run = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices["run"]
    helps = {a.dest: a.help for a in run._actions}
    for name in ("twist", "pf_rotation"):
        assert "[rad, or give a unit: 1.95deg" in helps[name]
    assert "179.3°" not in helps["pf_rotation"]  # it takes rad: the degrees carry their unit
    assert "3.13 rad" in helps["pf_rotation"] and "179.3deg" in helps["pf_rotation"]


# ---- 4. honest words: the answer ----------------------------------------------------------

@pytest.mark.parametrize("clashing, grazing, stretch, want", [
    (0, 0, 0.02, "fits"),
    (0, 0, 0.045, "borderline"),          # fits, within 1 point of the 5 % tolerance
    (0, 0, 0.058, "borderline"),          # the linker 5, seed 0: 5.8 %
    (0, 0, 0.07, "no layout found"),
    (3, 3, 0.01, "borderline"),           # grazing pairs only
    (3, 2, 0.01, "no layout found"),      # one deep clash
    (3, 3, 0.3, "no layout found"),       # grazing, but the linkers tore
])
def test_answer(clashing, grazing, stretch, want):
    from fibrilfit.model import answer as A
    assert A.answer(clashing=clashing, grazing=grazing, max_stretch=stretch,
                    tolerance=0.05) == want


def test_a_stretch_one_point_past_the_tolerance_is_still_borderline():
    # the band's edge is in it: tolerance 0, so |stretch − tolerance| is exactly
    # BORDERLINE_STRETCH in floating point (at 5 % the sum rounds either way)
    from fibrilfit.model import answer as A
    edge = A.BORDERLINE_STRETCH
    assert A.answer(clashing=0, grazing=0, max_stretch=edge, tolerance=0.0) == "borderline"
    assert A.answer(clashing=2, grazing=2, max_stretch=edge, tolerance=0.0) == "borderline"
    assert A.answer(clashing=0, grazing=0, max_stretch=2 * edge, tolerance=0.0) == (
        "no layout found")


def test_an_old_result_gets_its_answer_from_its_pairs():
    # a result from before the answer existed (no "answer"): counted from its pair lists, 300
    # grazing pairs of 300 clashing on a long fibril are borderline; no verdict, no answer
    from fibrilfit.model import answer as A
    pairs = [[0, k, 0.1] for k in range(300)]
    old = {"verdict": "failed", "clashing_pairs": pairs, "grazing_pairs": list(pairs),
           "max_bond_stretch": 0.01, "params": {"stretch_tolerance": 0.05}}
    assert A.of_result(old) == "borderline"
    assert A.of_result(old | {"grazing_pairs": pairs[:299]}) == "no layout found"
    assert A.of_result(old | {"answer": "no exit"}) == "no exit"
    assert A.of_result({"answer": "fits"}) is None


def result(**changes):
    r = {"fibrilfit_version": "0", "blender_version": "5.0.1", "seed": 0, "stage": "check",
         "gravity": [0.1, 0.2, 0.3], "frames_simulated": 91, "settled_at": 91,
         "cancelled": False, "timings_s": {"build": 0.1, "bake": 1, "check": 0.1},
         "params": P.DEFAULTS.to_dict() | {"linker": 5}, "verdict": "successful",
         "intersecting_faces": 0, "clashing_pairs": [], "grazing_pairs": [], "max_overlap": 0.0,
         "sphere_check": {"tolerance": 0.29}, "max_bond_stretch": 0.058,
         "linker_intact": False, "accommodated": False, "warnings": []}
    return r | changes


def test_one_failed_relaxation_says_no_layout_was_found_and_what_to_run():
    from fibrilfit.exports import run_text
    text = run_text.text(result(max_bond_stretch=0.3))
    last = text.splitlines()[-1]
    assert "do not fit" not in text and "fits" not in last.split(";")[0]
    assert last.startswith("answer: no layout found in this run")
    assert "30.0 %" in last and "5.0 %" in last
    assert "--restarts" in last and "inflate" in last and "minimal-linker" in last
    clashes = run_text.text(result(verdict="intersection", intersecting_faces=9,
                                     clashing_pairs=[[0, 1, 2.5]], max_overlap=2.5,
                                     max_bond_stretch=0.01, linker_intact=True))
    assert "1 globule pairs clash (deepest overlap 2.50 Å)" in clashes.splitlines()[-1]


def test_near_the_criterion_the_answer_is_borderline():
    from fibrilfit.exports import run_text
    assert "answer: borderline" in run_text.text(result())  # 5.8 % against 5 %
    fits = run_text.text(result(max_bond_stretch=0.045, linker_intact=True, accommodated=True))
    assert "answer: borderline (fits by the criterion)" in fits
    graze = run_text.text(result(verdict="intersection", clashing_pairs=[[0, 1, 0.1]],
                                   grazing_pairs=[[0, 1, 0.1]], max_bond_stretch=0.0,
                                   linker_intact=True, intersecting_faces=3))
    assert "answer: borderline" in graze and "only graze" in graze
    good = run_text.text(result(max_bond_stretch=0.0, linker_intact=True, accommodated=True))
    assert good.splitlines()[-1].startswith("answer: fits.")


# ---- 2. the model up front -----------------------------------------------------------------

def test_printed_result_states_the_model_and_its_sources():
    from fibrilfit.exports import run_text
    r = result(params=P.DEFAULTS.to_dict() | {"twist": -0.016773, "protocol": "inflate"},
               sources={"linker": "2n0a.pdb.gz: modelled tail 98-140 (the anchor and 43 "
                                  "residues)", "twist": "2n0a.pdb.gz: measured", "seed": "option",
                        "layers": "case", "rise": "default"})
    model = next(line for line in run_text.text(r).splitlines() if line.startswith("model:"))
    for text in ("rise 4.8 Å", "twist -0.961° per layer", "left-handed", "1 protofilament",
                 "anchor 21.75 Å from the axis", "linker 6 residues (from 2n0a.pdb.gz: "
                 "modelled tail 98-140", "globule 30 Å", "protocol inflate"):
        assert text in model, text
    said = next(line for line in run_text.text(r).splitlines() if line.startswith("sources:"))
    assert said == ("sources: linker, twist from 2n0a.pdb.gz; seed from options; layers from "
                    "the case; the rest defaults")


def test_printed_result_counts_frames_in_the_users_terms():
    from fibrilfit.exports import run_text
    periodic = result(frames_simulated=1250, settled_at=None, periodic={
        "images": {"moving": 1, "static": 1, "cells": [-1, 1]}, "check_cells": 1, "chains": 13,
        "scene_frames_per_frame": 5}, params=P.DEFAULTS.to_dict() | {"periodic": 13})
    text = run_text.text(periodic)
    assert "baked 250 frames (1250 scene frames" in text and "baked 1250" not in text
    assert "not settled within 250 frames" in text and "at frame 250:" in text
    inflate = run_text.text(result(
        frames_simulated=318, settled_at=None, max_bond_stretch_bake=0.1,
        max_bond_stretch_bake_frame=101, push_apart_end_frame=2, intact_from_frame=302,
        frames_over_tolerance=95, params=P.DEFAULTS.to_dict() | {"protocol": "inflate"},
        inflate={"start_scale": 0.16, "cycles": [
            {"cycle": 0, "judged_at": 157, "accommodated": False, "clashing_pairs": 0,
             "max_bond_stretch": 0.051}]}))
    assert "push-apart" not in inflate and "(frame 2)" not in inflate
    assert "cycle 0 judged at frame 157" in inflate and "within tolerance from frame 302" in inflate
    assert "not settled" not in inflate  # inflate judges its own layouts


def test_printed_result_lists_every_file_written():
    from fibrilfit.exports import run_text
    files = {"json": "o/r.json", "blend": "o/r.blend", "movie": "o/m.mp4",
             "envelope_plot": "o/e.png", "save_case": "o/c.toml"}
    text = run_text.text(result(movie={"error": "no ffmpeg"}), files=files)
    assert "wrote: result o/r.json, blend file o/r.blend, envelope plot o/e.png, case o/c.toml" \
        in text and "m.mp4" not in text  # a failed one is not listed as written


# ---- 3. warnings travel; a fibril is not a domain ----------------------------------------

def test_structure_warnings_and_sources():
    from fibrilfit import structure
    from fibrilfit.structure import from_files
    fib = structure.measure_fibril(DATA / "5oqv_addedH.pdb.gz")
    dom = structure.measure_domain(DATA / "1gfl.pdb.gz")
    applied, block = from_files.split(fib, dom, explicit={"linker"},
                                      known={f.name for f in P.fields()})
    warned = block["warnings"]
    assert any("5oqv_addedH.pdb.gz: anchor" in w and "buried" in w for w in warned)
    assert any(w.startswith("1gfl.pdb.gz:") and "chain A used" in w for w in warned)
    src = block["sources"]
    assert set(src) == set(applied) | {"linker"}  # an option's linker: what the numbering gives
    assert src["linker"].startswith("the --linker option")
    assert src["globule_diameter"].startswith("1gfl.pdb.gz: measured") and "chain A" in src[
        "globule_diameter"]
    assert "BURIED" in src["anchor"]
    tail = from_files.split(structure.measure_fibril(DATA / "2n0a.pdb.gz"), None, explicit=set(),
                            known={f.name for f in P.fields()})[1]["sources"]
    assert tail["linker"].startswith("2n0a.pdb.gz: modelled tail 98-140")


@pytest.mark.parametrize("name", ["6cu7", "7ymn", "8a9l"])
def test_a_fibril_is_refused_as_a_domain(name):
    from fibrilfit import structure
    from fibrilfit.structure.errors import StructureError
    with pytest.raises(StructureError, match="holds a stacked fibril") as err:
        structure.measure_domain(DATA / f"{name}.pdb.gz")
    assert "--domain" in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("name", ["1ubq", "1gfl"])
def test_domains_are_not_fibrils(name):
    from fibrilfit import structure
    assert structure.measure_domain(DATA / f"{name}.pdb.gz").globule_diameter > 0


# ---- 4. sweeps never call a fraction what its seeds cannot show ----------------------------

def test_sweep_minimal_linker_says_what_two_seeds_show():
    from fibrilfit.sweep import summary
    records = [{"params": P.DEFAULTS.to_dict() | {"linker": L, "seed": s}, "status": "ok",
                "accommodated": L >= 6, "verdict": "successful", "max_bond_stretch": 0.0,
                "frames_simulated": 90} for L in (5, 6) for s in (0, 1)]
    lines = summary.minimal_lines(summary.rows(records), 0.95)
    assert "protocol tutorial, 2 seeds per point" in lines[0]
    assert "reaching 95 %" not in "\n".join(lines)
    assert "linker 6 (all 2 of 2 seeds accommodated, 95 % CI 0.34-1.00; 2 seeds cannot show " \
           "P(fit) ≥ 0.95" in lines[1] and "at least 73 seeds" in lines[1]
    assert summary.seeds_to_show(0.95) == 73 and summary.seeds_to_show(1.0) is None
    head = summary.csv_text(summary.rows(records)).splitlines()[0]
    assert head.endswith(",protocol")


def test_the_restarts_check_compares_verdicts():
    from fibrilfit.api.model import ResolvedModel
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.api.one_run import annotate
    plan, case = make_plan(RunPlan, {"restarts": 2})
    p = P.make_params(seed=1)
    best = {"seed": 1, "accommodated": True, "verdict": "successful", "max_bond_stretch": 0.0101}
    for stretch, verdict, accommodated, same in [(0.0102, "successful", True, True),
                                                 (0.0101, "intersection", False, False)]:
        restarts = {"runs": [best]}
        r = {"max_bond_stretch": stretch, "verdict": verdict, "accommodated": accommodated,
             "warnings": []}
        annotate(plan, p, r, ResolvedModel(p, {}, None, None), restarts, case)
        assert restarts["reproduced"] is same
        assert any("did not reproduce" in w for w in r["warnings"]) is not same
        assert r["sources"]["seed"].startswith("the best of --restarts 2")


def test_sources_name_every_parameter(tmp_path):
    from fibrilfit.api.model import param_sources
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.cli import build_parser
    case_file = tmp_path / "c.toml"
    case_file.write_text("[params]\nlinker = 9\nlayers = 8\n", encoding="utf-8")
    argv = ["run", "--case", str(case_file), "--layers", "6", "--twist=-0.9deg"]
    args = build_parser().parse_args(argv)
    given = {k: v for k, v in vars(args).items() if k not in ("command", "case")}
    plan, case = make_plan(RunPlan, given, case=args.case, command="run")
    src = param_sources(plan.model, P.make_params(**plan.model), case=case)
    assert set(src) == {f.name for f in P.fields()}
    assert (src["linker"], src["layers"], src["twist"], src["rise"]) == (
        "case", "option", "option", "default")
    assert src["pf_rotation"] == "default: 2π/K"


def test_a_saved_case_keeps_no_stale_description():
    case = cases.from_dict({"name": "N", "description": "linker 25 on 7ZIR", "expected": "fits",
                            "observed": "it fits", "params": {"linker": 25}})
    same = case.resolved(P.make_params(linker=25))
    assert same["description"] == "linker 25 on 7ZIR" and same["expected"] == "fits"
    changed = case.resolved(P.make_params(linker=4), changed=["linker"])
    assert cases.Case({"name": "M"}, {}).resolved(P.DEFAULTS, changed=["linker"]) == {
        "name": "M", "params": P.DEFAULTS.to_dict(), "overridden": []}  # nothing to go stale
    assert "25" not in changed["description"] and "linker" in changed["description"]
    assert "expected" not in changed and "observed" not in changed
    assert cases.from_dict(cases.tomllib.loads(cases.dumps(changed)))  # still a valid case


# ---- 5. the small things -------------------------------------------------------------------

@pytest.mark.parametrize("argv, hint", [
    (["run", "--linkr", "5"], "did you mean --linker?"),
    (["run", "--globule-diamter=30"], "did you mean --globule-diameter?"),
    (["sweep", "--seed-lst", "0"], "did you mean --seed-list?"),
    (["rn"], "did you mean run?"),
])
def test_a_typo_gets_a_suggestion(argv, hint):
    from fibrilfit.cli import build_parser
    with pytest.raises(UsageError) as err:
        build_parser().parse_args(argv)
    assert hint in str(err.value) and "\n" not in str(err.value)


def test_no_bpy_is_one_line_pointing_to_the_venv():
    code = ("import runpy, sys; sys.modules['bpy'] = None; sys.argv = ['headless.py', 'run']; "
            "sys.exit(runpy.run_path('headless.py', run_name='__main__'))")
    env = {k: v for k, v in os.environ.items() if k != "FIBRILFIT_TRACEBACK"}
    cp = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                        timeout=120, env=env)
    assert cp.returncode == 2, cp.stderr
    lines = cp.stderr.strip().splitlines()
    assert len(lines) == 1 and "please report" not in lines[0]
    assert ".venv/bin/python headless.py" in lines[0] and "make run" in lines[0]
    assert "blender -b -P headless.py" in lines[0]


def test_inspect_into_a_closed_pipe_is_no_bug():
    read, write = os.pipe()
    os.close(read)  # the reader (`| head`) has gone before the first line
    try:
        cp = subprocess.run([sys.executable, "headless.py", "inspect", "--domain",
                             str(DATA / "1ubq.pdb.gz")], stdout=write, stderr=subprocess.PIPE,
                            text=True, cwd=ROOT, timeout=120)
    finally:
        os.close(write)
    assert "BrokenPipeError" not in cp.stderr and "please report" not in cp.stderr
    assert cp.returncode not in (0, 4)


def test_inspect_json_to_stdout():
    import json
    cp = subprocess.run([sys.executable, "headless.py", "inspect", "--domain",
                         str(DATA / "1ubq.pdb.gz"), "--json", "-"], capture_output=True,
                        text=True, cwd=ROOT, timeout=120)
    assert cp.returncode == 0, cp.stderr
    assert json.loads(cp.stdout)["domain"]["rg"] == pytest.approx(11.73, abs=0.01)
    assert "rg 11.73 Å" in cp.stderr
