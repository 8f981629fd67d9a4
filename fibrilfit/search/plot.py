"""minimal_linker.png: globule diameter against the minimal linker, one line per fibril kind.
matplotlib's Agg canvas (no pyplot, no display), written atomically."""
from __future__ import annotations

from .. import files

MARKERS = "os^Dv<>p"


def write(path, rows: list[dict]):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.5, 4.5), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    kinds: dict[str, list] = {}
    for r in rows:
        kinds.setdefault(r["kind"], []).append(r)
    for k, (kind, members) in enumerate(kinds.items()):
        members = sorted(members, key=lambda r: r["globule_diameter"])
        found = [r for r in members if r["minimal_linker"] is not None]
        (line,) = ax.plot([r["globule_diameter"] for r in found],
                          [r["minimal_linker"] for r in found],
                          marker=MARKERS[k % len(MARKERS)], label=kind)
        missing = [r for r in members if r["minimal_linker"] is None and r["linker_below"]]
        if missing:  # no fit up to the cap: an arrow up from the last length tried
            ax.plot([r["globule_diameter"] for r in missing],
                    [r["linker_below"] for r in missing], linestyle="none", marker="^",
                    markerfacecolor="none", color=line.get_color(),
                    label=f"{kind}: none up to this length")
    ax.set_xlabel("globule diameter (Å)")
    ax.set_ylabel("minimal linker (residues, counting the anchor)")
    ax.yaxis.get_major_locator().set_params(integer=True)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle("FibrilFit: shortest linker with an accommodated layout\n"
                 "(a fit: at least one restart passed the check; one residue less: none did)",
                 fontsize=9)
    fig.tight_layout()
    return files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
