"""The minimal-linker walk on a thread (search/background.py, the sidebar's Minimal linker…): the
same rows as the command's plan and walk, its progress counted, and a stop that ends it with
nothing kept. Executors answer from a table here; tests/blender/test_ui_minimal.py runs the real
workers."""
import threading
import time

import pytest

from fibrilfit.api.plans import MinimalLinkerPlan
from fibrilfit.batch.executors import ProcessExecutor, Stopped
from fibrilfit.plans import PlanError
from fibrilfit.search import linker_map
from fibrilfit.search.background import BackgroundWalk
from fibrilfit.search.plans import BatchOutput, SearchPlan

FITS_FROM = {8.0: 1, 20.0: 3}  # the shortest linker that fits, by diameter


class Table:
    """The executor interface with stop(), answering at once from FITS_FROM (seed 1 never fits)."""

    def __init__(self):
        self.queue, self.ran, self.exited = [], [], None
        self.stopped = threading.Event()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.exited = exc[0]

    def submit(self, job):
        self.queue.append(job)

    def pending(self):
        return len(self.queue)

    def stop(self):
        self.stopped.set()

    def wait(self):
        job = self.queue.pop(0)
        p = job["params"]
        self.ran.append((p["globule_diameter"], p["linker"], p["seed"]))
        fits = p["linker"] >= FITS_FROM[p["globule_diameter"]] and p["seed"] != 1
        return job, {"id": job["id"], "ok": True, "result": {
            "params": p, "status": "ok", "accommodated": fits, "verdict": "successful",
            "clashing_pairs": [], "max_overlap": 0.0, "max_bond_stretch": 0.0,
            "frames_simulated": 10}}


class Hanging(Table):
    """Runs that never end until stop(): then wait() raises Stopped, as ProcessExecutor's."""

    def wait(self):
        while not self.stopped.wait(0.01):
            pass
        raise Stopped("stopped")


VALUES = {"globule_diameter": "8,20", "protocol": "tutorial", "layers": "3", "seed": "4"}


def _plan(**search):
    return MinimalLinkerPlan(search=SearchPlan(**search),
                             output=BatchOutput(quiet=True, no_plot=True))


def _finished(walk, seconds=300.0):  # a hang guard, not a timing: the walk computes its bound
    end = time.monotonic() + seconds
    while not walk.finished:
        assert time.monotonic() < end, "the walk's thread did not end"
        time.sleep(0.01)


def test_the_background_walk_gives_the_commands_rows_and_counts_its_runs(tmp_path):
    plan = _plan(restarts=2, max_linker=6)
    ex = Table()
    walk = BackgroundWalk(plan, VALUES, ex).start()
    _finished(walk)
    assert walk.error is None and not walk.stopped and ex.exited is None
    got = walk.result

    values, seeds, walks = linker_map.walks_for(VALUES, plan)  # the command's own steps
    again = Table()
    linker_map.step_walks(values, seeds, walks, tmp_path, plan, lambda: again)
    assert got["rows"] == linker_map.minimal_rows(values, seeds, walks, force=plan.force)
    assert [r["minimal_linker"] for r in got["rows"]] == [1, 3]
    assert got["rows"][1]["tried"]["2"] == {"accommodated": 0, "restarts": 2}
    assert got["table"].splitlines()[0].startswith("minimal linker: the shortest length at "
                                                   "which at least one of 2 restarts (protocol "
                                                   "tutorial, seeds 4-5)")
    assert "20 Å: impossible below" in got["table"] and got["seeds"] == [4, 5]
    assert ex.ran == again.ran and walk.progress.done == walk.progress.submitted == len(ex.ran)


def test_a_stopped_walk_ends_with_nothing_but_stopped():
    plan = _plan(restarts=2, max_linker=6)
    ex = Hanging()
    walk = BackgroundWalk(plan, VALUES, ex).start()
    end = time.monotonic() + 300  # a hang guard (the bound comes first; slow on a loaded machine)
    while walk.progress.submitted == 0:  # a run is under way
        assert time.monotonic() < end
        time.sleep(0.01)
    assert not walk.finished
    walk.stop()
    _finished(walk, 60)
    assert walk.stopped and walk.result is None and walk.error is None
    assert ex.exited is Stopped  # the executor was left on the exception: its workers killed


def test_a_process_executors_wait_wakes_up_to_stop():
    ex = ProcessExecutor(1)
    caught = []

    def waiting():
        try:
            ex.wait()
        except Stopped as exc:
            caught.append(exc)
    t = threading.Thread(target=waiting)
    t.start()
    time.sleep(0.1)
    ex.stop()
    t.join(5)
    assert not t.is_alive() and len(caught) == 1
    with pytest.raises(Stopped):
        ex.submit({"id": 0})
    assert ex.workers == []  # nothing was started


def test_bad_options_are_refused_in_one_line():
    """A bad search option is refused when the plan is made, before any walk starts; a bad
    model value is the walk's error, in one line."""
    with pytest.raises(PlanError) as caught:
        _plan(restarts=0)
    assert str(caught.value) == "--restarts: must be at least 1 (got 0)"
    walk = BackgroundWalk(_plan(), {**VALUES, "linker": "8"}, Table()).start()
    _finished(walk)
    assert walk.result is None and str(walk.error) == (
        "--linker: minimal-linker searches the linker length; leave it out")
