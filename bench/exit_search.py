"""The exit search and the linker bound of the deposited survey, old code against new, side by
side on the same calls: every `shortest_exit` that `fibril.measure` (C and N) and each
protofilament's own terminus (structure/termini.own_termini) make on the given files, and
`linker_bound` for a 44 Å ball at each terminus the survey builds. The old code is read from
git (geom/exit_path.py and geom/polygons.py at --old); each call is timed old and new in turn,
--repeat times, and its median kept. Every result must be identical (found, length, depth,
every point of the path; the bound's whole result), or the bench says which differ.

    PYTHONPATH=. .venv/bin/python bench/exit_search.py [FILES ...] [--old cbf562c] [--repeat 3]
        [--survey]

--survey times instead the survey's whole row for each file (`survey_file` of tools/deposited_survey.py:
inspect, run's checks at C and N, the bound), once with the old geom modules in every module
that uses them and each file's own termini measured twice (as before), once as today; the rows
must be the same but for their seconds.

Numbers in docs/guide/structures.md#survey-speed. The machine is shared and noisy: compare the
medians' ratio, measured in turn on the same calls, not the absolute seconds.
"""
from __future__ import annotations

import argparse
import importlib.util
import pathlib
import statistics
import subprocess
import sys
import time
import types

from fibrilfit.geom import exit_path as NEW
from fibrilfit.model import bound as B
from fibrilfit.structure import fibril as F, termini

ROOT = pathlib.Path(__file__).resolve().parents[1]
_SPEC = importlib.util.spec_from_file_location("deposited_survey",
                                               ROOT / "tools" / "deposited_survey.py")
S = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(S)

FILES = [ROOT / "tests" / "data" / "5oqv_ae.pdb.gz", ROOT / "tests" / "data" / "5oqv_addedH.pdb.gz"]


def old_modules(commit: str):
    """geom/polygons.py and geom/exit_path.py as they were at `commit`, loaded beside the new."""
    mods = {}
    for name in ("polygons", "exit_path"):
        src = subprocess.run(["git", "-C", str(ROOT), "show", f"{commit}:fibrilfit/geom/{name}.py"],
                             capture_output=True, text=True, check=True).stdout
        spec = importlib.util.spec_from_loader(f"fibrilfit.geom.old_{name}", loader=None)
        mod = importlib.util.module_from_spec(spec)
        mod.__package__ = "fibrilfit.geom"
        sys.modules[spec.name] = mod
        if name == "exit_path":
            src = src.replace("from . import polygons", "from . import old_polygons as polygons")
        exec(compile(src, f"{commit}:{name}.py", "exec"), mod.__dict__)
        mods[name] = mod
    if not hasattr(mods["polygons"], "inside_by"):  # the bound's old test, as it was written
        old = mods["polygons"]
        mods["polygons"] = types.SimpleNamespace(**{
            k: getattr(old, k) for k in dir(old) if not k.startswith("__")},
            inside_by=lambda p, q, m: old.even_odd(p, q) & (old.edge_distance(p, q)[0] >= m))
    return mods


def same_path(a, b) -> bool:
    return (a.found == b.found and a.length == b.length and a.depth == b.depth
            and a.points.shape == b.points.shape and bool((a.points == b.points).all()))


def timed(f, *a, **k):
    t = time.perf_counter()
    out = f(*a, **k)
    return out, time.perf_counter() - t


def swapped(pairs):
    """Point every fibrilfit module's name for a module in `pairs` (new -> old) at the old."""
    undo = []
    for mod in list(sys.modules.values()):
        if getattr(mod, "__name__", "").startswith("fibrilfit") and "old_" not in mod.__name__:
            for k, v in list(vars(mod).items()):
                if any(v is new for new in pairs):
                    undo.append((mod, k, v))
                    setattr(mod, k, pairs[next(n for n in pairs if n is v)])
    return undo


def survey_rows(files, old) -> None:
    """Each file's survey row, old code then new, timed once each."""
    import pathlib as pl
    pairs = {NEW: old["exit_path"], NEW.polygons: old["polygons"]}
    for f in files:
        F.measure.cache_clear()
        undo = swapped(pairs)
        termini.own_termini = S._OWN_TERMINI  # measured twice, as before
        o, t_old = timed(S.survey_file, pl.Path(f))
        for mod, k, v in undo:
            setattr(mod, k, v)
        termini.own_termini = S.own_termini_once
        F.measure.cache_clear()
        n, t_new = timed(S.survey_file, pl.Path(f))
        same = {k: v for k, v in o.items() if k != "seconds"} == \
            {k: v for k, v in n.items() if k != "seconds"}
        print(f"survey row of {f.name}: old {t_old:.1f} s, new {t_new:.1f} s "
              f"({t_old / t_new:.1f}x); the same row: {same}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="*", type=pathlib.Path, default=FILES)
    ap.add_argument("--old", default="cbf562c", help="the commit whose code is the old")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--survey", action="store_true", help="time each file's survey row instead")
    a = ap.parse_args()
    old = old_modules(a.old)
    if a.survey:
        import functools
        F.measure = functools.lru_cache(maxsize=4)(F.measure)  # as the survey does, both arms
        survey_rows(a.files, old)
        return
    calls, real = [], NEW.shortest_exit

    def record(*args, **kw):
        calls.append((args, kw))
        return real(*args, **kw)
    NEW.shortest_exit = record
    for f in a.files:  # the calls the survey makes (measured once, by the new code)
        for side in ("C", "N"):
            g = F.measure(str(f), terminus=side)
            if g.protofilaments > 1:
                termini.own_termini(str(f), g)
    NEW.shortest_exit = real
    t_old, t_new, differ = [], [], 0
    for args, kw in calls:
        o_t, n_t = [], []
        for _ in range(a.repeat):
            o, dt = timed(old["exit_path"].shortest_exit, *args, **kw)
            o_t.append(dt)
            n, dt = timed(real, *args, **kw)
            n_t.append(dt)
        differ += not same_path(o, n)
        t_old.append(statistics.median(o_t))
        t_new.append(statistics.median(n_t))
    sealed = sum(not real(*c[0], **c[1]).found for c in calls)
    print(f"exit searches: {len(calls)} ({sealed} sealed) from {', '.join(f.name for f in a.files)}; "
          f"identical: {len(calls) - differ} of {len(calls)}")
    print(f"  per search, median of medians: old {statistics.median(t_old):.3f} s, new "
          f"{statistics.median(t_new):.3f} s; all searches: old {sum(t_old):.1f} s, new "
          f"{sum(t_new):.1f} s ({sum(t_old) / sum(t_new):.1f}x)")
    b_old, b_new, b_differ, n = [], [], 0, 0
    for f in a.files:
        for side in ("C", "N"):
            p = S.run_check(str(f), side)["p"]
            if p is None:
                continue
            n += 1
            o_t, n_t = [], []
            for _ in range(a.repeat):
                B.polygons = old["polygons"]
                B._CACHE.clear()
                o, dt = timed(B.linker_bound, p)
                o_t.append(dt)
                B.polygons = NEW.polygons
                B._CACHE.clear()
                new, dt = timed(B.linker_bound, p)
                n_t.append(dt)
            b_differ += repr(o) != repr(new)
            b_old.append(statistics.median(o_t))
            b_new.append(statistics.median(n_t))
    if n:
        print(f"linker bounds: {n}; identical: {n - b_differ} of {n}; per bound, median: old "
              f"{statistics.median(b_old):.2f} s, new {statistics.median(b_new):.2f} s "
              f"({sum(b_old) / sum(b_new):.1f}x)")


if __name__ == "__main__":
    main()
