"""Every protofilament's own terminus, measured, for a fibril whose protofilaments are not copies
of protofilament 0 at their termini (docs/guide/structures.md#interface-termini).

The model repeats protofilament 0's chain on every protofilament, turned by its measured turn.
When a copy of that chain's anchor lands inside the core's outline (6XYO, 6L1U, 6OSL, ...), the
copy is not where the file's own protofilament starts: this module measures, for each
protofilament, its anchor residue's CA, the anchor the model would give it (one bead outside
the outline, or where its own way out leaves, the exit measured through the atoms of every
protofilament, structure/exit.py) and how far the copy lands from it, and says so in the
refusal with what the user can do. Plain numpy over the read chains; no bpy.
"""
from __future__ import annotations

import math

import numpy as np

from ..geom import exit_path, polygons
from ..model import params as P
from ..model.chain import AnchorInside
from ..model.param_spec import ParamError
from . import exit as X, fibril as F, reading
from .mapping import anchor_outside, clear_of

# what, beside the measured values, makes the copies the user's rather than the file's
CHOSEN = ("anchor", "core_outline", "protofilaments", "pf_rotation", "pf_rise", "pf_turns")


def own_termini(path, geometry, residue_radius: float = P.DEFAULTS.residue_radius,
                residue_spacing: float = P.DEFAULTS.residue_spacing) -> list[dict]:
    """Per protofilament: its anchor residue, CA (layer frame), its own way out measured through
    every protofilament's atoms (found, length, the residues it spends at the model's spacing)
    and the model's anchor for it (where that way leaves the outline, one bead out)."""
    loaded = reading.load(path, "--fibril", peptides=True)
    chains = F._stacked_core(loaded, loaded.path.name, "--fibril")[0]
    by_name = {c.name: c for c in chains}
    origin, frame = F.layer_frame(geometry)
    outline = np.asarray(geometry.core_outline, float)
    side = "N" if geometry.terminus == "N" else "C"
    out = []
    for k, a in enumerate(geometry.anchors):
        way = geometry.exit if k == 0 else X.measure(
            chains, by_name[a["chain"]], a["residue"], side, origin, frame, outline,
            geometry.rise)
        spent = (exit_path.residues_spent(way["length"], residue_spacing) if way["found"]
                 else None)
        if spent:
            end = way["path"][-1][:2]
            bead = clear_of(outline, anchor_outside(outline, end, residue_radius),
                            residue_radius)
        else:
            bead = anchor_outside(outline, a["position"], residue_radius)
        out.append({"protofilament": k, "chain": a["chain"], "residue": a["residue"],
                    "residue_name": a["residue_name"], "ca": a["position"],
                    "exit_found": way["found"], "exit_length": way["length"],
                    "exit_residues": spent, "anchor": bead})
    return out


def _exit_words(t: dict) -> str:
    if not t["exit_found"]:
        return "sealed: no way out clear of the atoms"
    if not t["exit_residues"]:
        return f"on the surface ({t['exit_length']:g} Å out, no residue spent)"
    return f"{t['exit_length']:g} Å to the surface, {t['exit_residues']} residue(s) spent"


def explained(exc: ParamError, measured, explicit) -> ParamError:
    """The refusal to raise for `exc`: where the model refused protofilament j's copy of a
    measured anchor inside the core (model/chain.AnchorInside, j >= 1), the same refusal with
    what the file's own protofilaments measure and what the user can do; else `exc` itself
    (an anchor, outline or turn the user chose is refused as given)."""
    if (not isinstance(exc, AnchorInside) or exc.protofilament == 0 or measured is None
            or measured.fibril is None or set(explicit) & set(CHOSEN)):
        return exc
    g, j, xy = measured.fibril, exc.protofilament, exc.xy
    poly = np.asarray(g.core_outline, float)
    depth = float(polygons.edge_distance(poly, xy[None])[0][0])
    termini = own_termini(measured.fibril_path, g)
    own, first = termini[j], termini[0]
    apart = math.dist(xy, own["anchor"])
    return ParamError("anchor", (
        f"protofilament {j}'s copy of protofilament 0's chain (turned by "
        f"{math.degrees(exc.turn):.1f}°) would start at ({xy[0]:.2f}, {xy[1]:.2f}) Å, "
        f"{depth:.2f} Å inside the core's outline, {apart:.1f} Å from where the file's own "
        f"protofilament {j} starts: its chain {own['chain']} {own['residue_name']}"
        f"{own['residue']} (CA at ({own['ca'][0]:.1f}, {own['ca'][1]:.1f}) Å; its way out, "
        f"measured through every protofilament's atoms: {_exit_words(own)}), protofilament 0's "
        f"chain {first['chain']} {first['residue_name']}{first['residue']} "
        f"({_exit_words(first)}). The model repeats protofilament 0's chain on every "
        f"protofilament, and this file's protofilaments are not copies at their termini: "
        f"give --protofilaments 1 (protofilament 0's chains decorated, the whole core kept; "
        f"its bound holds for the fully decorated fibril too), or --anchor X Y outside every "
        f"copy (docs/guide/structures.md#interface-termini)"))


def make_params(values: dict, measured, explicit, force: bool = False):
    """P.make_params(**values), a refused copy of a measured anchor explained (`explained`)."""
    try:
        return P.make_params(force=force, **values)
    except ParamError as exc:
        raise explained(exc, measured, explicit) from None


def run_check(measured) -> dict:
    """What `run` would do with the files `inspect` read (a from_files.Measured), nothing given
    beside them (the default domain when none is named): {"builds": True} or {"builds":
    False, "refusal": its one line}, so that `inspect` says before `run` why it will not."""
    from .from_files import merged
    if measured.fibril is None:
        return {"builds": None, "refusal": None}
    try:
        values, _ = merged(measured.fibril, measured.domains, measured.segmentation, {})
        make_params(values, measured, {})
    except ParamError as exc:
        return {"builds": False, "refusal": str(exc)}
    return {"builds": True, "refusal": None}


def run_line(check: dict) -> str | None:
    """`inspect`'s line for run_check."""
    if check["builds"] is None:
        return None
    return ("run: builds (these files, nothing else given)" if check["builds"] else
            f"run: refuses these files as they are: {check['refusal']}")
