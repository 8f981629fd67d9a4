"""bench/stop_traces.py (issue #35, docs/benchmarks.md#stopping-rule): the candidate stopping
rules replayed on a run's inflate judgements say what their labels say, and the replay counts a
stop of a run that fit in the end as a wrong stop."""
import importlib.util
import json

from helpers import ROOT

spec = importlib.util.spec_from_file_location("stop_traces", ROOT / "bench" / "stop_traces.py")
st = importlib.util.module_from_spec(spec)
spec.loader.exec_module(st)

# the clear-miss rule off: a run baked to the end of its schedule (stop_traces.to_the_end)
P = {"stretch_tolerance": 0.05, "regrow_cycles": 4, "near_cycles": 5, "clear_miss_pairs": 0,
     "clear_miss_stretch": 0.0}


def judged(cycle, pairs, stretch, overlap=2.0, frame=801):
    return {"cycle": cycle, "accommodated": False, "clashing_pairs": pairs,
            "max_bond_stretch": stretch, "max_overlap": overlap, "judged_at": frame}


def test_or_and_and_rules_fire_as_their_labels_say():
    name_or, fires_or = st.rule(0, pairs=8, stretch=10)
    name_and, fires_and = st.rule(0, pairs=8, stretch=10, both=True)
    assert "pairs >= 8 or stretch >= 10 x tol" in name_or
    assert "pairs >= 8 and stretch >= 10 x tol" in name_and
    many_pairs = judged(0, pairs=9, stretch=0.2)       # 4 x tol
    both_far = judged(0, pairs=9, stretch=0.6)         # 12 x tol
    assert fires_or(P, many_pairs) and not fires_and(P, many_pairs)
    assert fires_or(P, both_far) and fires_and(P, both_far)
    near = judged(0, pairs=9, stretch=0.1, overlap=0.5)  # the schedule's near miss: never stopped
    assert not fires_or(P, near) and not fires_and(P, near)
    assert not fires_or(P, judged(0, pairs=2, stretch=0.2))


def test_a_stop_of_a_run_that_fit_later_is_counted_wrong():
    runs = [{"params": P, "fit": True, "frames": 2403,
             "cycles": [judged(0, 9, 0.6), judged(1, 0, 0.02, 0.0, 1602) | {"accommodated": True}]},
            {"params": P, "fit": False, "frames": 4005, "cycles": [judged(0, 9, 0.6)]}]
    x = st.replay(runs, st.rule(0, pairs=8, stretch=10)[1])
    assert x["stopped"] == 2 and x["stopped_then_fit"] == 1
    assert x["frames_saved"] == round((2403 - 801 + 4005 - 801) / (2403 + 4005), 3)


def test_runs_without_inflate_judgements_are_not_traces(tmp_path):
    from fibrilfit.model.version import MODEL_VERSION
    case = tmp_path / "validate" / "tutorial" / "real"
    case.mkdir(parents=True)
    base = {"status": "ok", "model_version": MODEL_VERSION, "seed": 0, "accommodated": True,
            "frames_simulated": 801, "params": {"linker": 5, "globule_diameter": 20.0, **P}}
    lines = [dict(base), dict(base, inflate={"cycles": [judged(0, 0, 0.01) | {"accommodated": True}]})]
    (case / "results.jsonl").write_text("".join(json.dumps(x) + "\n" for x in lines))
    rows = st.traces(tmp_path / "none", also=[case / "results.jsonl"])
    assert len(rows) == 1 and rows[0]["system"] == "tutorial/real"


def test_only_runs_baked_to_their_end_are_traces(tmp_path):
    """MODEL_VERSION 5 runs, and later ones with the clear-miss rule off; a run the rule cut
    short is not a trace (docs/model/search.md#clear-miss)."""
    runs = tmp_path / "sys" / "results.jsonl"
    runs.parent.mkdir()
    inflate = {"cycles": [judged(0, 9, 0.6)]}
    base = {"status": "ok", "seed": 0, "accommodated": False, "frames_simulated": 801,
            "inflate": inflate}
    on = dict(P, clear_miss_pairs=8, clear_miss_stretch=10.0)
    lines = [dict(base, model_version=5, params={"linker": 5, "globule_diameter": 20.0, **on}),
             dict(base, model_version=6, params={"linker": 6, "globule_diameter": 20.0, **P}),
             dict(base, model_version=6, params={"linker": 7, "globule_diameter": 20.0, **on}),
             dict(base, model_version=4, params={"linker": 8, "globule_diameter": 20.0, **P})]
    runs.write_text("".join(json.dumps(x) + "\n" for x in lines))
    assert [r["linker"] for r in st.traces(tmp_path)] == [5, 6]
