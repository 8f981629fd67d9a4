"""Issue #44 item 3: the largest fraction at a linker (search/fraction.py: the minimal-linker walk
over the decorated count), its map's steps, resumption, the bound's settled side, and the
minimal linker at a fraction taking the bound at that fraction. A stubbed judge, no Blender."""
import subprocess
import sys

import pytest

from fibrilfit.model import params as P
from fibrilfit.search import fraction, minimal
from helpers import ROOT, bench_module

PY = sys.executable


def _walk(w, largest, luck=lambda k, seed: True):
    """Drive a fraction walk as the map does, with a monotone judge: a seed fits at k decorated
    when k <= largest (and its luck says so); seeds run in order. Returns the (count, restarts)
    asked."""
    asked = []
    while (step := w.next_step()) is not None:
        x, n = step
        k = w.decorated(x)
        assert len(asked) < 80 and 1 <= k <= w.subunits
        asked.append((k, n))
        fits = [k <= largest and luck(k, s) for s in range(n)]
        if w.stop_at_fit and any(fits):
            n = fits.index(True) + 1  # seeds start in order; the first fit decides
        w.record(x, sum(fits[:n]), n)
    return asked


@pytest.mark.parametrize("n", [1, 2, 12, 30])
@pytest.mark.parametrize("largest_frac", [0.0, 0.25, 0.66, 1.0])
@pytest.mark.parametrize("stop", [True, False])
def test_the_walk_brackets_the_largest_count_with_a_miss_at_one_more(n, largest_frac, stop):
    largest = int(largest_frac * n)
    w = fraction.fraction_walk(20.0, 3, n, bound_count=n, fraction_bound=1.0, restarts=3,
                               stop_at_fit=stop)
    asked = _walk(w, largest)
    row = w.row()
    if largest == 0:  # not even one decorated subunit fits: k = 1 missed with every restart
        assert row["largest_count"] is None and row["largest_fraction"] is None
        assert row["count_above"] == 1 and w.tried[w.step_of(1)] == (0, 3)
        assert "no layout found" in row["bracket"]
        return
    assert row["largest_count"] == largest
    assert row["largest_fraction"] == pytest.approx(largest / n, abs=1e-6)
    assert row["fits"] >= 1
    if largest == n:  # every subunit: nothing above it to miss
        assert row["count_above"] is None
    else:  # one more decorated: every restart missed
        assert row["count_above"] == largest + 1 and row["p_fit_above"] == 0.0
        assert row["restarts_above"] == 3 and not row["above_settled_by_bound"]
        assert row["tried"][str(largest + 1)]["accommodated"] == 0
    # only the answer's two counts cost all three restarts; the rest were screened
    assert all(r in (minimal.SCREEN, 3) or (stop and r >= 1) for _, r in asked)
    assert len(asked) <= 2 * n.bit_length() + 4


def test_counts_above_the_bound_are_settled_never_run():
    """The bound allows 5 of 12: a judge that would fit at 9 is never asked above 5, and the
    answer is 5 with one more excluded by proof; the bracket is closed."""
    w = fraction.fraction_walk(30.0, 2, 12, bound_count=5, fraction_bound=5 / 12, restarts=3)
    asked = _walk(w, largest=9)
    assert max(k for k, _ in asked) == 5
    row = w.row()
    assert row["largest_count"] == 5 and row["count_above"] == 6
    assert row["above_settled_by_bound"] and row["p_fit_above"] == 0.0
    assert row["bound_count"] == 5 and "closed" in row["bracket"]


def test_a_bound_that_allows_nothing_runs_nothing():
    w = fraction.fraction_walk(50.0, 1, 30, bound_count=0, fraction_bound=0.0, restarts=3)
    assert w.next_step() is None
    row = w.row()
    assert row["largest_count"] is None and row["count_above"] == 1
    assert row["above_settled_by_bound"] and row["tried"] == {}


def test_a_screened_miss_that_fits_with_every_restart_moves_the_walk_up():
    """Count 7 of 12 fits only with seed 2 (a screen of 2 misses it): completing 7 finds it,
    and the answer is 7, not 6."""
    w = fraction.fraction_walk(20.0, 3, 12, bound_count=12, fraction_bound=1.0, restarts=3)
    _walk(w, largest=7, luck=lambda k, seed: k < 7 or seed == 2)
    assert w.row()["largest_count"] == 7 and w.tried[w.step_of(8)] == (0, 3)


def test_the_steps_model_values_round_back_to_the_count():
    from fibrilfit.model import occupancy
    p = P.make_params(globule_diameter=20.0, linker=3, layers=7, protofilaments=2)
    w = fraction.fraction_walk(20.0, 3, 14, bound_count=14, fraction_bound=1.0, restarts=2)
    for k in range(1, 15):
        at = w.at(w.step_of(k))
        q = p.replace(occupancy=at["occupancy"])
        assert occupancy.decorated(q).sum() == k and at["linker"] == 3


def _judge(n, largest):
    """An executor answering from a table, no Blender (bench/walk_replay.py's Answering): a run
    fits when at most `largest` of the N subunits are decorated (the fraction of its params);
    `ran` lists (decorated count, seed)."""
    def answer(p):
        fits = round(p["occupancy"] * n) <= largest
        return {"status": "ok", "accommodated": fits,
                "verdict": "successful" if fits else "intersection", "clashing_pairs": [],
                "max_overlap": 0.0, "max_bond_stretch": 0.0, "frames_simulated": 10}
    return bench_module("walk_replay").Answering(
        answer, noted=lambda p, r: (round(p["occupancy"] * n), p["seed"]))


def test_the_map_steps_on_an_executor_and_a_resumed_walk_runs_nothing_again(tmp_path):
    from fibrilfit.api.plans import LargestFractionPlan
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.search import linker_map
    from fibrilfit.search.plans import BatchOutput, SearchPlan
    plan = LargestFractionPlan(search=SearchPlan(restarts=3), output=BatchOutput(quiet=True),
                               executor=ExecutorPlan(executor="processes", workers=1))
    values = {"protocol": "inflate", "layers": 10}
    rows = []
    for attempt in range(2):
        w = fraction.fraction_walk(30.0, 2, 10, bound_count=10, fraction_bound=1.0, restarts=3)
        ex = _judge(10, largest=6)
        linker_map.step_walks(values, range(3), [w], tmp_path, plan, lambda: ex)
        rows.append(w.row())
        if attempt == 0:
            assert sorted(s for k, s in ex.ran if k == 7) == [0, 1, 2]  # one more: every seed
            assert sorted(s for k, s in ex.ran if k == 6) == [0]  # stopped at its first fit
        else:
            assert ex.ran == []  # every step read back from results.jsonl
    assert rows[0] == rows[1] and rows[0]["largest_count"] == 6


def test_minimal_linker_at_a_fraction_takes_the_bound_at_that_fraction(monkeypatch):
    """A mixed fibril's floor is impossible_below_at(p, its drawn fraction), never the bound a
    run records (the fully decorated fibril's, which would settle linkers that may fit)."""
    from fibrilfit.model import fraction_bound, occupancy
    from fibrilfit.search import linker_map
    asked = []

    def at(p, f, *a, **k):
        asked.append(f)
        return 3

    monkeypatch.setattr(fraction_bound, "impossible_below_at", at)
    mixed = P.make_params(globule_diameter=30.0, linker=1, layers=10, occupancy=0.3)
    recorded = {"status": "ok", "bound": {"impossible_below": 7}}  # f = 1's
    assert linker_map.floor_of(mixed, [recorded]) == 3
    assert asked == [pytest.approx(occupancy.fraction(mixed))] and asked[0] == 0.3
    full = mixed.replace(occupancy=1.0)
    assert linker_map.floor_of(full, [recorded]) == 7  # f = 1: the recorded bound, as before


def test_the_fraction_floor_is_never_above_the_full_bound_on_a_real_geometry():
    """On the infinite fibril of 30 Å balls (one protofilament), where the bound at f = 1 rules
    out short linkers: a fraction's floor lies at or below it, and a small fraction's below."""
    from fibrilfit.model import bound
    from fibrilfit.search import linker_map
    base = P.make_params(globule_diameter=30.0, linker=1, periodic=18, protocol="inflate")
    full = bound.linker_bound(base)["impossible_below"]
    floors = [linker_map.floor_of(base.replace(occupancy=f)) for f in (1 / 18, 0.5, 1.0)]
    assert floors[-1] == full
    assert floors == sorted(floors) and floors[0] <= floors[1] <= full


@pytest.mark.parametrize("args, named", [
    (["--occupancy", "0.5"], "--occupancy: largest-fraction searches the fraction"),
    (["--pattern", "periodic"], "--pattern: largest-fraction searches the random pattern"),
    (["--restarts", "0"], "--restarts: must be at least 1"),
    (["--linker", "0"], "linker"),
    (["--known-fit", "3"], "unrecognized arguments: --known-fit"),
    # refused for a mixed model only: said before anything runs, not met as a count unstarted
    (["--domain", str(ROOT / "tests/data/1ubq.pdb.gz"), "--domain-shape", "hull",
      "--bare-tail", "5"], "bare_tail: is judged against sphere domains only"),
])
def test_largest_fraction_refuses_bad_input_in_one_line(tmp_path, args, named):
    proc = subprocess.run([PY, str(ROOT / "headless.py"), "largest-fraction", *args, "--out",
                           str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.strip().count("\n") == 0 and named in proc.stderr
    assert "Traceback" not in proc.stderr and not (tmp_path / "out").exists()


def test_a_results_bound_is_the_bound_at_its_fraction_with_the_bracket_on_the_fraction():
    """The run's `bound` block (pipeline.check): unchanged at f = 1; a mixed fibril's states the
    bound at its fraction (never the fully decorated one's), f_B at its linker and the bracket
    on the fraction, which the printed result and the report carry."""
    from fibrilfit.exports import run_text
    from fibrilfit.model import bound, bracket, fraction_bound
    from fibrilfit.search import report
    base = P.make_params(globule_diameter=30.0, linker=2, periodic=18, protocol="inflate")
    assert bracket.bound_block(base, True) == bound.bound_block(base)
    mixed = base.replace(occupancy=0.5)
    b = bracket.bound_block(mixed, True)
    assert b["impossible_below"] == fraction_bound.impossible_below_at(mixed, 0.5)
    assert b["impossible_below"] <= b["impossible_below_full"] == \
        bound.bound_block(base)["impossible_below"]
    assert b["fraction_bound"] == fraction_bound.fraction_bound(mixed, 2)
    assert b["fraction_bracket"] == fraction_bound.fraction_bracket(b["fraction_bound"], 0.5)
    assert "no layout found" in bracket.bound_block(mixed, False)["fraction_bracket"]
    lines = run_text._bound_lines({"bound": b})
    assert lines[0].startswith("bound at 50 % decorated:")
    assert lines[-1] == f"bound on the fraction at linker 2: {b['fraction_bracket']}"
    got = report.fraction_bracket_of(b, {"accommodated": 0})
    assert got["fits_at"] is None and got["text"] == bracket.bound_block(mixed, False)[
        "fraction_bracket"]
    assert report.fraction_bracket_of(bound.bound_block(base), {"accommodated": 1}) is None
