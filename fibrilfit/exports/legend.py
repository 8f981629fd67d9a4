"""A legend and a scale bar drawn onto a rendered PNG, so a picture says what it shows.

Composed after rendering with matplotlib's Agg canvas (no display, no pyplot): the PNG is read,
shown pixel for pixel on a figure of the same size, and written back with a legend box (what
each colour is: core, linker, each protofilament's domains, clash, graze) and a scale bar in Å
measured at the depth of the fibril axis (the render is a perspective view: nearer parts look
larger, farther ones smaller). Blender's own Python has no matplotlib: there `available()` is
False and the render keeps no legend, which its JSON says (`legend.drawn: false`).
"""
from __future__ import annotations

import importlib.util
import math

import numpy as np

SCALE_FRACTION = 0.2   # the scale bar is about a fifth of the picture's width
NICE = (1, 2, 5)       # its length: 1, 2 or 5 times a power of ten Å


MIN_SIZE = (240, 135)  # below this a legend would hide the model (and cannot be read)


def available() -> bool:
    return importlib.util.find_spec("matplotlib") is not None


def why_not(width: int, height: int) -> str | None:
    """Why a picture of this size gets no legend (None: it gets one)."""
    if width < MIN_SIZE[0] or height < MIN_SIZE[1]:
        return f"the picture is smaller than {MIN_SIZE[0]}x{MIN_SIZE[1]} pixels"
    if not available():
        return "needs matplotlib"
    return None


def srgb(linear) -> tuple[float, float, float]:
    """A linear colour (ob.color) as the Standard view transform shows it (sRGB)."""
    c = np.clip(np.asarray(linear, dtype=float)[:3], 0.0, 1.0)
    out = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    return tuple(float(v) for v in out)


def scale_length(angstrom_per_px: float, width_px: int) -> float:
    """A round length (1, 2 or 5 × 10^k Å) near SCALE_FRACTION of the picture's width."""
    want = SCALE_FRACTION * width_px * angstrom_per_px
    power = 10.0 ** math.floor(math.log10(want))
    return max((n * power for n in NICE if n * power <= want), default=power)


CORNERS = {"upper left": (0, 1), "upper right": (1, 1), "lower left": (0, 0),
           "lower right": (1, 0)}


def emptiest_corners(image: np.ndarray, box_w: float, box_h: float) -> list[str]:
    """The corners ordered by how little of the model a box of box_w × box_h pixels there
    would hide: pixels unlike the backdrop (the picture's commonest colour) count."""
    h, w = image.shape[:2]
    rgb = np.asarray(image[..., :3], dtype=float)
    border = np.concatenate([rgb[0], rgb[-1], rgb[:, 0], rgb[:, -1]])
    backdrop = np.median(border, axis=0)
    busy = np.abs(rgb - backdrop).max(axis=2) > 0.06
    bw, bh = int(min(w, max(1, box_w))), int(min(h, max(1, box_h)))

    def hidden(name):
        cx, cy = CORNERS[name]  # (0, 0): lower left; image rows run top to bottom
        cols = slice(0, bw) if cx == 0 else slice(w - bw, w)
        rows = slice(h - bh, h) if cy == 0 else slice(0, bh)
        return float(busy[rows, cols].mean())

    return sorted(CORNERS, key=lambda name: (hidden(name), list(CORNERS).index(name)))


def compose(png_in, png_out, entries: list[tuple[str, tuple]], angstrom_per_px: float | None,
            *, note: str | None = None) -> dict:
    """Draw the legend (`entries`: (label, linear RGB[A]) pairs) and a scale bar onto the PNG
    `png_in`, written to `png_out` at the same size. Returns what was drawn."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.image import imread
    from matplotlib.patches import Patch, Rectangle

    image = imread(str(png_in))
    h, w = image.shape[:2]
    dpi = 100
    fig = Figure(figsize=(w / dpi, h / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.imshow(image, interpolation="none", extent=(0, w, 0, h))
    ax.set(xlim=(0, w), ylim=(0, h))
    ax.set_axis_off()
    font = max(6.0, min(11.0, h / 45))
    handles = [Patch(facecolor=srgb(c), edgecolor="0.15", label=label) for label, c in entries]
    longest = max((len(label) for label, _ in entries), default=0)
    corners = emptiest_corners(image, longest * font * 0.62 + 40,
                               len(entries) * font * 1.75 + 12)
    where = corners[0]
    if handles:
        ax.legend(handles=handles, loc=where, fontsize=font, framealpha=0.85,
                  facecolor="white", edgecolor="0.4", handlelength=1.2, borderpad=0.4,
                  labelspacing=0.3)
    bar = None
    if angstrom_per_px and angstrom_per_px > 0:
        bar = scale_length(angstrom_per_px, w)
        px = bar / angstrom_per_px
        # the scale bar: the emptiest other corner at the bottom (the note sits bottom right)
        low = [c for c in corners[1:] if c.startswith("lower")] or ["lower left"]
        right = low[0] == "lower right"
        thick = max(2.0, h / 120)
        x0 = (w - 0.04 * w - px) if right else 0.04 * w
        y0 = 0.05 * h + (font * 1.6 if right else 0)
        ax.add_patch(Rectangle((x0 - 6, y0 - 6), px + 12, thick + font * 2.6 + 6,
                               facecolor="white", alpha=0.85, edgecolor="0.4", lw=0.6))
        ax.add_patch(Rectangle((x0, y0), px, thick, facecolor="black"))
        ax.text(x0 + px / 2, y0 + thick + 2, f"{bar:g} Å", ha="center", va="bottom",
                fontsize=font, color="black")
    if note:
        ax.text(w - 6, 6, note, ha="right", va="bottom", fontsize=font * 0.8, color="white",
                alpha=0.9)
    fig.savefig(str(png_out), format="png", dpi=dpi)
    return {"drawn": True, "entries": [label for label, _ in entries], "legend_corner": where,
            "scale_bar_angstrom": bar,
            "angstrom_per_pixel": None if not angstrom_per_px else round(angstrom_per_px, 5)}
