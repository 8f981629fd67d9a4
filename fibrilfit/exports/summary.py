"""The short human summary of a result, with the verdict worded as honestly as it is known."""
from __future__ import annotations


def percent(fraction: float) -> str:
    """A fraction as a percentage with one decimal, as every summary, panel and report shows it."""
    text = f"{100 * fraction:.1f} %"
    return "0.0 %" if text == "-0.0 %" else text  # a bond compressed by 0.001 % is not "-0.0"


def summary(r: dict, quiet: bool = False) -> str:
    """The summary a run prints: the model, the bake, the verdict and what it proves."""
    head = "\n".join([_head_line(r), *_case_lines(r.get("case"))])
    if "verdict" not in r:
        return head + f"\nstopped after {r['stage']}; no verdict"
    if quiet:
        return _quiet_line(r)
    return "\n".join([head, _bake_line(r), *_clash_lines(r), *_linker_lines(r),
                      *_periodic_lines(r), *[f"warning: {w}" for w in r.get("warnings", [])],
                      *_envelope_lines(r), *_export_lines(r), _answer_line(r)])


def _quiet_line(r: dict) -> str:
    """--quiet: the verdict alone."""
    return f"verdict: {r['verdict']}" + (
        "  (accommodated)" if r["accommodated"] else "  (not accommodated)")


def _head_line(r: dict) -> str:
    p = r["params"]
    size = (f"periodic cell of {p['periodic']} layers (an infinite fibril)" if p.get("periodic")
            else f"{p['layers']} layers")
    return (f"FibrilFit {r['fibrilfit_version']} on Blender {r['blender_version']}: "
            f"{size}"
            + (f" × {p['protofilaments']} protofilaments" if p.get("protofilaments", 1) > 1
               else "")
            + f", linker {p['linker']}, globule {p['globule_diameter']:g} Å, "
            f"seed {r['seed']}")


def _bake_line(r: dict) -> str:
    p, t = r["params"], r["timings_s"]
    g = ", ".join(f"{v:+.3f}" for v in r["gravity"])
    settled = (f" (settled: every body under {p['settle_speed']:g} Å/frame for "
               f"{p['settle_frames']} frames)" if r.get("settled_at") else "")
    return (f"gravity ({g}); baked {r['frames_simulated']} frames{settled}; "
            f"build {t['build']:.2f} s, bake {t['bake']:.2f} s, check {t['check']:.2f} s")


def _clash_lines(r: dict) -> list[str]:
    p = r["params"]
    lines = [
        f"verdict: {r['verdict']} at frame {r['frames_simulated']}: {r['intersecting_faces']} "
        f"intersecting faces, {len(r['clashing_pairs'])} clashing globule pairs"
        + (f" (deepest overlap {r['max_overlap']:.2f} Å)" if r.get("clashing_pairs") else "")
        + (f" in layers {r['scored_layers'][0]}-{r['scored_layers'][1]}"
           if p.get("score_layers") else "")]
    if r.get("grazing_pairs"):
        n, band = len(r["grazing_pairs"]), r["sphere_check"]["tolerance"]
        if n == len(r["clashing_pairs"]):
            lines.append(f"  all of them only graze (overlap at most {band:.2f} Å, the globule "
                         f"mesh's resolution): this verdict can flip from frame to frame")
        else:
            lines.append(f"  {n} of them only graze (overlap at most {band:.2f} Å, the globule "
                         f"mesh's resolution)")
    return lines


def _linker_lines(r: dict) -> list[str]:
    lines = [
        f"linker: worst bond stretch {percent(r['max_bond_stretch'])} at the end "
        f"({'intact' if r['linker_intact'] else 'STRETCHED'}, tolerance "
        f"{percent(r['params']['stretch_tolerance'])})"]
    if r.get("max_bond_stretch_bake") is not None:
        after = r.get("max_bond_stretch_after_push")
        lines.append(
            f"  during the bake: {percent(r['max_bond_stretch_bake'])} at worst (frame "
            f"{r['max_bond_stretch_bake_frame']}, the push-apart of the overlapping start); "
            + (f"{percent(after)} at worst once back within tolerance (frame "
               f"{r['push_apart_end_frame']}); " if after is not None else
               "never back within tolerance; ")
            + f"over tolerance in {r['frames_over_tolerance']} of {r['frames_simulated']} frames")
    return lines


def _periodic_lines(r: dict) -> list[str]:
    if not r.get("periodic"):
        return []
    per, lag = r["periodic"], r.get("image_lag") or {}
    return [
        f"periodic: {per['images']['moving']} moving and {per['images']['static']} static "
        f"images in cells {', '.join(f'{m:+d}' for m in per['images']['cells'])}; "
        f"pairs counted once, with images up to {per['check_cells']} cells above "
        f"(globule j + m·{per['chains']} is globule j's image in cell m); frames are scene "
        f"frames, {per.get('scene_frames_per_frame', 1)} per frame of the model"
        + ("; gravity: its axial part only (the screw turns the rest)"
           if per.get("gravity") == "axial" else "")
        + (f"; images lag their originals by {lag['last']:.2f} Å at the last frame"
           if lag else "")]


def _envelope_lines(r: dict) -> list[str]:
    """Where the domains ended up (analysis/envelope.py), when there are any."""
    env = r.get("envelope") or {}
    if not env.get("n"):
        return []
    return [f"envelope: domain centres {env['r_median']:.1f} Å from the axis (median; 95 % "
            f"within {env['r95']:.1f} Å), outer diameter {env['outer_diameter']:.0f} Å"]


def _answer_line(r: dict) -> str:
    if r["accommodated"]:
        return ("accommodated: yes. This relaxation found a clash-free layout with intact "
                "linkers, which proves that one exists for this model.")
    if r["verdict"] == "successful":
        return ("accommodated: no. No globules intersect, but only because the linkers "
                "stretched beyond tolerance: the domains do not fit at this length.")
    return ("accommodated: no. This relaxation ended with clashes"
            + ("" if r["linker_intact"] else ", even with linkers stretched")
            + ". That does not prove "
            "that no clash-free layout exists: one bake is one random search, not an "
            "exhaustive one. Sweep seeds to see how often one is found.")


def _case_lines(case: dict | None) -> list[str]:
    """With --case: which case, and which of its numbers are estimates or were overridden."""
    if not case:
        return []
    name = case.get("name") or case.get("file", "")
    ref = case.get("doi") or case.get("pdb")
    line = f"case: {name}" + (f" ({ref})" if ref else "")
    if case.get("estimates"):
        line += f"; estimates: {', '.join(case['estimates'])}"
    if case.get("overridden"):
        line += f"; set on the command line: {', '.join(case['overridden'])}"
    return [line]


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
