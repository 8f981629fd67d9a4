"""The ensemble's figures in words, for the printed result (run_text.py) and the report's page
(report_page.py): the outer diameter as a distribution with its interval, the width from the
projection, where the radial density of domain mass peaks, the density's Volume object, and the single layout's outer diameter labelled as
such beside them (docs/model/ensemble.md#use)."""
from __future__ import annotations


def outer(block: dict) -> str:
    """'134 Å (median; 95 % of layouts 125–139 Å), mean 133.9 ± 0.3 Å'."""
    od = block["outer_diameter"]
    lo, hi = od["interval_95"]
    return (f"{od['median']:.0f} Å (median; 95 % of layouts {lo:.0f}–{hi:.0f} Å), mean "
            f"{od['mean']:.1f} ± {od['sem']:.1f} Å")


def convergence(block: dict) -> str:
    """'ESS 292, halves 0.6 % apart, 16 replicas × 100 sweeps, seed 0'."""
    od = block["outer_diameter"]
    halves = od.get("halves")
    return (f"ESS {od['ess']:.0f}"
            + ("" if od.get("tau_reliable", True) else " (a run under 50 τ: uncertain)")
            + (f", halves {100 * halves['relative_difference']:.1f} % apart" if halves else "")
            + f", {block['replicas']} replicas × {block['sweeps']} sweeps, seed {block['seed']}")


def width(block: dict) -> str:
    """'110 Å (the projection's profile at 10 % of its peak)'."""
    w = block["width"]
    return f"{w['value']:.0f} Å (the projection's profile at {100 * w['fraction_of_peak']:.0f} % " \
           f"of its peak)"


def radial_peak(block: dict) -> tuple[float, float]:
    """(r Å, Da/Å³): where the radial density of domain mass is highest, and its value."""
    rd = block["radial_density"]
    mass = rd["mass_density_da_per_a3"]
    i = max(range(len(mass)), key=mass.__getitem__)
    return float(rd["r"][i]), float(mass[i])


def radial(block: dict) -> str:
    """'highest 36 Å from the axis (0.35 Da/Å³)'."""
    r, top = radial_peak(block)
    return f"domain mass highest {r:.0f} Å from the axis ({top:.2f} Da/Å³)"


def lines(block: dict | None) -> list[str]:
    """The printed result's ensemble lines (none without an ensemble block)."""
    if not block:
        return []
    if not block.get("sampled"):
        return [f"ensemble: not sampled: {block['reason']}"]
    return [f"ensemble: outer diameter {outer(block)}; {convergence(block)}",
            f"ensemble: width {width(block)}"
            + (f"; map {block['map']['path']}" if block.get("map") else ""),
            *([volume(block)] if block.get("volume") else [])]


def volume(block: dict) -> str:
    """'ensemble: density over the model as the Volume object "ensemble density" (...)'."""
    v = block["volume"]
    return (f"ensemble: density over the model as the Volume object \"{v['object']}\" "
            f"({v['window_layers']} layers, {v['voxel']:g} Å voxels, empty below a volume "
            f"fraction of {v['threshold']:g})")


def cells(block: dict | None) -> list[tuple[str, str]]:
    """The report's rows for the ensemble of its best layout (none without an ensemble)."""
    if not block:
        return []
    if not block.get("sampled"):
        return [("ensemble", f"not sampled: {block['reason']}")]
    return [("ensemble: outer diameter", outer(block)),
            ("ensemble: width", width(block)),
            ("ensemble: radial density", radial(block)),
            ("ensemble: convergence", convergence(block))]
