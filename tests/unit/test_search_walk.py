"""Issue #13: the inflate protocol, restarts and the minimal-linker map."""
import subprocess
import sys
import pytest
from fibrilfit.model import params as P
from fibrilfit.search import minimal, restarts
from helpers import ROOT, bench_module

PY = sys.executable


def test_protocol_is_a_choice_named_in_its_error():
    assert P.make_params(protocol="Inflate ").protocol == "inflate"
    with pytest.raises(P.ParamError, match="protocol: must be one of tutorial, inflate"):
        P.make_params(protocol="anneal")
    p = P.make_params(protocol="inflate", grow_frames=10, hold_frames=5, regrow_cycles=2)
    assert p.bake_frames() == (3 + 5) * 16  # near_cycles (5) more for a near miss
    assert p.replace(near_cycles=0).bake_frames() == 3 * 16
    # polishing on: each cycle may be polished, one hold more
    assert p.replace(polish_factor=4, near_cycles=0).bake_frames() == 3 * (11 + 2 * 5)


def test_sweeps_take_the_protocol_as_an_axis():
    from fibrilfit.sweep import grid
    points = grid.build({"protocol": grid.parse_spec("protocol", "tutorial,inflate")}, ["0"])
    assert [pt.point["protocol"] for pt in points] == ["tutorial", "inflate"]
    with pytest.raises(P.ParamError, match="protocol"):
        grid.build({"protocol": grid.parse_spec("protocol", "tutorial,grow")}, ["0"])


def test_cli_refuses_a_bad_protocol_in_one_line(tmp_path):
    proc = subprocess.run([PY, str(ROOT / "headless.py"), "run", "--protocol", "anneal"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.strip().count("\n") == 0 and "--protocol" in proc.stderr


def _record(seed, fits, pairs=0, stretch=0.0):
    return {"params": {"seed": seed}, "status": "ok", "accommodated": fits, "verdict":
            "successful" if not pairs else "intersection", "clashing_pairs": [[0, 1, 1.0]] * pairs,
            "max_overlap": float(pairs), "max_bond_stretch": stretch, "frames_simulated": 100}


def test_restarts_tally_has_p_fit_its_wilson_interval_and_the_best_seed():
    recs = [_record(0, False, 2, 0.1), _record(1, True), _record(2, False, 1, 0.02),
            {"params": {"seed": 3}, "status": "failed", "error": "boom"}]
    s = restarts.tally(recs)
    assert (s["restarts"], s["failed"], s["accommodated"], s["best_seed"]) == (3, 1, 1, 1)
    assert s["p_fit"] == pytest.approx(1 / 3, abs=1e-4)
    lo, hi = s["p_fit_interval"]
    assert 0 < lo < 1 / 3 < hi < 1
    none = restarts.tally([_record(0, False, 1), _record(1, False, 3)])
    assert none["p_fit"] == 0 and none["p_fit_interval"][0] == 0 and none["best_seed"] == 0


def answering(fits, noted=lambda p, r: (p["linker"], p["seed"])):
    """An executor answering from a table, no Blender (bench/walk_replay.py's Answering): a
    run fits when `fits(params)`; `ran` lists `noted(params, record)`."""
    return bench_module("walk_replay").Answering(
        lambda p: _record(p["seed"], fits(p)), noted)


@pytest.mark.parametrize("stop, window, ran", [(False, 1, [0, 1, 2, 3, 4]), (True, 1, [0, 1, 2]),
                                               (True, 2, [0, 1, 2, 3])])
def test_stop_on_fit_starts_no_seed_after_a_fit(tmp_path, stop, window, ran):
    base = P.make_params(linker=5).to_dict()
    ex = answering(lambda p: p["seed"] in {2, 4}, noted=lambda p, r: p["seed"])
    recs = restarts.run_restarts(ex, base, range(5), tmp_path / "r.jsonl", stop_on_fit=stop,
                                 window=window)
    assert ex.ran == ran and [r["params"]["seed"] for r in recs] == ran
    assert restarts.tally(recs)["best_seed"] == 2


@pytest.mark.parametrize("start", [1, 3, 5, 9])
def test_walk_finds_the_minimum_with_a_miss_just_below_it(start):
    w = minimal.Walk(30.0, start, max_linker=20)
    while (L := w.next_linker()) is not None:
        w.record(L, 2 if L >= 5 else 0, 5)
    row = w.row()
    assert row["minimal_linker"] == 5 and row["linker_below"] == 4
    assert row["p_fit"] == 0.4 and row["p_fit_below"] == 0.0 and row["p_fit_below_interval"][1] < 0.5
    # every length between the guess and the minimum costs at most about log2 of the distance
    assert {4, 5} <= set(w.tried) and len(w.tried) <= 2 * abs(start - 5).bit_length() + 3


@pytest.mark.parametrize("start, minimum, path", [
    (7, 3, [7, 6, 4, 2, 3]),           # down in steps 1, 2; a step past the floor bisects
    (9, 2, [9, 8, 6, 2, 1]),
    (9, 5, [9, 8, 6, 2, 4, 5]),        # bracketed by 6 and 2: bisection
    (1, 12, [1, 2, 4, 8, 16, 12, 10, 11]),  # up in steps 1, 2, 4, 8
])
def test_the_walk_gallops_from_the_guess_then_bisects(start, minimum, path):
    # the method of fibrilfit/search/minimal.py (docs/model/search.md): the path, not only the
    # answer (a walk that finds the same minimum by more runs costs more)
    w = minimal.Walk(30.0, start, max_linker=40)
    asked = []
    while (L := w.next_linker()) is not None:
        asked.append(L)
        w.record(L, 1 if L >= minimum else 0, 1)
    assert asked == path and w.minimal == minimum


def _screened(w, minimum, p_fit=lambda L, seed: True):
    """Drive a walk with restarts as minimal-linker does: a fit needs L >= minimum and the
    seed's own luck (p_fit), seeds run in order; returns the (length, restarts) asked."""
    asked = []
    while (step := w.next_step()) is not None:
        L, n = step
        assert len(asked) < 60 and 1 <= L <= w.max_linker
        asked.append((L, n))
        fits = sum(L >= minimum and p_fit(L, s) for s in range(n))
        w.record(L, fits, n)
    return asked


@pytest.mark.parametrize("start", [1, 3, 9, 19])
@pytest.mark.parametrize("minimum", [1, 2, 11, 20])
def test_a_screened_walk_measures_the_answer_with_every_restart(start, minimum):
    """Issue #25: lengths on the way get SCREEN restarts; the minimum and one below get all R,
    so the row is what a walk with R everywhere reports."""
    w = minimal.Walk(30.0, start, max_linker=20, restarts=5)
    asked = _screened(w, minimum)
    assert w.minimal == minimum and w.tried[minimum] == (5, 5)
    assert minimum == 1 or w.tried[minimum - 1] == (0, 5)
    full = sum(n for _, n in asked)
    assert all(n in (minimal.SCREEN, 5) for _, n in asked)
    # only the answer's two lengths cost all five
    assert sorted(L for L, n in asked if n == 5) == sorted({minimum, max(1, minimum - 1)})
    assert full <= 5 * 2 + minimal.SCREEN * (2 * abs(start - minimum).bit_length() + 3)


def test_a_screened_miss_that_fits_with_more_restarts_moves_the_walk_down():
    """Linker 7 fits only with seed 3 (a screen of 2 misses it); 8 and up fit with any seed.
    The walk must not report 8: completing 7 finds the fit, and 6 is then measured in full."""
    w = minimal.Walk(30.0, 5, max_linker=20, restarts=5)
    _screened(w, 7, p_fit=lambda L, s: L >= 8 or s == 3)
    assert w.minimal == 7 and w.tried[7] == (1, 5) and w.tried[6] == (0, 5)


def test_a_screened_walk_that_finds_nothing_runs_the_cap_in_full():
    w = minimal.Walk(60.0, 3, max_linker=12, restarts=5)
    asked = _screened(w, 99)
    assert w.minimal is None and w.tried[12] == (0, 5) and asked[-1] == (12, 5)
    assert w.row()["linker_below"] == 12 and w.row()["restarts"] == 5


def test_walk_gives_up_at_the_cap_and_at_one_needs_no_miss():
    w = minimal.Walk(60.0, 3, max_linker=6)
    while (L := w.next_linker()) is not None:
        w.record(L, 0, 5)
    assert w.minimal is None and max(w.tried) == 6 and w.row()["linker_below"] == 6
    w = minimal.Walk(5.0, 3, max_linker=6)
    while (L := w.next_linker()) is not None:
        w.record(L, 5, 5)
    assert w.minimal == 1 and w.row()["p_fit_below"] is None


def test_minimal_linker_passes_model_options_through(tmp_path):
    """--periodic reaches the model (inflate in a cell is allowed; a too-short cell is refused
    in one line), nothing written."""
    proc = subprocess.run([PY, str(ROOT / "headless.py"), "minimal-linker", "--periodic", "3",
                           "--out", str(tmp_path / "x")], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2 and "periodic" in proc.stderr and "at least" in proc.stderr
    assert proc.stderr.strip().count("\n") == 0 and not (tmp_path / "x").exists()


def test_minimal_linker_refuses_a_given_linker(tmp_path):
    proc = subprocess.run([PY, str(ROOT / "headless.py"), "minimal-linker", "--linker", "5",
                           "--out", str(tmp_path / "x")], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2 and "--linker" in proc.stderr
    assert not (tmp_path / "x").exists()


def _walk(w, minimum):
    order = []
    while (L := w.next_linker()) is not None:
        assert L not in w.tried and 1 <= L <= w.max_linker and len(order) < 50
        order.append(L)
        w.record(L, 2 if L >= minimum else 0, 3)
    return order


@pytest.mark.parametrize("start", [1, 3, 5, 9, 19])
@pytest.mark.parametrize("minimum", [1, 2, 5, 11, 19, 20])
def test_a_walk_below_a_known_fit_finds_the_same_minimum_and_measures_its_neighbours(start,
                                                                                   minimum):
    """Issue #25: with a known fit (the real linker) the walk brackets and bisects; it ends with
    the same answer as the one-residue walk, measured the same way (a fit at the minimum, R
    missed restarts one below)."""
    w = minimal.Walk(30.0, start, max_linker=20, known_fit=20)
    order = _walk(w, minimum)
    without = minimal.Walk(30.0, start, max_linker=20)
    _walk(without, minimum)
    assert w.row()["minimal_linker"] == without.row()["minimal_linker"] == minimum
    assert w.tried[minimum] == (2, 3)
    assert minimum == 1 or w.tried[minimum - 1] == (0, 3)
    assert w.row()["p_fit_below"] == (None if minimum == 1 else 0.0)
    # a guess far off costs steps that grow like log2 of the distance, not the distance itself
    assert len(order) <= 2 * abs(start - minimum).bit_length() + 3
    if abs(start - minimum) >= 8:  # fewer than a one-residue walk's lengths
        assert len(order) < abs(start - minimum) + 1


def test_a_walk_below_a_known_fit_past_its_cap_gives_up_at_the_cap():
    w = minimal.Walk(30.0, 3, max_linker=40, known_fit=121)  # Sup35: real 121, searched to 40
    order = _walk(w, 45)
    assert w.minimal is None and max(order) == 40 and w.row()["linker_below"] == 40
    w = minimal.Walk(30.0, 3, max_linker=40, known_fit=121)
    assert _walk(w, 40)[-1] in (39, 40) and w.minimal == 40


def test_a_known_fit_the_walk_cannot_reproduce_falls_back_to_stepping_up():
    """The known fit came from other seeds (or another protocol): if its R restarts all miss,
    the walk no longer counts on it."""
    w = minimal.Walk(30.0, 5, max_linker=12, known_fit=6)
    order = _walk(w, 9)
    assert order[:2] == [5, 6] and w.minimal == 9 and w.tried[8] == (0, 3)


def test_a_known_fit_that_a_screen_misses_is_measured_in_full_before_it_is_dropped():
    """The known fit at 6 fits only with seed 3: the screen (seeds 0-1) misses it, all five find
    it; the walk must neither loop on the screen nor drop the known fit after it."""
    w = minimal.Walk(30.0, 5, max_linker=12, known_fit=6, restarts=5)
    asked = _screened(w, 6, p_fit=lambda L, s: L >= 7 or s == 3)
    assert (6, 5) in asked and w.minimal == 6 and w.tried[5] == (0, 5)
    assert len(asked) == len(set(asked))  # nothing asked twice


# ---- issue #35: restarts that cannot change the answer are not run ----------------------------

@pytest.mark.parametrize("start", [1, 3, 9, 19])
@pytest.mark.parametrize("minimum", [1, 2, 11, 20])
def test_stopping_at_a_fit_keeps_the_minimal_linker_and_the_misses_below_it(start, minimum):
    """The walk's question at a length is whether any restart fits: stopping at the first fit
    gives the same minimum, with all R missed one below, and costs fewer runs."""
    luck = lambda L, s: s % 3 == 2 or L >= minimum + 2  # the first two seeds miss near the minimum
    full = minimal.Walk(30.0, start, max_linker=20, restarts=5)
    _screened(full, minimum, luck)
    fast = minimal.Walk(30.0, start, max_linker=20, restarts=5, stop_at_fit=True)
    asked = _screened_stopping(fast, minimum, luck)
    assert fast.minimal == full.minimal == minimum
    assert minimum == 1 or fast.tried[minimum - 1] == (0, 5)
    assert fast.tried[minimum][0] >= 1 and fast.tried[minimum][1] <= 5
    row = fast.row()
    assert row["stopped_at_fit"] == (fast.tried[minimum][1] < 5)
    assert row["p_fit"] == round(fast.tried[minimum][0] / fast.tried[minimum][1], 4)
    assert asked <= sum(n for _, n in full.tried.values())


def _screened_stopping(w, minimum, luck):
    """_screened with each length's seeds stopping at the first fit; returns the runs made."""
    runs = 0
    while (step := w.next_step()) is not None:
        L, n = step
        k, done = w.tried.get(L, (0, 0))
        assert runs < 300 and 1 <= L <= w.max_linker and not (k and w.stop_at_fit)
        for s in range(done, n):
            runs += 1
            done += 1
            if L >= minimum and luck(L, s):
                k += 1
                break
        w.record(L, k, done)
    return runs


def test_lengths_below_the_proven_bound_are_settled_not_run():
    """A fit at the bound is the minimum with nothing run below it; above it the walk is as
    before, and never tries a length below the bound."""
    w = minimal.Walk(30.0, 2, max_linker=20, restarts=5, stop_at_fit=True, floor=6)
    _screened_stopping(w, 6, lambda L, s: True)
    assert w.minimal == 6 and min(w.tried) == 6
    row = w.row()
    assert row["below_settled_by_bound"] and row["p_fit_below"] == 0.0
    assert row["p_fit_below_interval"] is None and row["restarts_below"] == 0
    w = minimal.Walk(30.0, 2, max_linker=20, restarts=5, floor=4)
    _screened(w, 7)
    assert w.minimal == 7 and w.tried[6] == (0, 5) and min(w.tried) >= 4
    assert not w.row()["below_settled_by_bound"]
    w = minimal.Walk(30.0, 2, max_linker=10, restarts=5, floor=12)  # nothing possible up to the cap
    assert w.next_step() is None and w.row()["minimal_linker"] is None


def test_restarts_decided_by_a_fit_or_by_the_interval_asked():
    ok = [_record(s, s == 1) for s in range(3)]
    assert restarts.decided(ok[:1], stop_on_fit=True) is None
    assert restarts.decided(ok[:2], stop_on_fit=True) == "a fit found"
    assert restarts.decided(ok, stop_on_fit=False) is None  # all R by default
    misses = [_record(s, False) for s in range(12)]
    # 0 of n: the Wilson interval's width is 3.84 / (n + 3.84): 0.28 at 10, 0.24 at 12
    assert restarts.decided(misses[:9], width=0.25) is None
    assert restarts.decided(misses, width=0.25) == "interval at most 0.25 wide"


def test_the_walk_starts_no_restart_of_a_length_once_one_fits_there(tmp_path):
    """linker_map.step_walks on an executor that answers from a table: at the minimum the walk
    stops at the first fit (seed 1: seeds 0 and 1 were in flight on 2 workers), one below every
    seed runs; with --all-restarts every seed runs at both."""
    from fibrilfit.api.plans import MinimalLinkerPlan
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.search import linker_map
    from fibrilfit.search.plans import BatchOutput, SearchPlan

    for every, ran_at_5 in ((False, [0, 1]), (True, [0, 1, 2, 3, 4])):
        plan = MinimalLinkerPlan(search=SearchPlan(max_linker=20, all_restarts=every),
                                 output=BatchOutput(quiet=True),
                                 executor=ExecutorPlan(executor="processes", workers=2))
        base = P.make_params(globule_diameter=30.0, linker=1)
        w = linker_map.new_walk(plan.search, base, 5)
        ex = answering(lambda p: p["linker"] >= 5 and p["seed"] >= 1)
        out = tmp_path / f"every{every}"
        out.mkdir()
        linker_map.step_walks({"protocol": "inflate"}, range(5), [w], out, plan, lambda: ex)
        assert w.minimal == 5 and w.tried[4] == (0, 5)
        assert sorted(s for L, s in ex.ran if L == 5) == ran_at_5
        assert sorted(s for L, s in ex.ran if L == 4) == [0, 1, 2, 3, 4]


@pytest.mark.parametrize("args, named", [
    (["run", "--interval-width", "0.3"], "--interval-width: only with --restarts"),
    (["run", "--restarts", "2", "--interval-width", "1.5"], "--interval-width: must be between"),
])
def test_interval_width_is_refused_in_one_line(args, named):
    proc = subprocess.run([PY, str(ROOT / "headless.py"), *args], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2 and proc.stderr.strip().count("\n") == 0
    assert named in proc.stderr


def test_the_restarts_line_says_how_many_ran_and_why_it_stopped():
    from fibrilfit.search import linker_map
    recs = [_record(0, False, 1), _record(1, True)]
    s = {**restarts.tally(recs), "stop_on_fit": True, "asked": 5,
         "decided": restarts.decided(recs, stop_on_fit=True)}
    line = linker_map.restarts_line(s)
    assert "1/2 accommodated" in line and "stopped after 2 of 5 runs: a fit found" in line
    s["decided"] = None
    assert "stopped" not in linker_map.restarts_line(s)


def test_a_resumed_walk_runs_nothing_again(tmp_path):
    """The walk stopped a length at its first fit; walked again over the same results it runs
    nothing (the length is decided by the recorded fit), and gives the same row."""
    from fibrilfit.api.plans import MinimalLinkerPlan
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.search import linker_map
    from fibrilfit.search.plans import BatchOutput, SearchPlan

    plan = MinimalLinkerPlan(search=SearchPlan(max_linker=20, all_restarts=False),
                             output=BatchOutput(quiet=True),
                             executor=ExecutorPlan(executor="processes", workers=1))
    base = P.make_params(globule_diameter=30.0, linker=1)
    rows = []
    for k in range(2):
        w = linker_map.new_walk(plan.search, base, 5)
        ex = answering(lambda p: p["linker"] >= 5 and p["seed"] != 1)
        linker_map.step_walks({"protocol": "inflate"}, range(5), [w], tmp_path, plan,
                              lambda: ex)
        rows.append(w.row())
        if k == 0:
            assert (5, 0) in ex.ran and (5, 1) not in ex.ran  # one worker: stopped at seed 0
        else:
            assert ex.ran == []
    assert rows[0] == rows[1] and rows[0]["minimal_linker"] == 5


def test_the_walk_takes_the_bound_from_a_run_of_its_geometry():
    """A run's record carries the bound it was judged under (pipeline: `bound`); the walk uses
    it rather than computing it again, and starts at it when the guess lies below."""
    from fibrilfit.search import linker_map
    from fibrilfit.search.plans import SearchPlan
    search = SearchPlan(max_linker=20, all_restarts=False)
    base = P.make_params(globule_diameter=30.0, linker=1)
    rec = {**_record(0, True), "bound": {"impossible_below": 7}}
    w = linker_map.new_walk(search, base, 5, records=[rec])
    assert w.floor == 7 and w.start == 7 and w.next_step() == (7, minimal.SCREEN)
    failed = {"params": {"seed": 1}, "status": "failed", "bound": {"impossible_below": 9}}
    assert linker_map.floor_of(base, [failed, rec]) == 7


def test_a_length_whose_model_cannot_start_is_a_miss_without_runs():
    # 5OQV + GFP: with the exit's 5 residues spent, linkers 6 and 7 leave the globule no straight
    # way out of the groove (param_checks refuses the model); the walk must go on, not stop
    from fibrilfit.search.minimal import Walk
    w = Walk(43.9, 8, 30, restarts=3, stop_at_fit=True)
    for _ in range(50):
        step = w.next_step()
        if step is None:
            break
        L = step[0]
        if L in (6, 7):
            w.unstarted[L] = "anchor: no straight direction"
            continue
        w.record(L, 1 if L >= 8 else 0, 1 if L >= 8 else 3)
    row = w.row()
    assert w.minimal == 8 and row["linker_below"] == 7
    assert row["below_unstarted"] == "anchor: no straight direction"
    # nothing ran one below: no P(fit) there (not 0/0 read as 0), no restarts, no interval
    assert row["p_fit_below"] is None and row["p_fit_below_interval"] is None
    assert row["restarts_below"] == 0 and row["unstarted"] == {"7": "anchor: no straight direction"}
    assert 7 not in w.tried  # nothing ran there


def test_a_decided_length_counts_its_seeds_up_to_the_first_fit_whatever_finished_first():
    """Seeds 0-3 at a length that stops at its first fit: seed 1 fits. Seed 2 was already
    running when the fit came, and finishing depends on the machine's speed; it is not
    counted, so P(fit) there is 1 of 2 either way."""
    from fibrilfit.search import restarts
    runs = [{"params": {"seed": s}, "accommodated": s == 1, "status": "ok"} for s in range(3)]
    assert restarts.up_to_first_fit(runs) == runs[:2]
    assert restarts.up_to_first_fit(runs[:2]) == runs[:2]
    misses = [dict(r, accommodated=False) for r in runs]
    assert restarts.up_to_first_fit(misses) == misses  # a miss needs every restart
