"""The report's P(fit) against the fraction of subunits carrying the domain (issue #44 item 5;
docs/guide/report.md#fraction-plot), asked with --fraction-plot F1,F2,...: the report's model
at each fraction (pattern random: each restart draws its own subunits with its seed), at the
report's linker, with the report's seeds and restarts; P(fit) at each with its 95 % Wilson
interval (search/restarts.py's tally, as everywhere), a table of the same numbers on the page,
and fraction_plot.png. The runs are report.py's (on its workers, into its results.jsonl: a
fraction that is the report's own reuses its restarts); this room says which models, what a
row holds, and draws the plot. Plain Python and matplotlib's Agg canvas: no bpy.
"""
from __future__ import annotations

from .. import files
from ..model import occupancy, params as P
from ..plans import PlanError
from . import restarts

PNG = "fraction_plot.png"


def models(p: P.Params, fractions) -> list[P.Params]:
    """The report's model at each fraction (the linker, seed and the rest its own), each
    checked; refused in one line, naming --fraction-plot: another pattern than random (its
    fraction is fixed), a fraction the model cannot draw, or two fractions that decorate the
    same count of its N subunits (they would be one model)."""
    if not fractions:
        return []
    if p.pattern != "random":
        raise PlanError("fraction_plot", f"needs pattern random (the {p.pattern} pattern fixes "
                                         f"the fraction)")
    out, counts = [], {}
    for f in fractions:
        try:
            q = p.replace(occupancy=f)
        except P.ParamError as exc:
            raise PlanError("fraction_plot", f"at {f:g}: {exc}") from None
        k = occupancy.decorated_count(f, q.chains)
        if k in counts:
            raise PlanError("fraction_plot", f"{counts[k]:g} and {f:g} both decorate {k} of the "
                                             f"{q.chains} subunits: give fractions at least "
                                             f"1/{q.chains} apart")
        counts[k] = f
        out.append(q)
    return out


def row(q: P.Params, records: list[dict], seeds: range, report_fraction: float) -> dict:
    """One fraction's row: asked, as drawn (k of N), P(fit) over its restarts with its 95 %
    Wilson interval, and whether it is the report's own model."""
    t = restarts.tally(records)
    k = occupancy.decorated_count(q.occupancy, q.chains)
    return {"fraction_asked": q.occupancy, "decorated": k, "subunits": q.chains,
            "fraction": round(k / q.chains, 6), "fits": t["accommodated"],
            "restarts": t["restarts"], "failed": t["failed"], "p_fit": t["p_fit"],
            "interval": t["p_fit_interval"], "seeds": [seeds[0], seeds[-1]],
            "best_seed": t["best_seed"], "report_fraction": q.occupancy == report_fraction}


def block(rows: list[dict], p: P.Params, restarts_asked: int) -> dict:
    """report.json's "fraction_plot": the rows by fraction, and what they were run with."""
    return {"linker": p.linker, "protocol": p.protocol, "restarts": restarts_asked,
            "interval": "95 % Wilson", "pattern": "random",
            "rows": sorted(rows, key=lambda r: r["fraction"])}


def write(path, plot: dict, fraction_bound: float | None = None):
    """fraction_plot.png: P(fit) against the fraction at the report's linker, each point with
    its 95 % Wilson interval as an error bar, the report's own fraction marked; `fraction_bound`
    f_B at that linker, when known, as the line above which no layout exists (a proof)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rows = plot["rows"]
    fig = Figure(figsize=(6.5, 4.5), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    xs = [r["fraction"] for r in rows if r["restarts"]]
    ys = [r["p_fit"] for r in rows if r["restarts"]]
    low = [r["p_fit"] - r["interval"][0] for r in rows if r["restarts"]]
    high = [r["interval"][1] - r["p_fit"] for r in rows if r["restarts"]]
    ax.errorbar(xs, ys, yerr=[low, high], marker="o", capsize=4, label="P(fit), 95 % Wilson")
    own = [r for r in rows if r["report_fraction"] and r["restarts"]]
    if own:
        ax.plot([r["fraction"] for r in own], [r["p_fit"] for r in own], linestyle="none",
                marker="o", markersize=11, markerfacecolor="none", color="black",
                label="the report's fraction")
    if fraction_bound is not None and fraction_bound < 1:
        ax.axvline(fraction_bound, color="grey", linestyle="--", linewidth=1,
                   label=f"impossible above f_B = {fraction_bound:.3g} (proven bound)")
    for r in rows:
        ax.annotate(f"{r['fits']}/{r['restarts']}", (r["fraction"], r["p_fit"] or 0.0),
                    textcoords="offset points", xytext=(6, 6), fontsize=7)
    ax.set_xlim(0, 1.02)
    ax.set_ylim(-0.04, 1.04)
    ax.set_xlabel("fraction of subunits carrying the domain (as drawn: k of N)")
    ax.set_ylabel("P(fit): accommodated restarts")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(f"FibrilFit: P(fit) against the fraction at linker {plot['linker']} "
                 f"({plot['restarts']} restarts each, protocol {plot['protocol']})", fontsize=9)
    fig.tight_layout()
    files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
    return {"path": str(path)}
