"""The anchor's way out: the shortest path from protofilament 0's anchor CA to the core's
surface clear of the core's atoms, in the model's layer frame, by the rule of
docs/model/buried-terminus.md#rule: the atoms a side chain's rotamer can move (every side-chain
atom beyond Cβ, and the terminal OXT) neither block the way nor define the surface; measured
from the reference layer and its neighbours, the shortest kept. The way through the atoms as
deposited is measured beside it, from the same layers, as the exit's sensitivity. Plain numpy
over the read chains.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..geom import exit_path as E, rigid as G
from ..model import params as P
from . import outline as O

BEAD_RADIUS = P.DEFAULTS.residue_radius  # Å, 1.75: the model's residue is the exit's bead
BONDED = 3.0  # Å: the anchor's own chain's atoms this near its CA are its peptide bond's
Z_HALF_RISES = 1.0  # the path stays within one rise above and below the anchor's layer
FIXED = ("N", "CA", "C", "O", "CB")  # the atoms no rotamer moves (docs/...#rule)
LAYERS = 3  # the reference layer and its nearest interior neighbours, each measured
RULE = ("side chains cut to Cβ and terminal OXT removed (they neither block the way nor make "
        "the surface), the shortest way from the reference layer and its neighbours")


def obstacles(chains, ref, residue: int, side: str, origin, frame) -> tuple:
    """Heavy atoms (n, 3) in the layer frame, their radii, and the anchor CA: every chain of the
    file but for the residues beyond the anchor on the linker's side (they are linker: the
    path stands for them), the anchor residue itself, and its own chain's atoms bonded to its
    CA (the C and O before it: 2.45 and 2.85 Å in 5OQV)."""
    ca = (ref.ca_of([residue])[0] - origin) @ frame.T
    xyz, radii = [], []
    for c in chains:
        local = (c.heavy - origin) @ frame.T
        keep = c.heavy_residue <= residue if side == "C" else c.heavy_residue >= residue
        if c is ref:
            keep &= c.heavy_residue != residue
            keep &= np.linalg.norm(local - ca, axis=1) >= BONDED
        xyz.append(local[keep])
        radii.append(c.heavy_radius[keep])
    return np.concatenate(xyz), np.concatenate(radii), ca


def measure(chains, ref, residue: int, side: str, origin, frame, outline, rise: float,
            bead_radius: float = BEAD_RADIUS) -> dict:
    """The anchor's exit through `chains` as given, to `outline`: found, its length, the
    anchor's depth below the outline, the path (layer frame, Å, anchor first), the bead radius
    and what the path keeps clear of (JSON-ready)."""
    atoms, radii, ca = obstacles(chains, ref, residue, side, origin, frame)
    found = E.shortest_exit(atoms, radii, ca, np.asarray(outline, float),
                            bead_radius=bead_radius, z_half=Z_HALF_RISES * rise)
    return {"found": found.found,
            "length": round(found.length, 2) if found.found else None,
            "depth": round(found.depth, 2),
            "path": [[round(float(v), 3) for v in p] for p in found.points],
            "bead_radius": bead_radius,
            "clearance": f"bead {bead_radius:g} Å + each heavy atom's van der Waals radius",
            "searched": f"{E.STEP:g} Å grid, within {Z_HALF_RISES:g} rise of the anchor's "
                        f"layer, up to {E.MAX_LENGTH:g} Å"}


def fixed(chain):
    """The chain with only the atoms no rotamer moves (FIXED): N, CA, C, O and CB."""
    keep = np.isin(np.asarray(chain.heavy_name, dtype=str), FIXED)
    return _kept(chain, keep)


def without_oxt(chain):
    """The chain as deposited less its terminal oxygen (OXT)."""
    return _kept(chain, np.asarray(chain.heavy_name, dtype=str) != "OXT")


def _kept(chain, keep):
    sub = {k: getattr(chain, k)[keep] for k in
           ("heavy", "heavy_residue", "heavy_radius", "heavy_name", "heavy_element",
            "heavy_resname", "heavy_b") if getattr(chain, k) is not None}
    return dataclasses.replace(chain, **sub)


def in_core(numbers, segments) -> np.ndarray:
    """Which residue `numbers` lie in the core's segments ([[first, last], ...])."""
    numbers = np.asarray(numbers)
    return np.logical_or.reduce([(numbers >= a) & (numbers <= b) for a, b in segments])


def fixed_outline(layer, segments, origin, frame) -> np.ndarray:
    """The outline (k, 2) of the reference layer's core residues' FIXED atoms (the core's
    segments, [[first, last], ...]): the surface the rule's way out must reach."""
    xyz, radii = [], []
    for c in layer:
        c = fixed(c)
        keep = in_core(c.heavy_residue, segments)
        xyz.append(c.heavy[keep])
        radii.append(c.heavy_radius[keep])
    section = ((np.concatenate(xyz) - origin) @ frame.T)[:, :2]
    return np.round(O.polygon(section, np.concatenate(radii))[0], 2)


def measured_layers(stack: list, ref: str) -> list:
    """The chain names, along protofilament 0's stack `stack`, whose anchors are measured: the
    reference layer and its nearest neighbours up to LAYERS, interior ones only (a chain at an
    end of the file's stack has no layer on one side: its way out would leave through it)."""
    inner = stack[1:-1] if len(stack) >= 3 else list(stack)
    if ref not in inner:
        inner = list(stack)
    at = inner.index(ref)
    return sorted(inner, key=lambda n: (abs(inner.index(n) - at), inner.index(n)))[:LAYERS]


def way_out(chains, stack: list, ref, residue: int, side: str, origin, frame, outline, rise,
            segments, layer, spacing: float = P.DEFAULTS.residue_spacing) -> dict:
    """Protofilament 0's exit by the rule (RULE; docs/model/buried-terminus.md#rule), as the
    fibril's measurement records it: `measure`'s keys for the shortest of the measured layers'
    ways out through the FIXED atoms to the FIXED atoms' outline, with `rule`, the `layer`
    (chain) it came from, and `sensitivity`: per layer and per set of atoms (fixed; as
    deposited; deposited less OXT where the file has one) found, length and residues spent,
    the deposited ones to the model's outline."""
    by_name = {c.name: c for c in chains}
    cut = [fixed(c) for c in chains]
    cut_by = {c.name: c for c in cut}
    no_oxt = [without_oxt(c) for c in chains]
    has_oxt = sum(len(c.heavy) for c in no_oxt) < sum(len(c.heavy) for c in chains)
    surface = fixed_outline(layer, segments, origin, frame)
    common = ref.residues[in_core(ref.residues, segments)]
    rows, ways = [], []
    for name in measured_layers(stack, ref.name):
        here = by_name[name]
        shared = common[np.isin(common, here.residues)]
        rot, shift, _ = G.superpose(ref.ca_of(shared), here.ca_of(shared))
        o, f = origin @ rot.T + shift, frame @ rot.T  # the layer frame carried to this layer
        sets = [("fixed", cut, cut_by[name], surface), ("deposited", chains, here, outline)]
        if has_oxt:
            sets.append(("deposited, no OXT", no_oxt, no_oxt[chains.index(here)], outline))
        for atoms, obstacle_chains, own, edge in sets:
            way = measure(obstacle_chains, own, residue, side, o, f, edge, rise)
            rows.append({"layer": name, "atoms": atoms, "found": way["found"],
                         "length": way["length"],
                         "residues": (E.residues_spent(way["length"], spacing)
                                      if way["found"] else None)})
            if atoms == "fixed":
                ways.append((name, way))
    found = [(n, w) for n, w in ways if w["found"]]
    name, best = min(found, key=lambda nw: nw[1]["length"]) if found else ways[0]
    return {**best, "rule": RULE, "layer": name, "sensitivity": rows}


def sensitivity_words(way: dict) -> str:
    """The exit's range in one phrase: per set of atoms, over the measured layers, the ways
    found and their residues spent."""
    parts = []
    for atoms in ("fixed", "deposited", "deposited, no OXT"):
        rows = [r for r in way.get("sensitivity", ()) if r["atoms"] == atoms]
        if not rows:
            continue
        got = [r for r in rows if r["found"]]
        spent = sorted({r["residues"] for r in got})
        lengths = [r["length"] for r in got]
        lo, hi = (f"{min(lengths):.2f}", f"{max(lengths):.2f}") if got else ("", "")
        span = (f"{lo}{'-' + hi if hi != lo else ''} Å, "
                f"{spent[0]}{'-' + str(spent[-1]) if len(spent) > 1 else ''} residue(s)"
                if got else "")
        sealed = len(rows) - len(got)
        parts.append(f"{atoms}: {span}{'; ' if got and sealed else ''}"
                     f"{f'sealed in {sealed} of {len(rows)} layers' if sealed else ''}")
    return "; ".join(parts)
