"""Every protofilament's own terminus, measured, for a fibril whose protofilaments are not copies
of protofilament 0 at their termini (docs/guide/structures.md#interface-termini).

The model repeats protofilament 0's chain on every protofilament, turned by its measured turn.
When a copy of that chain's anchor lands inside the core's outline (6XYO, 6L1U, 6OSL, ...) or
on another protofilament's anchor (7QJX), the copy is not where the file's own protofilament
starts: this module measures, for each protofilament, its anchor residue's CA, its own way out
(the exit measured through the atoms of every protofilament, structure/exit.py) and the anchor
the model gives it (one bead outside the outline where that way leaves it), and the model is
built from those (Params.pf_anchors, pf_exit_paths: `as_they_are`). What still cannot be built
(an own exit sealed, own anchors on top of each other) is refused with what was measured and
what the user can do. Plain numpy over the read chains; no bpy.
"""
from __future__ import annotations

import math

import numpy as np

from ..geom import exit_path, polygons
from ..model import params as P
from ..model.chain import AnchorInside, CopiesBlocked
from ..model.param_checks import AnchorsTogether
from ..model.param_spec import ParamError
from . import exit as X, fibril as F, reading
from .mapping import anchor_outside, clear_of

# what, beside the measured values, makes the copies the user's rather than the file's
CHOSEN = ("anchor", "core_outline", "protofilaments", "pf_rotation", "pf_rise", "pf_turns")


def own_termini(path, geometry, residue_radius: float = P.DEFAULTS.residue_radius,
                residue_spacing: float = P.DEFAULTS.residue_spacing) -> list[dict]:
    """Per protofilament: its anchor residue, CA (layer frame), its own way out measured through
    every protofilament's atoms by the exit's rule (structure/exit.way_out: found, length, the
    residues it spends at the model's spacing)
    and the model's anchor for it (where that way leaves the outline, one bead out)."""
    loaded = reading.load(path, "--fibril", peptides=True)
    chains = F._stacked_core(loaded, loaded.path.name, "--fibril")[0]
    by_name = {c.name: c for c in chains}
    origin, frame = F.layer_frame(geometry)
    outline = np.asarray(geometry.core_outline, float)
    side = "N" if geometry.terminus == "N" else "C"
    out = []
    for k, a in enumerate(geometry.anchors):
        way = geometry.exit if k == 0 else X.way_out(  # by the rule (buried-terminus.md#rule)
            chains, geometry.layer_chains[k], by_name[a["chain"]], a["residue"], side, origin,
            frame, outline, geometry.rise,
            geometry.core_segments or [geometry.core_residues],
            [by_name[b["chain"]] for b in geometry.anchors])
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
                    "exit_residues": spent, "anchor": bead,
                    "path": way["path"] if spent else None})
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


def _copies_refused(values: dict) -> bool:
    """Whether the model refuses protofilament 0's chain turned onto the others: a copy's
    anchor inside the core (AnchorInside, j >= 1) or on another's (AnchorsTogether), or the
    copies block every straight way out that protofilament 0's own chain has (CopiesBlocked).
    Any other refusal is left to make_params to say."""
    try:
        P.make_params(force=True, **values)
    except (AnchorInside, AnchorsTogether, CopiesBlocked) as exc:
        return not isinstance(exc, AnchorInside) or exc.protofilament > 0
    except (ParamError, ValueError, TypeError):
        return False
    return False


def as_they_are(values: dict, measured, explicit, block: dict | None = None):
    """(values, block) with each protofilament's own terminus (pf_anchors, pf_exit_paths) where
    the file's protofilaments are not copies at their termini: protofilament 0's chain turned
    onto protofilament j would start inside the core or on another's anchor, or the copies
    block every way out (_copies_refused), nothing of the
    geometry chosen by the user (CHOSEN). Where the copies build (most files), `values` as
    they are: nothing changes. `block` (the result's structure block) gets the values applied
    and their sources. Raises ParamError when an own exit is sealed (with the measurement)."""
    if (measured is None or measured.fibril is None or measured.fibril.protofilaments < 2
            or set(explicit) & set(CHOSEN + ("pf_anchors", "pf_exit_paths"))
            or int(values.get("protofilaments", 1)) < 2 or not _copies_refused(values)):
        return values, block
    g = measured.fibril
    radius = float(values.get("residue_radius", P.DEFAULTS.residue_radius))
    spacing = float(values.get("residue_spacing", P.DEFAULTS.residue_spacing))
    termini = own_termini(measured.fibril_path, g, radius, spacing)
    sealed = [t for t in termini[1:] if not t["exit_found"]]
    if sealed:
        t = sealed[0]
        raise ParamError("anchor", (
            f"protofilament {t['protofilament']}'s own terminus, chain {t['chain']} "
            f"{t['residue_name']}{t['residue']} (CA at ({t['ca'][0]:.1f}, {t['ca'][1]:.1f}) Å), "
            f"is sealed: measured through every protofilament's atoms, no way out clear of them "
            f"for a {radius:g} Å bead; protofilament 0's chain {termini[0]['chain']} "
            f"{termini[0]['residue_name']}{termini[0]['residue']}: {_exit_words(termini[0])}. "
            f"Its chains cannot carry the domain as deposited: give --protofilaments 1 "
            f"(protofilament 0's chains decorated, the whole core kept) "
            f"(docs/guide/structures.md#interface-termini)"))
    rows = [[*(values["anchor"] if k == 0 and "anchor" in values else t["anchor"]),
             int(values.get("exit_residues", 0)) if k == 0 else int(t["exit_residues"] or 0)]
            for k, t in enumerate(termini)]
    paths = [[k, *pt] for k, t in enumerate(termini) if t["path"] for pt in t["path"]]
    values = {**values, "pf_anchors": rows}
    if paths:
        values["pf_exit_paths"] = paths
    if block is not None:
        said = ", ".join(f"{k}: chain {t['chain']} {t['residue_name']}{t['residue']} "
                         f"({_exit_words(t)})" for k, t in enumerate(termini))
        block = {**block, "applied": {**block["applied"], "pf_anchors": rows},
                 "sources": {**block.get("sources", {}),
                             "pf_anchors": f"{g.file}: measured, each protofilament's own "
                                           f"terminus and its way out through every "
                                           f"protofilament's atoms ({said}): protofilament "
                                           f"0's chain turned onto the others would start "
                                           f"inside the core or on another's anchor, or "
                                           f"find no way out "
                                           f"(docs/guide/structures.md#interface-termini)"}}
        if paths:
            block["applied"]["pf_exit_paths"] = f"[... {len(paths)} rows]"
            block["sources"]["pf_exit_paths"] = f"{g.file}: measured, each protofilament's " \
                                                f"own exit path"
    return values, block


def own_apart(exc: AnchorsTogether, values: dict, measured) -> ParamError:
    """The refusal for own anchors (pf_anchors) of two protofilaments on top of each other:
    what was measured and what the user can do."""
    a, b = exc.protofilaments
    rows = values["pf_anchors"]
    return ParamError("pf_anchors", (
        f"the file's own protofilaments {a} and {b} start {exc.apart:.2f} Å apart (their "
        f"anchors, measured where each one's way out leaves the core: ({rows[a][0]:.1f}, "
        f"{rows[a][1]:.1f}) and ({rows[b][0]:.1f}, {rows[b][1]:.1f}) Å), less than two "
        f"residue radii: their chains would start on each other. Give --protofilaments 1 "
        f"(protofilament 0's chains decorated, the whole core kept), or --anchor X Y "
        f"(docs/guide/structures.md#interface-termini)"))


def make_params(values: dict, measured, explicit, force: bool = False):
    """P.make_params(**values), a refused copy of a measured anchor explained (`explained`),
    own anchors on top of each other said so (`own_apart`)."""
    try:
        return P.make_params(force=force, **values)
    except AnchorsTogether as exc:
        if values.get("pf_anchors") is not None and "pf_anchors" not in explicit:
            raise own_apart(exc, values, measured) from None
        raise
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
        values, _ = as_they_are(values, measured, {})
        make_params(values, measured, {})
    except ParamError as exc:
        return {"builds": False, "refusal": str(exc)}
    if values.get("pf_anchors") is not None:  # each protofilament's own terminus
        return {"builds": True, "refusal": None,
                "own_exits": [int(r[2]) for r in values["pf_anchors"]]}
    return {"builds": True, "refusal": None}


def run_line(check: dict) -> str | None:
    """`inspect`'s line for run_check."""
    if check["builds"] is None:
        return None
    if check["builds"] and check.get("own_exits") is not None:
        spent = ", ".join(map(str, check["own_exits"]))
        return (f"run: builds (these files, nothing else given), each protofilament from its own "
                f"terminus (its exit spends {spent} residue(s); docs/guide/structures.md"
                f"#interface-termini)")
    return ("run: builds (these files, nothing else given)" if check["builds"] else
            f"run: refuses these files as they are: {check['refusal']}")
