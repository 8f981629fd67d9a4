"""`--fibril FILE` / `--domain FILE` / `--full-length FILE` for `run`, `sweep` and a case's
[structure] (the command line's `--case` and the sidebar's Load case): the files measured, the
model values measured from them, the explicit options winning, and the `structure` block a
result records."""
from __future__ import annotations

import dataclasses
import sys

from ..exits import UsageError
from ..model import params as P
from .request import StructureRequest
from .mapping import EXIT_PARAMS, PF_PARAMS, RESIDUE_RADIUS, linker_source, model_values


def block(fibril, domain, applied: dict, overridden: dict, not_in_model: list) -> dict:
    """What a result says it was computed from: files, sha256, measurements, what was used."""
    out = {}
    for key, m in (("fibril", fibril), ("domain", domain)):
        if m is not None:
            out[key] = {"file": m.file, "sha256": m.sha256, "measured": m.to_dict()}
    out["applied"] = {k: ("[... %d rows]" % len(v) if k in ("domain_atoms", "domain_spheres",
                                                             "further_atoms", "further_spheres")
                          else v) for k, v in applied.items()}
    out["overridden"] = sorted(overridden)  # measured, but an explicit option set the value
    out["not_in_model"] = not_in_model  # measured, but this model has no such parameter
    return out


def warnings(fibril, domain, *more_domains) -> list[str]:
    """Every warning and note of the measurement, each naming its file: buried anchors, an
    approximate axis, a core in pieces, the chain or model chosen, layers built by symmetry."""
    out = []
    for m in (fibril, domain, *more_domains):
        if m is not None:
            out += [f"{m.file}: {w}" for w in (*getattr(m, "warnings", []), *m.notes)]
    return out


def sources(fibril, domain, applied, more_domains=()) -> dict:
    """Parameter name -> where its measured value came from, for each applied value: the file
    and what in it ('2n0a.pdb.gz: modelled tail 98-140 ...', '1ubq.pdb.gz: measured, ...')."""
    out = {}
    if fibril is not None:
        f = fibril
        axis = "" if f.axis_exact else ", axis approximate"
        pairs = sum(max(0, len(q) - 1) for q in f.layer_chains)
        a = f.anchors[0]
        # a β-solenoid's layer is a molecule (docs/guide/structures.md#beta-solenoids)
        per = (f", one layer per molecule of {f.rungs} rungs (β-solenoid)" if f.rungs > 1 else "")
        pieces = ", ".join(f"{lo}-{hi}" for lo, hi in (f.core_segments or [f.core_residues]))
        said = {
            "rise": f"{f.file}: measured over {pairs} layer pairs, sd {f.rise_sd:g} Å{axis}{per}",
            "twist": f"{f.file}: measured over {pairs} layer pairs, sd {f.twist_sd:g} rad{axis}",
            "protofilaments": f"{f.file}: measured, {f.protofilaments} stacks of chains",
            "pf_rotation": f"{f.file}: measured between protofilaments 0 and 1",
            "pf_rise": f"{f.file}: measured between protofilaments 0 and 1",
            "pf_turns": f"{f.file}: measured, each protofilament's turn and rise from "
                        f"protofilament 0",
            "core_outline": f"{f.file}: measured, the section of core residues {pieces}",
            "anchor": f"{f.file}: measured, one bead outside chain {a['chain']} "
                      f"{a['residue_name']}{a['residue']}, the core's {f.terminus}"
                      f"{'-terminal residue' if f.terminus in ('N', 'C') else ''}"
                      f"{', BURIED' if a['buried'] else ''}",
        }
        way = f.exit or {}
        if "exit_residues" in applied:
            said["exit_residues"] = (
                f"{f.file}: measured, a {way['length']:g} Å path from {a['residue_name']}"
                f"{a['residue']}'s CA (layer {way.get('layer')}) to the surface, clear of the "
                f"core's atoms by the {way['clearance']}, by the rule: {way.get('rule')} "
                f"(docs/model/buried-terminus.md#rule)"
                if way.get("found") else
                f"{f.file}: measured, no path from {a['residue_name']}{a['residue']}'s CA to "
                f"the surface clear of the core's atoms ({way.get('searched')}) from any "
                f"measured layer, by the rule: {way.get('rule')}: no exit")
            said["exit_path"] = f"{f.file}: measured, the exit's path"
            if way.get("found"):
                said["anchor"] = (f"{f.file}: measured, one bead outside the outline where "
                                  f"the exit from chain {a['chain']} {a['residue_name']}"
                                  f"{a['residue']} (BURIED) leaves it")
        if f.tail_residues:
            t = f.tail_residues
            said["linker"] = (f"{f.file}: modelled tail {t[0]}-{t[1]} (the anchor and "
                              f"{t[1] - t[0] + 1} residues)")
        out.update({k: v for k, v in said.items() if k in applied})
    if domain is not None and "globule_diameter" in applied:
        d = domain
        out["globule_diameter"] = (f"{d.file}: measured, 2·√(5/3)·Rg, Rg {d.rg:g} Å, chain "
                                   f"{d.chain} residues {d.residues[0]}-{d.residues[1]}")
    if domain is not None:  # the real shapes (docs/model/domain-shapes.md#domain-shapes)
        files = [d.file for d in (domain, *more_domains)]
        said = {"domain_atoms": (files[:1], "hull atoms"),
                "domain_spheres": (files[:1], "covering spheres"),
                "domain_joint": (files[:1], "the incoming terminal CA"),
                "further_atoms": (files[1:], "hull atoms"),
                "further_spheres": (files[1:], "covering spheres"),
                "further_joints": (files[1:], "the incoming terminal CAs"),
                "domain_exits": (files[:-1], "the outgoing terminal CAs"),
                "domain_diameters": (files[1:], "2·√(5/3)·Rg of each")}
        out.update({k: f"{', '.join(f)}: measured, {what}" for k, (f, what) in said.items()
                    if k in applied and f})
    return out


def split(fibril, domain, *, explicit: set, known: set, residue_radius: float = RESIDUE_RADIUS,
          more_domains=(), shape: str = "sphere",
          residue_spacing: float = P.DEFAULTS.residue_spacing):
    """(values to apply, structure block). `explicit`: parameters given as options (they win;
    an explicit anchor takes the measured exit with it); `known`: the model's parameter names;
    `more_domains`: the domains after `domain`; `shape`: the domain_shape asked for."""
    values = model_values(fibril, domain, residue_radius=residue_radius,
                          more_domains=more_domains, shape=shape,
                          residue_spacing=residue_spacing)
    if "anchor" in explicit:  # the exit leads to the measured anchor, not to the one given
        explicit = explicit | {k for k in EXIT_PARAMS if k in values}
    if explicit & set(PF_PARAMS) and "pf_turns" in values:  # the turns given, not measured
        explicit = explicit | {"pf_turns"}
    applied = {k: v for k, v in values.items() if k in known and k not in explicit}
    overridden = {k: v for k, v in values.items() if k in explicit}
    missing = sorted(k for k in values if k not in known)
    out = block(fibril, domain, applied, overridden, missing)
    out["warnings"] = warnings(fibril, domain, *more_domains)
    out["sources"] = sources(fibril, domain, applied, more_domains)
    # the linker from the files' numbering (a modelled tail is said above), and an option's
    # linker with what the numbering would have given
    said = linker_source(fibril, domain, explicit="linker" in explicit)
    if "linker" in explicit or ("linker" in applied and said.startswith("numbering")):
        out["sources"]["linker"] = said
    return applied, out


def merged(fib, doms: list, seg, explicit: dict) -> tuple[dict, dict]:
    """The model values measured from a fibril (or None), its domains in chain order and a
    full-length model's segmentation (or None), with the `explicit` values over them; and the
    result's `structure` block. (measure_files reads the files a StructureRequest names.)"""
    dom = doms[0] if doms else None
    radius = explicit.get("residue_radius", P.DEFAULTS.residue_radius)
    spacing = explicit.get("residue_spacing", P.DEFAULTS.residue_spacing)
    try:
        radius, spacing = float(radius), float(spacing)
    except (TypeError, ValueError):  # make_params names the bad value below
        radius, spacing = P.DEFAULTS.residue_radius, P.DEFAULTS.residue_spacing
    spacing = spacing if spacing > 0 else P.DEFAULTS.residue_spacing
    shape = str(explicit.get("domain_shape", P.DEFAULTS.domain_shape)).strip().lower()
    applied, block = split(fib, dom, explicit=set(explicit),
                           known={f.name for f in P.fields()}, residue_radius=radius,
                           more_domains=doms[1:], shape=shape, residue_spacing=spacing)
    if block["not_in_model"]:
        block["warnings"].append(f"measured but not in this model: "
                                 f"{', '.join(block['not_in_model'])}")
    if seg is not None:
        block["full_length"] = seg.to_dict()
    if len(doms) > 1:
        block["domains"] = [{"file": d.file, "sha256": d.sha256, "measured": d.to_dict()}
                            for d in doms]
    return {**applied, **explicit}, block


def say_warnings(block: dict | None) -> None:
    """Every warning of the measurement on stderr (issue #23: they travel with every run and
    sweep), said once the run's input has passed its checks, so bad input stays one line."""
    for warning in (block or {}).get("warnings", []):
        print(f"fibrilfit: warning: {warning}", file=sys.stderr)


def exit_block(p, block: dict | None) -> dict | None:
    """The result's `exit` (docs/model/buried-terminus.md#model): the residues the chain spent
    from its anchor to the surface (None when no path leaves it), the anchor's depth below the
    outline, the path's length and points (layer frame, Å), the clearance it keeps, the free
    linker left and where it came from; None without a measured fibril."""
    way = ((block or {}).get("fibril") or {}).get("measured", {}).get("exit")
    if not way:
        return None
    sealed = p.exit_residues >= P.SEALED
    source = (block.get("sources") or {}).get("exit_residues") or (
        "measured; the run's anchor and exit are its explicit values (--anchor, a case's "
        "params)" if "exit_residues" in block["overridden"]
        else "measured: the anchor is on the surface, its path costs no residue")
    out = {"residues": None if sealed else int(p.exit_residues), "found": way["found"],
           "depth": way["depth"], "length": way["length"],
           "path": way["path"],
           "clearance": way["clearance"], "bead_radius": way["bead_radius"],
           "free_linker": p.free_linker, "source": source,
           "rule": way.get("rule"), "layer": way.get("layer"),
           "sensitivity": way.get("sensitivity", [])}
    if p.pf_anchors is not None:  # interface termini: each protofilament's own exit, and the
        # free linker every chain simulates (the smallest; docs/model/bound.md#interface-termini)
        out["pf_residues"] = [int(v) for v in p.pf_exit_residues()]
        out["pf_anchors"] = [list(r[:2]) for r in p.pf_anchors]
    return out


# ---- the files named: a StructureRequest (request.py), from the command line, a case's
# [structure] or the Python API

def domain_files(request: StructureRequest) -> list:
    return [str(v) for v in request.domain]


def domain_specs(request: StructureRequest, fib=None) -> tuple[list, object]:
    """[(file, chain, residues)] of the domains in chain order from the core outward, and the
    full-length model's Segmentation (or None). --full-length gives the folded domains on the
    linker's side of the core."""
    files = domain_files(request)
    chains, ranges = list(request.domain_chain), list(request.domain_residues)
    full = request.full_length
    if full:
        if files:
            raise UsageError("--full-length: gives the domains itself; leave out --domain")
        if chains or ranges:
            raise UsageError("--domain-chain/--domain-residues: not with --full-length")
        from .full_length import segment
        seg = segment(full, fib.core_residues if fib is not None else None)
        side = "N" if fib is not None and fib.terminus == "N" else "C"
        return [(full, seg.chain, f"{d['first']}-{d['last']}")
                for d in seg.chain_order(side)], seg
    for name, given in (("--domain-chain", chains), ("--domain-residues", ranges)):
        if given and not files:
            raise UsageError(f"{name}: needs --domain")
        if len(given) > 1 and len(given) != len(files):
            raise UsageError(f"{name}: given {len(given)} times for {len(files)} --domain "
                             "files: give it once (for all) or once per --domain")
    pick = (lambda given, i: None if not given else given[i] if len(given) > 1 else given[0])
    return [(f, pick(chains, i), pick(ranges, i)) for i, f in enumerate(files)], None


@dataclasses.dataclass
class Measured:
    """The files a request names, measured: the fibril (FibrilGeometry or None) and its file, the
    domains' specs [(file, chain, residues)] and their DomainSizes in chain order, the
    full-length model's Segmentation (or None)."""

    fibril: object
    fibril_path: str | None
    specs: list
    domains: list
    segmentation: object

    @property
    def option(self) -> str:
        return "--full-length" if self.segmentation is not None else "--domain"


def measure_files(request: StructureRequest, *, inspect: bool = False,
                  every_exit: bool = False) -> Measured:
    """Measure the files `request` names. `inspect`: a full-length model
    with no folded domain is shown, not refused; `every_exit`: every domain's outgoing point,
    the last one's too (the sidebar's list, whose order can change; the model never reads the
    last one's: mapping.further_shapes)."""
    from .domain import measure as measure_domain
    from .fibril import measure as measure_fibril
    if request.anchor_residue is not None and not request.fibril:
        raise UsageError("--anchor-residue: needs --fibril")
    fib = None
    if request.fibril:
        fib = measure_fibril(request.fibril, terminus=request.terminus,
                             anchor_residue=request.anchor_residue)
    specs, seg = domain_specs(request, fib)
    if seg is not None and not specs and not inspect:
        from .full_length import no_domain
        raise UsageError(f"--full-length: {no_domain(seg.file)}")
    option = "--full-length" if seg is not None else "--domain"
    doms = [measure_domain(f, chain=c, residues=r, option=option,
                           follows=request.terminus == "C",
                           outgoing=every_exit or i < len(specs) - 1)
            for i, (f, c, r) in enumerate(specs)]
    return Measured(fib, request.fibril, specs, doms, seg)


def measure_all(request: StructureRequest, *, inspect: bool = False) -> tuple:
    """(FibrilGeometry or None, [DomainSize] in chain order, Segmentation or None)."""
    m = measure_files(request, inspect=inspect)
    return m.fibril, m.domains, m.segmentation

