"""What `inspect` prints: plain lines, units in the text."""
from __future__ import annotations

import math

from ..model.helix import handedness
from . import exit as X


def _deg(rad: float) -> str:
    return f"{math.degrees(rad):+.3f}°"


def core_text(g) -> str:
    """'5-65, 102-132 (66-101 between them: inside the fibril, not linker)' for a core in
    pieces (docs/guide/structures.md#cores-in-pieces); '38-97' for one."""
    pieces = g.core_segments or [g.core_residues]
    text = ", ".join(f"{a}-{b}" for a, b in pieces)
    if len(pieces) > 1:
        gaps = ", ".join(f"{b + 1}-{c - 1}" for (_, b), (c, _) in zip(pieces, pieces[1:]))
        text += f" ({gaps} between them: inside the fibril, not linker)"
    return text


def fibril_lines(g) -> list:
    hand = handedness(g.twist)
    lines = [f"fibril {g.file} (sha256 {g.sha256[:12]}…)"]
    lines += [f"  note: {n}" for n in g.notes]
    ax = g.axis
    lines.append(f"  axis: through ({', '.join(f'{v:.2f}' for v in ax['point'])}) along "
                 f"({', '.join(f'{v:.4f}' for v in ax['direction'])})"
                 + ("" if g.axis_exact else " (approximate)"))
    lines.append(f"  rise {g.rise:.3f} ± {g.rise_sd:.3f} Å, twist {g.twist:+.5f} ± "
                 f"{g.twist_sd:.5f} rad ({_deg(g.twist)} per layer, {hand})")
    pf = (f", pf_rotation {g.pf_rotation:+.4f} rad ({_deg(g.pf_rotation)}), pf_rise "
          f"{g.pf_rise:.3f} Å" if g.protofilaments > 1 else "")
    lines.append(f"  protofilaments {g.protofilaments}{pf}; layers {g.layers} "
                 f"({' | '.join(' '.join(q) for q in g.layer_chains)})")
    if g.rungs > 1:  # docs/guide/structures.md#beta-solenoids
        lines.append(f"  β-solenoid, {g.rungs} rungs per molecule, one molecule per {g.rise:.1f} Å "
                     f"(rungs {g.rung_rise:.2f} ± {g.rung_rise_sd:.2f} Å apart along the axis); "
                     "a layer is a molecule: one domain and one anchor each")
    lines.append(f"  core residues {core_text(g)}; outline {len(g.core_outline)} points")
    for a in g.anchors:
        tail = (f", tail {a['tail_residues'][0]}-{a['tail_residues'][1]} (linker)"
                if a["tail_residues"] else "")
        lines.append(f"  anchor pf {a['protofilament']}: {a['chain']} {a['residue_name']}"
                     f"{a['residue']} at r {a['radius']:.2f} Å, depth {a['depth']:.1f} Å"
                     f"{' BURIED' if a['buried'] else ''}{tail}")
    way = g.exit or {}
    if way:  # protofilament 0's anchor to the surface (docs/model/buried-terminus.md#method)
        lines.append(f"  exit pf 0: {way['length']:.2f} Å to the surface, CA {way['depth']:.2f} Å "
                     f"inside it (a {way['bead_radius']:g} Å bead clear of the atoms; "
                     f"layer {way.get('layer')})"
                     if way["found"] else
                     f"  exit pf 0: sealed: no path to the surface for a {way['bead_radius']:g} "
                     f"Å bead clear of the atoms ({way['searched']})")
        if "rule" in way:
            lines.append(f"    by the rule: {way['rule']} (docs/model/buried-terminus.md#rule)")
            lines.append(f"    range over layers and atoms: {X.sensitivity_words(way)}")
    lines += [f"  warning: {w}" for w in g.warnings]
    return lines


def domain_lines(d) -> list:
    lines = [f"domain {d.file} (sha256 {d.sha256[:12]}…): chain {d.chain} residues "
             f"{d.residues[0]}-{d.residues[1]}, {d.atoms} heavy atoms"]
    lines += [f"  note: {n}" for n in d.notes]
    lines.append(f"  rg {d.rg:.2f} Å, globule_diameter {d.globule_diameter:.2f} Å "
                 f"(2·√(5/3)·Rg; largest dimension {d.max_dimension:.1f} Å)")
    if d.shape:
        s = d.shape
        first = "first: it follows the core" if s["joint_terminus"] == "N" else "last: it precedes"
        lines.append(f"  joint: CA of residue {s['joint_residue']} (the domain's {first}), "
                     f"{s['joint_depth']:.2f} Å below the hull, {s['joint_depth_spheres']:.2f} Å "
                     f"below the spheres")
        if "exit_residue" in s:  # a further domain follows: the outgoing linker's point
            lines.append(f"  exit: CA of residue {s['exit_residue']} (the domain's other end, "
                         f"towards the next domain), {s['exit_depth']:.2f} Å below the hull, "
                         f"{s['exit_depth_spheres']:.2f} Å below the spheres; "
                         f"{s['joint_exit_distance']:.1f} Å from the joint")
        lines.append(f"  shapes: hull of {s['hull_atoms']} outer atoms within "
                     f"{s['bounding_radius']:.1f} Å of the centroid; {s['spheres']} covering "
                     f"spheres of {min(s['spheres_radius']):.1f}-{max(s['spheres_radius']):.1f} Å")
    return lines


def segmentation_lines(seg) -> list:
    lines = [f"full-length model {seg.file} (sha256 {seg.sha256[:12]}…): chain {seg.chain} "
             f"residues {seg.residues[0]}-{seg.residues[1]}"
             + (f", fibril core {seg.core[0]}-{seg.core[1]}" if seg.core else
                " (no --fibril: the core is not known)")]
    lines += [f"  note: {n}" for n in seg.notes]
    for d in seg.domains:
        lines.append(f"  domain {d['first']}-{d['last']} ({d['residues']} residues"
                     + (f", {d['side']} side" if d["side"] else "")
                     + f"): pLDDT {d['plddt_mean']:.1f}, diameter {d['diameter']:.1f} Å")
    if not seg.domains:
        lines.append("  no folded domain (pLDDT >= 70 over at least 40 residues) outside the core")
    for k in seg.linkers:
        lines.append(f"  linker {k['first']}-{k['last']}: {k['length']} residues "
                     f"({k['between'][0]} to {k['between'][1]})")
    return lines


def text(fibril=None, domain=None, values=None, segmentation=None, more_domains=()) -> str:
    lines = []
    if fibril is not None:
        lines += fibril_lines(fibril)
    if segmentation is not None:
        lines += segmentation_lines(segmentation)
    for n, d in enumerate([domain, *more_domains] if domain is not None else []):
        lines += [("" if not more_domains else f"[{n + 1}] ") + line if k == 0 else line
                  for k, line in enumerate(domain_lines(d))]
    if fibril is not None and domain is not None:
        from .mapping import linker_source
        lines.append(f"linker: {linker_source(fibril, domain, explicit=False)}")
    if values:
        shown = {k: (f"{len(v)} points" if k == "core_outline" else v) for k, v in values.items()}
        lines.append("model values: " + ", ".join(f"{k}={v}" for k, v in shown.items()))
    return "\n".join(lines)
