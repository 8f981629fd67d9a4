"""The short human summary of a result, with the verdict worded as honestly as it is known."""
from __future__ import annotations


def _pct(x: float) -> str:
    return f"{100 * x:.1f} %"


def summary(r: dict, quiet: bool = False) -> str:
    p = r["params"]
    head = (f"FibrilFit {r['fibrilfit_version']} on Blender {r['blender_version']}: "
            f"{p['layers']} layers, linker {p['linker']}, globule {p['globule_diameter']:g} Å, "
            f"seed {r['seed']}")
    if "verdict" not in r:
        return head + f"\nstopped after {r['stage']}; no verdict"
    verdict = f"verdict: {r['verdict']}"
    if quiet:
        return verdict + ("  (accommodated)" if r["accommodated"] else "  (not accommodated)")
    g = ", ".join(f"{v:+.3f}" for v in r["gravity"])
    t = r["timings_s"]
    settled = f", at rest from frame {r['settled_at']}" if r.get("settled_at") else ""
    lines = [
        head,
        f"gravity ({g}); baked {r['frames_simulated']} frames{settled}; "
        f"build {t['build']:.2f} s, bake {t['bake']:.2f} s, check {t['check']:.2f} s",
        f"{verdict}: {r['intersecting_faces']} intersecting faces, "
        f"{len(r['clashing_pairs'])} clashing globule pairs"
        + (f" in layers {r['scored_layers'][0]}-{r['scored_layers'][1]}"
           if p.get("score_exclude") else ""),
        f"linker: worst bond stretch {_pct(r['max_bond_stretch'])} at the end "
        f"({'intact' if r['linker_intact'] else 'STRETCHED'}, tolerance "
        f"{_pct(p['stretch_tolerance'])}); {_pct(r['max_bond_stretch_bake'])} at worst during the bake",
    ]
    lines += [f"warning: {w}" for w in r.get("warnings", [])]
    lines += _export_lines(r)
    if r["accommodated"]:
        lines.append("accommodated: yes. This relaxation found a clash-free layout with intact "
                     "linkers, so one exists for this model.")
    elif r["verdict"] == "successful":
        lines.append("accommodated: no. No globules intersect, but only because the linkers "
                     "stretched beyond tolerance: the domains do not fit at this length.")
    else:
        lines.append("accommodated: no. This relaxation ended with clashes. One random draw "
                     "cannot prove that no clash-free layout exists; sweep seeds for a fraction.")
    return "\n".join(lines)


def _export_lines(r: dict) -> list[str]:
    """One line per picture or structure written (exports/)."""
    out = []
    pdb, png = r.get("pdb"), r.get("render")
    if pdb and "error" not in pdb:
        n = len(pdb["frames"])
        out.append(f"pdb: {pdb['path']} ({pdb['atoms_per_model']} atoms"
                   + (f" x {n} models, frames {pdb['frames'][0]}-{pdb['frames'][-1]})" if n > 1
                      else f", frame {pdb['frames'][0]})"))
    if png and "error" not in png:
        how = (f"cycles, {png['samples']} samples" + (", denoised" if png["denoiser"] else "")
               if png["engine"] == "cycles" else png["engine"])
        out.append(f"render: {png['path']} ({png['width']}x{png['height']}, {how}, "
                   f"{png['seconds']:.1f} s)")
    return out
