"""The largest-fraction map (`largest-fraction`, the API's `largest_fraction`): for each domain
diameter and linker, the largest fraction of subunits that can carry the domain, searched with
restarts (search/fraction.py: the minimal-linker walk over the decorated count), bracketed by
the proven bound on the fraction (model/fraction_bound.py). The walks run on the plan's
executor through linker_map's step_walks; the output folder is resumable as minimal-linker's
(DIR/results.jsonl, --resume). docs/model/largest-fraction.md#largest-fraction.

A plan here is the API's LargestFractionPlan (api/plans.py): `.search` (SearchPlan),
`.output` (BatchOutput), `.executor` (ExecutorPlan) and `.force`.
"""
from __future__ import annotations

import json

from .. import exits, files
from ..model import fraction_bound, params as P
from ..model.searches import search_words
from ..model.version import fibrilfit_version
from ..sweep import grid
from . import fraction, linker_map, minimal
from .plans import seed_range
from .table import csv_lines

CSV, JSON, PNG = "largest_fraction.csv", "largest_fraction.json", "largest_fraction.png"
COLUMNS = ("kind", "globule_diameter", "linker", "subunits", "largest_count", "largest_fraction",
           "p_fit", "p_fit_low", "p_fit_high", "fraction_above", "p_fit_above",
           "p_fit_above_high", "restarts", "fraction_bound", "bracket", "protocol")
SEARCHED = ("occupancy",)  # what the command finds: refused when given


def walks_for(values: dict, plan) -> tuple:
    """The model options (protocol inflate unless given; the random pattern), the restarts'
    seeds and one walk per (diameter, linker), every bad value refused in one line before
    anything runs. Each walk's bound costs 3-16 s per geometry (cached across linkers)."""
    for name in SEARCHED:
        if name in values:
            raise exits.UsageError(f"--{name}: largest-fraction searches the fraction; leave "
                                   f"it out")
    if values.get("pattern", "random") != "random":
        raise exits.UsageError(f"--pattern: largest-fraction searches the random pattern's "
                               f"fraction (a nested draw); {values['pattern']} fixes its own")
    values = dict(values)
    diameters = grid.parse_spec("globule_diameter",
                                values.pop("globule_diameter", P.DEFAULTS.globule_diameter))
    linkers = grid.parse_spec("linker", values.pop("linker", P.DEFAULTS.linker))
    values.setdefault("protocol", "inflate")
    first = int(P.make_params(**values).seed)
    values.pop("seed", None)  # each restart's own: --seed is the first
    search = plan.search
    seeds = seed_range(first, search.restarts)
    walks = []
    for d in diameters:
        for L in linkers:
            base = P.make_params(force=plan.force, **values, globule_diameter=d, linker=int(L),
                                 seed=first)
            base.replace(seed=seeds[-1])
            n = subunits(base)
            if n > 1:  # a mixed model's own refusals (bare tails beside hulls), in one line
                base.replace(occupancy=(n - 1) / n)
            walks.append(new_walk(search, base, len(seeds)))
    return values, seeds, walks


def subunits(p: P.Params) -> int:
    """N: the model's own subunits, over which the random pattern draws (a periodic cell's
    M × K, a fibril's layers × K)."""
    return int(p.layers) * int(p.protofilaments)


def new_walk(search, base: P.Params, restarts: int) -> fraction.FractionWalk:
    """The walk at `base`'s diameter and linker, over the decorated count of its subunits,
    counts above the bound's settled (fraction_bound.fraction_limit: its `count`)."""
    limit = fraction_bound.fraction_limit(base, base.linker)
    return fraction.fraction_walk(base.globule_diameter, base.linker, subunits(base),
                                  limit["count"], limit["fraction_bound"], restarts=restarts,
                                  stop_at_fit=not search.all_restarts)


def fraction_map(values: dict, seeds: range, walks: list, plan, out) -> dict:
    """Every walk run on the executor; largest_fraction.json, .csv and .png written into `out`
    (outdir.out_dir's check of plan.output). Returns the document with `table` and `paths`
    beside it. Interrupted, the finished runs stay in DIR/results.jsonl (continue with
    --resume)."""
    with linker_map.walking(out):
        linker_map.run_walks(values, seeds, walks, plan, out)
        return _write(plan, values, seeds, fraction_rows(values, walks), out)


def fraction_rows(values: dict, walks: list) -> list:
    """The map's rows (largest_fraction.json's), one per walk, once the walks are done."""
    kind = linker_map.kind_of(dict(values))
    return [{"kind": kind, **w.row(), "protocol": values["protocol"]} for w in walks]


def _write(plan, values: dict, seeds: range, rows: list, out) -> dict:
    import bpy
    search = plan.search
    document = {
        "fibrilfit_version": fibrilfit_version(), "blender_version": bpy.app.version_string,
        "method": ("the minimal-linker walk over the decorated count k of the model's N "
                   "subunits (random pattern, nested draws: more decorations never fit "
                   "better): from halfway to the bound's count in doubling steps until a fit "
                   "and a miss bracket the largest count, then bisection; counts on the way "
                   f"screened with {min(minimal.SCREEN, search.restarts)} restarts; ends at a fit "
                   "at k and R missed restarts at k + 1"
                   + (", all R at both" if search.all_restarts else
                      " (a count's restarts stop at its first fit)")
                   + "; counts above the proven bound on the fraction settled without runs "
                     "(search/fraction.py, docs/model/largest-fraction.md#largest-fraction)"),
        "model": {**values, "seeds": list(seeds)}, "protocol": values["protocol"],
        "restarts": search.restarts, "rows": rows,
    }
    files.write_json(out / JSON, document)
    files.write_text(out / CSV, csv_text(rows))
    paths = {"csv": out / CSV, "json": out / JSON, "results": out / linker_map.RESULTS}
    if not plan.output.no_plot:
        write_plot(out / PNG, rows)
        paths["png"] = out / PNG
    return {**document, "table": "\n".join([table(rows, values["protocol"], search.restarts,
                                                  seeds), *linker_map.free_end_lines(values)]),
            "paths": {k: str(v) for k, v in paths.items()}}


def csv_text(rows: list[dict]) -> str:
    """largest_fraction.csv: one line per (diameter, linker) (COLUMNS)."""
    def cells(r):
        lo, hi = r["p_fit_interval"] or (None, None)
        above_hi = (r["p_fit_above_interval"] or (None, None))[1]
        return (r["kind"], r["globule_diameter"], r["linker"], r["subunits"],
                r["largest_count"], r["largest_fraction"], r["p_fit"], lo, hi,
                r["fraction_above"], r["p_fit_above"], above_hi, r["restarts"],
                r["fraction_bound"], r["bracket"], r.get("protocol"))
    return csv_lines(COLUMNS, (cells(r) for r in rows))


def table(rows: list[dict], protocol: str | None = None, restarts: int | None = None,
          seeds=None) -> str:
    """The printed map, one line per (diameter, linker), then each row's bracket."""
    lines = []
    if protocol is not None:
        lines.append(f"largest fraction: the most decorated subunits (of the model's N, random "
                     f"nested pattern) at which at least one of {restarts} restarts (protocol "
                     f"{protocol}, seeds {seeds[0]}-{seeds[-1]}) found a layout, with none found "
                     f"at one more; the search: {search_words(protocol)}")
    lines.append("diameter (Å)  linker  largest k/N (fraction)  P(fit) (runs)   one more")
    notes = []
    for r in rows:
        k, n = r["largest_count"], r["subunits"]
        shown = f"{k}/{n} ({r['largest_fraction']:.3f})" if k is not None else "none"
        fit = f"{r['p_fit']:.2f} ({r['fits']}/{r['restarts']})" if k is not None else "-"
        lines.append(f"{r['globule_diameter']:>12g}  {r['linker']:>6}  {shown:>22}  "
                     f"{fit:<14}  {one_more(r)}")
        notes.append(f"{r['globule_diameter']:g} Å, linker {r['linker']}: {r['bracket']}")
        if r.get("error"):
            notes.append(f"{r['globule_diameter']:g} Å, linker {r['linker']}: {r['error']}")
    return "\n".join(lines + notes)


def one_more(r: dict) -> str:
    """A row's "one more" cell: the count above the largest found, and why it does not fit
    (excluded by the bound, its misses) or that it was not started; "-" when there is none
    to say. The printed map's and the docs' table's (tools/fraction_map.py)."""
    n = r["subunits"]
    if r["count_above"] is None:
        return "- (every subunit)"
    if r["above_settled_by_bound"]:
        return f"{r['count_above']}/{n}: excluded by the bound (not run)"
    if r.get("above_unstarted"):
        return f"{r['count_above']}/{n}: not started ({r['above_unstarted']})"
    if r["p_fit_above"] is not None:
        return f"{r['count_above']}/{n}: 0/{r['restarts_above']}"
    return "-"


def folder_rows(out) -> list[dict]:
    """Every row of the largest_fraction.json in each folder under `out` (one map run each),
    by diameter and linker."""
    rows = [r for path in sorted(out.glob("*/" + JSON))
            for r in json.loads(path.read_text(encoding="utf-8"))["rows"]]
    return sorted(rows, key=lambda r: (r["globule_diameter"], r["linker"]))


def write_plot(path, rows: list[dict]):
    """largest_fraction.png: the largest fraction found (filled) and the bound (open) against
    the linker, one line per diameter. matplotlib's Agg canvas, written atomically."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6.5, 4.5), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    by: dict = {}
    for r in rows:
        by.setdefault((r["kind"], r["globule_diameter"]), []).append(r)
    for i, ((kind, d), members) in enumerate(sorted(by.items(), key=lambda i: i[0][1])):
        members = sorted(members, key=lambda r: r["linker"])
        (line,) = ax.plot([r["linker"] for r in members],
                          [r["largest_fraction"] or 0.0 for r in members],
                          marker="os^Dv<>p"[i % 8], label=f"{d:g} Å: found")
        ax.plot([r["linker"] for r in members], [r["fraction_bound"] for r in members],
                linestyle="--", marker="o", markerfacecolor="none", color=line.get_color(),
                label=f"{d:g} Å: bound")
    ax.set_xlabel("linker (residues, counting the anchor)")
    ax.set_ylabel("fraction of subunits decorated")
    ax.set_ylim(0, 1.05)
    ax.xaxis.get_major_locator().set_params(integer=True)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle("FibrilFit: largest fraction with an accommodated layout (filled) and the "
                 "proven bound (open)\n(impossible above the bound; open between)", fontsize=9)
    fig.tight_layout()
    return files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
