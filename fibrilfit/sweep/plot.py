"""phase.png: accommodated fraction against linker length, one line per globule diameter with its
Wilson band; a heatmap when two other parameters vary. Drawn with matplotlib's Agg canvas (no
pyplot, no display), written atomically."""
from __future__ import annotations

import json

from .. import files
from ..model import params as P
from .summary import fmt_value, order_key, varied

MAX_LINES = 10
MARKERS = "os^Dv<>p"  # lines that coincide stay distinguishable


def _unit(name: str) -> str:
    unit = P.field_spec(name)["unit"]
    return f" {unit}" if unit in ("Å", "rad", "Å/s²") else ""


def _axis_label(name: str) -> str:
    unit = P.field_spec(name)["unit"]
    return name.replace("_", " ") + (f" ({unit})" if unit and unit not in ("×",) else "")


def _x(value):
    return value if not isinstance(value, list) else value[0]


def _lines(ax, rows, x: str, series: list[str], target: float) -> None:
    groups: dict[str, list] = {}
    for r in rows:
        groups.setdefault(json.dumps([r.values[n] for n in series]), []).append(r)
    shown = list(groups.items())[:MAX_LINES]
    for k, (label, members) in enumerate(shown):
        members = sorted((r for r in members if r.n), key=lambda r: _x(r.values[x]))
        if not members:
            continue
        xs = [_x(r.values[x]) for r in members]
        ys = [r.fraction for r in members]
        lows = [r.interval[0] for r in members]
        highs = [r.interval[1] for r in members]
        name = ", ".join(f"{n.replace('_', ' ')} {fmt_value(v)}{_unit(n)}"
                         for n, v in zip(series, json.loads(label))) or None
        (line,) = ax.plot(xs, ys, marker=MARKERS[k % len(MARKERS)], label=name,
                          linestyle=("-", "--", ":", "-.")[k // len(MARKERS) % 4])
        ax.fill_between(xs, lows, highs, color=line.get_color(), alpha=0.2, linewidth=0)
    ax.axhline(target, color="grey", linestyle="--", linewidth=1,
               label=f"target {100 * target:g} %")
    ax.set_xlabel(_axis_label(x))
    ax.set_ylabel("accommodated fraction of seeds")
    ax.set_ylim(-0.02, 1.02)
    if len(groups) > MAX_LINES:
        ax.set_title(f"first {MAX_LINES} of {len(groups)} series (all in summary.csv)",
                     fontsize=9)
    ax.legend(fontsize=8)


def _heatmap(fig, ax, rows, x: str, y: str) -> None:
    xs = sorted({json.dumps(r.values[x]) for r in rows}, key=lambda v: order_key(json.loads(v)))
    ys = sorted({json.dumps(r.values[y]) for r in rows}, key=lambda v: order_key(json.loads(v)))
    grid = [[float("nan")] * len(xs) for _ in ys]
    for r in rows:
        if r.n:
            grid[ys.index(json.dumps(r.values[y]))][xs.index(json.dumps(r.values[x]))] = r.fraction
    image = ax.imshow(grid, origin="lower", aspect="auto", vmin=0, vmax=1, cmap="viridis")
    ax.set_xticks(range(len(xs)), [fmt_value(json.loads(v)) for v in xs])
    ax.set_yticks(range(len(ys)), [fmt_value(json.loads(v)) for v in ys])
    if len(xs) * len(ys) <= 150:
        for r in rows:
            if r.n:
                ax.text(xs.index(json.dumps(r.values[x])), ys.index(json.dumps(r.values[y])),
                        f"{r.accommodated}/{r.n}", ha="center", va="center", fontsize=7,
                        color="white" if r.fraction < 0.6 else "black")
    ax.set_xlabel(_axis_label(x))
    ax.set_ylabel(_axis_label(y))
    fig.colorbar(image, ax=ax, label="accommodated fraction of seeds")


def layout(rows) -> tuple[str, str, list[str]]:
    """("lines" or "heatmap", the x parameter, the other varied parameters)."""
    names = varied(rows)
    if "linker" in names or not names:
        x = "linker"
    else:  # keep one line per globule diameter where there can be
        x = next((n for n in names if n != "globule_diameter"), names[0])
    others = [n for n in names if n != x]
    kind = "heatmap" if len(names) == 2 and "globule_diameter" not in names else "lines"
    return kind, x, others


def write(path, rows, target: float):
    """Draw the sweep's rows (summary.rows) into a PNG at `path`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    kind, x, others = layout(rows)
    fig = Figure(figsize=(7.5, 4.8), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    if kind == "heatmap":
        _heatmap(fig, ax, rows, x, others[0])
        how = "cells: accommodated / seeds"
    else:
        _lines(ax, rows, x, others, target)
        how = "bands: 95 % Wilson interval"
    fig.suptitle("FibrilFit sweep: fraction of seeds that found a clash-free layout "
                 f"with intact linkers ({how})", fontsize=9)
    fig.tight_layout()
    return files.atomic_write(path, lambda tmp: fig.savefig(tmp, format="png"))
