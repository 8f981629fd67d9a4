"""The ensemble's picture for the report (docs/model/ensemble.md#use): the helically averaged
map projected perpendicular to the axis (a negative-stain-like image over one helical turn,
the width's edges marked), the projection's profile across the axis with the width read from
it, and the radial density of domain mass with its peak. matplotlib's Agg canvas, written
atomically; matplotlib missing: the report says the picture was not drawn."""
from __future__ import annotations

import numpy as np

from .. import files
from ..ensemble import density
from . import ensemble_words


def draw(block: dict, dmap):
    """Three panels: the projection (the width's edges marked), its profile across the axis
    (the level at WIDTH_FRACTION of its peak, the width between the crossings), and the radial
    density of domain mass (its peak, the outer radius's 95 % interval)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(12, 4.2), dpi=100)
    FigureCanvasAgg(fig)
    left, middle, right = (fig.add_subplot(1, 3, k) for k in (1, 2, 3))
    image = density.projection(dmap)
    x0, z0, v = dmap.origin[0], dmap.origin[2], dmap.voxel
    left.imshow(image.T, origin="lower", cmap="gray_r", aspect="auto",
                extent=(z0, z0 + image.shape[0] * v, x0, x0 + image.shape[1] * v))
    w = block["width"]
    edges = density.width_edges(dmap, w["fraction_of_peak"])
    for y in edges:
        left.axhline(y, color="tab:red", lw=0.8, ls="--")
    left.set_xlabel("fibril axis z (Å)")
    left.set_ylabel("x (Å)")
    left.set_title(f"projection, one helical turn; width {w['value']:.0f} Å", fontsize=9)
    x, prof = density.profile(dmap)
    level = w["fraction_of_peak"] * float(prof.max())
    middle.plot(x, prof, color="black", lw=1)
    middle.axhline(level, color="tab:red", lw=0.8, ls=":",
                   label=f"{100 * w['fraction_of_peak']:.0f} % of the peak")
    middle.annotate("", xy=(edges[1], level), xytext=(edges[0], level),
                    arrowprops={"arrowstyle": "<->", "color": "tab:red", "lw": 1.2})
    for e in edges:
        middle.axvline(e, color="tab:red", lw=0.8, ls="--")
    middle.set_xlabel("x across the axis (Å)")
    middle.set_ylabel("projected thickness (Å), mean along the axis")
    middle.set_ylim(bottom=0)
    middle.legend(frameon=False, fontsize=8)
    middle.set_title(f"the projection's profile: width {w['value']:.0f} Å", fontsize=9)
    rd = block["radial_density"]
    right.plot(rd["r"], rd["mass_density_da_per_a3"], color="tab:blue")
    od = block["outer_diameter"]
    lo, hi = (x / 2.0 for x in od["interval_95"])
    right.axvspan(lo, hi, color="tab:orange", alpha=0.25,
                  label=f"outer radius, 95 % of layouts ({lo:.0f}–{hi:.0f} Å)")
    r_peak, _ = ensemble_words.radial_peak(block)
    right.axvline(r_peak, color="tab:blue", lw=0.8, ls="--", label=f"peak at {r_peak:.0f} Å")
    right.set_xlabel("distance from the fibril axis (Å)")
    right.set_ylabel("domain mass (Da/Å³)")
    right.set_ylim(bottom=0)
    right.legend(frameon=False, fontsize=8)
    right.set_title(f"radial density ({block['replicas']} replicas × {block['sweeps']} sweeps)",
                    fontsize=9)
    fig.tight_layout()
    return fig


def write(block: dict, dmap, path) -> dict:
    fig = draw(block, dmap)
    files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
    return {"path": str(path), "peak_projection": round(float(np.max(density.projection(dmap))),
                                                        2)}
