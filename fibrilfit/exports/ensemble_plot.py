"""The ensemble's picture for the report (docs/model/ensemble.md#use): the helically averaged
map projected perpendicular to the axis (a negative-stain-like image over one helical turn,
the width marked), and the radial density of domain mass. matplotlib's Agg canvas, written
atomically; matplotlib missing: the report says the picture was not drawn."""
from __future__ import annotations

import numpy as np

from .. import files
from ..ensemble import density


def draw(block: dict, dmap):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8, 4.2), dpi=100)
    FigureCanvasAgg(fig)
    left, right = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    image = density.projection(dmap)
    x0, z0, v = dmap.origin[0], dmap.origin[2], dmap.voxel
    left.imshow(image.T, origin="lower", cmap="gray_r", aspect="auto",
                extent=(z0, z0 + image.shape[0] * v, x0, x0 + image.shape[1] * v))
    half = block["width"]["value"] / 2.0
    for y in (-half, half):
        left.axhline(y, color="tab:red", lw=0.8, ls="--")
    left.set_xlabel("fibril axis z (Å)")
    left.set_ylabel("x (Å)")
    left.set_title(f"projection, one helical turn; width {2 * half:.0f} Å", fontsize=9)
    rd = block["radial_density"]
    right.plot(rd["r"], rd["mass_density_da_per_a3"], color="tab:blue")
    od = block["outer_diameter"]
    lo, hi = (x / 2.0 for x in od["interval_95"])
    right.axvspan(lo, hi, color="tab:orange", alpha=0.25,
                  label=f"outer radius, 95 % of layouts ({lo:.0f}–{hi:.0f} Å)")
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
