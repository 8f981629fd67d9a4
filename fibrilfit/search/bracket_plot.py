"""The report's bracket as a number line (docs/model/bound.md#bracket): impossible below B (the
proven bound), open between, fits at L (the minimal linker's layout), with P(fit) at each length
the search tried. `points` gathers the figure's numbers from the report's own (plain Python,
tested without Blender or matplotlib); `write` draws them with matplotlib's Agg canvas."""
from __future__ import annotations

from .. import files

PNG = "bracket.png"


def points(bracket: dict | None, tried: dict, asked: dict) -> dict | None:
    """The figure's numbers: `bracket` (report.bracket_of: impossible_below, fits_at, open),
    the walk's `tried` (linker -> {accommodated, restarts}) and the asked linker's P(fit)
    (`asked`: linker, fits, runs). Each length once, in order, with fits/runs and P(fit); at
    the asked linker its restarts, all of them (the walk may have stopped at the first fit
    there). None without a bound (nothing proven to draw against)."""
    if not bracket:
        return None
    runs = {int(L): (int(t["accommodated"]), int(t["restarts"])) for L, t in tried.items()}
    if asked.get("runs"):
        runs[int(asked["linker"])] = (int(asked["fits"]), int(asked["runs"]))
    lengths = [{"linker": L, "fits": k, "runs": n, "p_fit": round(k / n, 4)}
               for L, (k, n) in sorted(runs.items()) if n]
    return {"impossible_below": int(bracket["impossible_below"]),
            "fits_at": bracket.get("fits_at"), "open": bracket.get("open"),
            "asked": int(asked["linker"]), "lengths": lengths}


def write(path, data: dict, restarts: int, protocol: str):
    """bracket.png: the number line in residues, impossible below B shaded red, the open span
    grey, from the minimal linker on green; P(fit) at each length tried as a point, k/n beside
    it, the asked linker ringed."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    b, fit = data["impossible_below"], data["fits_at"]
    tried = [x["linker"] for x in data["lengths"]]
    top = max([b, data["asked"], *(tried or [b]), *([fit] if fit else [])]) + 2
    fig = Figure(figsize=(7.0, 3.4), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    if b > 1:
        ax.axvspan(0.5, b - 0.5, color="#d62728", alpha=0.18,
                   label=f"impossible below {b} (proof: the bound)")
    ax.axvspan(b - 0.5, (fit if fit else top) - 0.5, color="grey", alpha=0.15,
               label="open: neither proof reaches" if not fit or fit > b else None)
    if fit:
        ax.axvspan(fit - 0.5, top + 0.5, color="#2ca02c", alpha=0.18,
                   label=f"fits at {fit} (proof: a layout)")
    xs = [x["linker"] for x in data["lengths"]]
    ys = [x["p_fit"] for x in data["lengths"]]
    ax.plot(xs, ys, linestyle="none", marker="o", color="black", label="P(fit) at a length tried")
    for x in data["lengths"]:
        ax.annotate(f"{x['fits']}/{x['runs']}", (x["linker"], x["p_fit"]),
                    textcoords="offset points", xytext=(0, 7), ha="center", fontsize=7)
    asked = [x for x in data["lengths"] if x["linker"] == data["asked"]]
    if asked:
        ax.plot([data["asked"]], [asked[0]["p_fit"]], linestyle="none", marker="o",
                markersize=12, markerfacecolor="none", color="#1f77b4",
                label=f"the asked linker, {data['asked']}")
    ax.set_xlim(0.5, top + 0.5)
    ax.set_ylim(-0.08, 1.2)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("linker (residues)")
    ax.set_ylabel("P(fit)")
    ax.set_yticks([0, 0.5, 1])
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=3, frameon=False)
    fig.suptitle(f"FibrilFit: the bracket (up to {restarts} restarts a length, protocol "
                 f"{protocol})", fontsize=9)
    fig.tight_layout()
    files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
    return {"path": str(path)}
