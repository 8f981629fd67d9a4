"""--envelope-plot: where the domains went, seen down the fibril axis and as a radial density.

Drawn with matplotlib's Agg canvas (no pyplot, no display), written atomically. matplotlib is a
developer/sweep dependency that Blender does not ship: inside Blender the option is refused
with one line unless matplotlib was installed into Blender's Python.
"""
from __future__ import annotations

import importlib.util

import numpy as np

from .. import files
from ..analysis.envelope import radii
from ..exits import UsageError, missing_packages


def available(stop_after: str = "check") -> None:
    """Refuse the option before any work when it cannot be honoured."""
    if stop_after != "check":
        raise UsageError("--envelope-plot: needs the check (leave out --stop-after)")
    if importlib.util.find_spec("matplotlib") is None:
        raise UsageError(missing_packages(["matplotlib"], "--envelope-plot"))


def _scored_centres(result: dict) -> np.ndarray:
    centres = np.asarray(result["globule_centres"], dtype=float).reshape(-1, 3)
    lo, hi = result["scored_layers"]
    per_layer = max(1, len(centres) // result["params"]["layers"])  # chains per layer
    return centres[lo * per_layer:(hi + 1) * per_layer]


def core_shape(p: dict) -> tuple:
    """(outline (n, 2) or None, the core's reach from the axis in Å, its label): a structure
    model's own core outline and its farthest point, or the default slab's box and corner."""
    outline = p.get("core_outline")
    if outline:
        pts = np.asarray(outline, dtype=float).reshape(-1, 2)
        reach = float(np.hypot(pts[:, 0], pts[:, 1]).max())
        return pts, reach, f"core reach {reach:.1f} Å (outline's farthest point)"
    sx, sy = float(p["slab"][0]), float(p["slab"][1])
    box = np.array([(-sx, -sy), (sx, -sy), (sx, sy), (-sx, sy)]) / 2
    reach = float(np.hypot(sx, sy)) / 2
    return box, reach, f"core reach {reach:.1f} Å (slab corner)"


def draw(result: dict):
    """The figure: left, the centres seen down the axis; right, their radial density."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Polygon

    env, p = result["envelope"], result["params"]
    R = p["globule_diameter"] / 2
    c = _scored_centres(result)
    r = radii(c)
    fig = Figure(figsize=(10, 4.6), dpi=100)
    FigureCanvasAgg(fig)
    top, dens = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 1.3]})
    for x, y in c[:, :2]:
        top.add_patch(Circle((x, y), R, facecolor="0.75", edgecolor="0.35", alpha=0.35, lw=0.5))
    top.plot(c[:, 0], c[:, 1], ".", color="0.2", ms=3)
    outline, core, core_label = core_shape(p)
    if outline is not None:
        top.add_patch(Polygon(outline, closed=True, facecolor="lightsteelblue", alpha=0.5,
                              edgecolor="steelblue", lw=0.8, label="core outline (first layer)"))
    rings = [(core, "steelblue", core_label), (env["r95"], "darkorange", "r95"),
             (env["r95"] + R, "firebrick", "outer: r95 + R")]
    for radius, colour, label in rings:
        top.add_patch(Circle((0, 0), radius, fill=False, ls="--", color=colour, label=label))
    lim = 1.1 * (env["r95"] + R if r.size else core)
    lim = max(lim, 1.1 * (float(r.max()) + R)) if r.size else lim
    lim = max(lim, 1.1 * core)
    top.set(xlim=(-lim, lim), ylim=(-lim, lim), aspect="equal", xlabel="x (Å)", ylabel="y (Å)",
            title="domain centres, down the fibril axis")
    top.legend(loc="upper right", fontsize=7)

    width = max(1.0, (float(r.max()) if r.size else 1.0) / 40)
    bins = np.arange(0, (float(r.max()) if r.size else 1.0) + 2 * width, width)
    dens.hist(r, bins=bins, density=True, color="0.55", edgecolor="0.3")
    for x, colour, label in ((core, "steelblue", f"core reach {core:.1f} Å"),
                             (env["r_median"], "k", f"median {env['r_median']:.1f} Å"),
                             (env["r95"], "darkorange", f"r95 {env['r95']:.1f} Å"),
                             (env["r95"] + R, "firebrick",
                              f"r95 + R: outer diameter {env['outer_diameter']:.0f} Å")):
        dens.axvline(x, color=colour, ls="--", label=label)
    measured = (result.get("case") or {}).get("envelope_width")
    if measured:
        dens.axvline(measured / 2, color="seagreen", ls=":",
                     label=f"measured width {measured:.0f} Å (half)")
    dens.set(xlabel="distance of the domain centre from the fibril axis (Å)",
             ylabel="density (per Å)",
             title=f"{env['n']} scored domains, seed {result['seed']}")
    dens.legend(fontsize=7)
    name = (result.get("case") or {}).get("name")
    if name:
        fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    return fig


def write(result: dict, path) -> dict:
    fig = draw(result)
    files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
    return {"path": str(path)}
