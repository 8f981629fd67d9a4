"""The printed result: the lines a run prints, with the verdict worded as honestly as it is known
(docs/reference/glossary.md#printed-result)."""
from __future__ import annotations

import math

from ..model.helix import handedness
from ..model.searches import DEFAULT_RESTARTS
from . import ensemble_words
from .span_words import end_to_end
from ..model.answer import BORDERLINE, BORDERLINE_STRETCH, FITS, NO_EXIT, of_result


def percent(fraction: float) -> str:
    """A fraction as a percentage with one decimal, as the printed result, the panel and the
    report show it."""
    text = f"{100 * fraction:.1f} %"
    return "0.0 %" if text == "-0.0 %" else text  # a bond compressed by 0.001 % is not "-0.0"


def count(n: int, noun: str) -> str:
    """"1 residue", "8 residues", "1 restart": a number with its noun, singular for one (every
    printed word that counts something: the report page, the sidebar, the gallery's table)."""
    return f"{n} {noun}{'' if n == 1 else 's'}"


def text(r: dict, quiet: bool = False, files: dict | None = None) -> str:
    """The lines a run prints: the model and its sources, the bake, the verdict, the answer
    and every file written (`files`: option -> path, as the command line checked them)."""
    head = "\n".join([_head_line(r), *_model_lines(r), *_case_lines(r.get("case"))])
    if "verdict" not in r:
        return head + f"\nstopped after {r['stage']}; no verdict" + "".join(
            f"\n{line}" for line in _file_lines(r, files))
    if quiet:
        return _quiet_line(r)
    if r.get("answer") == NO_EXIT:  # settled without a bake (model/terminus.py)
        return "\n".join([head, *_exit_lines(r), *_file_lines(r, files),
                          f"answer: no exit. {r['no_exit'][0].upper()}{r['no_exit'][1:]}: no "
                          f"layout can exist (nothing was simulated; "
                          f"docs/model/buried-terminus.md#model)."])
    return "\n".join([head, *_exit_lines(r), _bake_line(r), *_inflate_lines(r), *_clash_lines(r),
                      *_linker_lines(r), *_periodic_lines(r),
                      *[f"warning: {w}" for w in r.get("warnings", [])],
                      *_envelope_lines(r), *_bound_lines(r), *_export_lines(r),
                      *_file_lines(r, files),
                      _answer_line(r)])


def _quiet_line(r: dict) -> str:
    """--quiet: the verdict alone."""
    return f"verdict: {r['verdict']}" + (
        "  (accommodated)" if r["accommodated"] else "  (not accommodated)") + (
        f"; answer: {r['answer']}" if r.get("answer") else "")


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


def anchor_radius(p: dict) -> float:
    """Protofilament 0's anchor's distance from the axis (params.Params.anchor_x), Å."""
    if p.get("anchor") is not None:
        return math.hypot(*p["anchor"])
    return p["slab"][0] / 2.0 + p["residue_radius"]


def _model_lines(r: dict) -> list[str]:
    """The model up front (issue #23): rise, twist in degrees with its hand, protofilaments,
    anchor radius, linker, domain size and protocol, then where the values came from."""
    p, src = r["params"], r.get("sources") or {}
    k = p.get("protofilaments", 1)
    pf = ""
    if k > 1:
        turn = (2 * math.pi / k) if p.get("pf_rotation") is None else p["pf_rotation"]
        pf = f" (each turned {math.degrees(turn):.1f}° and raised {p.get('pf_rise', 0):g} Å)"
        if p.get("pf_turns"):  # three or more, each at its own measured turn
            pf = " (turned " + ", ".join(f"{math.degrees(a):.1f}°" for a, _ in p["pf_turns"]) + \
                 " and raised " + ", ".join(f"{b:g}" for _, b in p["pf_turns"]) + " Å)"
    detail = lambda name: (f" (from {src[name]})" if name in src  # noqa: E731
                           and src[name] not in ("default", "option", "case") else "")
    core = ("the slab's box" if p.get("core_outline") is None
            else f"a {len(p['core_outline'])}-point outline")
    lines = [f"model: rise {p['rise']:g} Å, twist {math.degrees(p['twist']):+.3f}° per layer "
             f"({p['twist']:+.5g} rad, {handedness(p['twist'])}), {k} protofilament"
             f"{'s' if k > 1 else ''}{pf}, core {core}, anchor {anchor_radius(p):.2f} Å from "
             f"the axis, linker {p['linker']} residues{detail('linker')}, globule "
             f"{p['globule_diameter']:g} Å{detail('globule_diameter')}, protocol "
             f"{p['protocol']}"]
    occ = r.get("occupancy")
    if occ:  # a mixed fibril (docs/model/occupancy.md#what-fits-at-f-means)
        lines.append(f"occupancy: {occ['decorated']} of {occ['subunits']} subunits "
                     f"({percent(occ['fraction'])}) carry the domain ({occ['pattern']}"
                     + (f", drawn with seed {occ['seed']}" if "seed" in occ else "")
                     + f"; bare tail {occ['bare_tail']} residues); the answer speaks of this "
                     f"pattern on {occ['on']}")
        b = occ.get("second_domain")
        if b:  # a hetero-amyloid (docs/model/occupancy.md#hetero)
            lines.append(f"second domain: B, {b['diameter']:g} Å (a sphere) on a {b['linker']}-"
                         f"residue linker, on {len(b['subunits'])} of those subunits (pattern "
                         f"{occ['pattern_layers']!r}); the others carry A, "
                         f"{p['globule_diameter']:g} Å")
    if src:
        lines.append("sources: " + sources_text(src))
    return lines


def sources_text(sources: dict) -> str:
    """Which parameters came from where, grouped: files first, then options and the case; the
    rest are defaults (every source in the JSON's `sources`)."""
    groups: dict[str, list[str]] = {}
    for name, where in sources.items():
        if where == "default" or where.startswith("default"):
            continue
        key = where if where in ("option", "case") else where.split(" ")[0].rstrip(":")
        groups.setdefault(key, []).append(name)
    order = sorted(groups, key=lambda g: ({"option": 1, "case": 2}.get(g, 0), g))
    parts = [f"{', '.join(groups[g])} from {'the ' if g == 'case' else ''}"
             f"{g + 's' if g == 'option' else g}" for g in order]
    return "; ".join(parts + ["the rest defaults"]) if parts else "every value a default"


def _frames(r: dict, n: int) -> int:
    """Scene frames in the model's frames (a periodic cell bakes several scene frames per
    frame: docs/model/periodic-cell.md#periodic-cell)."""
    per = (r.get("periodic") or {}).get("scene_frames_per_frame", 1)
    return -(-n // per)


def _bake_line(r: dict) -> str:
    p, t = r["params"], r["timings_s"]
    g = ", ".join(f"{v:+.3f}" for v in r["gravity"])
    n = r["frames_simulated"]
    per = (r.get("periodic") or {}).get("scene_frames_per_frame", 1)
    baked = f"baked {_frames(r, n)} frames" + (
        f" ({n} scene frames, {per} per frame for the images)" if per > 1 else "")
    if r.get("settled_at"):
        settled = (f" (settled: every body under {p['settle_speed']:g} Å/frame for "
                   f"{p['settle_frames']} frames)")
    elif p.get("settle") and p.get("protocol") != "inflate" and not r.get("cancelled"):
        settled = (f"; not settled within {p['frames']} frames (some body still moved "
                   f"{p['settle_speed']:g} Å/frame or more; --frames sets the cap)")
    else:
        settled = ""
    return (f"gravity ({g}); {baked}{settled}; "
            f"build {t['build']:.2f} s, bake {t['bake']:.2f} s, check {t['check']:.2f} s")


def _inflate_lines(r: dict) -> list[str]:
    """inflate: each grow-and-hold cycle, judged at which frame (counted from frame 1 of the
    bake, as every frame of the printed result)."""
    cycles = (r.get("inflate") or {}).get("cycles") or []
    if not cycles:
        return []
    p = r["params"]
    said = [f"cycle {c['cycle']} judged at frame {c['judged_at']}: "
            + ("accommodated" if c["accommodated"] else
               f"{c['clashing_pairs']} clashing pairs, stretch {percent(c['max_bond_stretch'])}")
            for c in cycles]
    if cycles[-1]["accommodated"]:
        left = ""
    elif r["inflate"].get("clear_miss"):  # docs/model/search.md#clear-miss
        left = f"; a clear miss: stopped after {len(cycles)} of {1 + p['regrow_cycles']} cycles"
    elif len(cycles) >= 1 + p["regrow_cycles"]:
        left = f"; gave up after {len(cycles)} of {1 + p['regrow_cycles']} cycles"
    else:
        left = ""
    return [f"inflate: globules grown from {r['inflate']['start_scale']:g} of full size over "
            f"{p['grow_frames']} frames; " + "; ".join(said) + left]


def _clash_lines(r: dict) -> list[str]:
    p = r["params"]
    lines = [
        f"verdict: {r['verdict']} at frame {_frames(r, r['frames_simulated'])}: "
        f"{r['intersecting_faces']} "
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


def _exit_lines(r: dict) -> list[str]:
    """A measured anchor's exit in one line (the result's `exit`), when there is one; with
    interface termini a second line: each protofilament's own exit."""
    way = r.get("exit")
    if not way:
        return []
    own = [] if way.get("pf_residues") is None else [
        f"exit per protofilament (each from its own terminus, "
        f"docs/guide/structures.md#interface-termini): "
        f"{', '.join(map(str, way['pf_residues']))} residue(s) spent; every chain simulates "
        f"the smallest free linker, {way['free_linker']}"]
    return _first_exit_line(way) + own


def _first_exit_line(way: dict) -> list[str]:
    """Protofilament 0's exit in one line."""
    if not way.get("found"):
        return [f"exit: none: no path from the anchor to the core's surface clears the core's "
                f"atoms ({way['clearance']}); depth {way['depth']:.1f} Å"] + _exit_range(way)
    if not way["residues"]:
        return [f"exit: the anchor is on the surface ({way['length']:.1f} Å from its CA out of "
                f"the outline): no residues spent"]
    left = (f"the free linker starts there with {way['free_linker']}" if way["free_linker"] >= 1
            else "the linker ends before it")
    return [f"exit: {way['residues']} linker residue(s) spent from the buried anchor to the "
            f"surface ({way['length']:.1f} Å path, anchor {way['depth']:.1f} Å deep, clearance "
            f"{way['clearance']}); {left}"] + _exit_range(way)


def _exit_range(way: dict) -> list[str]:
    """The rule that decided the exit and its range over layers and atoms, when measured so."""
    from ..structure.exit import sensitivity_words
    if not way.get("sensitivity"):
        return []
    return [f"  by the rule: {way['rule']}; range: {sensitivity_words(way)} "
            f"(docs/model/buried-terminus.md#rule)"]


def _linker_lines(r: dict) -> list[str]:
    lines = [
        f"linker: worst bond stretch {percent(r['max_bond_stretch'])} at the end "
        f"({'intact' if r['linker_intact'] else 'STRETCHED'}, tolerance "
        f"{percent(r['params']['stretch_tolerance'])})"]
    if r.get("max_bond_stretch_bake") is not None and r.get("inflate"):
        intact = r.get("intact_from_frame")
        lines.append(
            f"  during the bake: {percent(r['max_bond_stretch_bake'])} at worst (frame "
            f"{r['max_bond_stretch_bake_frame']}); "
            + (f"within tolerance from frame {intact} on; " if intact else
               "over tolerance at the end; ")
            + f"over tolerance in {r['frames_over_tolerance']} of {r['frames_simulated']} frames")
    elif r.get("max_bond_stretch_bake") is not None:
        after = r.get("max_bond_stretch_after_push")
        lines.append(
            f"  during the bake: {percent(r['max_bond_stretch_bake'])} at worst (frame "
            f"{r['max_bond_stretch_bake_frame']}, the push-apart of the overlapping start); "
            + (f"{percent(after)} at worst once back within tolerance (frame "
               f"{r['push_apart_end_frame']}); " if after is not None else
               "never back within tolerance; ")
            + f"over tolerance in {r['frames_over_tolerance']} of {r['frames_simulated']} frames")
    if r.get("linker_stretch"):
        lines.append(f"  {end_to_end(r['linker_stretch'])}")
    return lines


def _periodic_lines(r: dict) -> list[str]:
    if not r.get("periodic"):
        return []
    per, lag = r["periodic"], r.get("image_lag") or {}
    return [
        f"periodic: {per['images']['moving']} moving and {per['images']['static']} static "
        f"images in cells {', '.join(f'{m:+d}' for m in per['images']['cells'])}; "
        f"pairs counted once, with images up to {per['check_cells']} cells above "
        f"(globule j + m·{per['chains']} is globule j's image in cell m); the linker's frames "
        f"above are scene frames, {per.get('scene_frames_per_frame', 1)} per frame of the model"
        + ("; gravity: its axial part only (the screw turns the rest)"
           if per.get("gravity") == "axial" else "")
        + (f"; images lag their originals by {lag['last']:.2f} Å at the last frame"
           if lag else "")]


def _envelope_lines(r: dict) -> list[str]:
    """Where the domains ended up (analysis/envelope.py), when there are any; with an
    ensemble (run --ensemble), its outer diameter and width first, the layout's labelled."""
    env = r.get("envelope") or {}
    if not env.get("n"):
        return ensemble_words.lines(r.get("ensemble"))
    sampled = (r.get("ensemble") or {}).get("sampled")
    return [*ensemble_words.lines(r.get("ensemble")),
            f"envelope{' (this layout)' if sampled else ''}: domain centres {env['r_median']:.1f} Å from the axis (median; 95 % "
            f"within {env['r95']:.1f} Å), outer diameter {env['outer_diameter']:.0f} Å"]


NEXT = (f"to know whether the domains fit, run report (P(fit) over {DEFAULT_RESTARTS} restarts "
        f"of inflate, the stronger search, and the shortest linker that fits), "
        f"--protocol inflate --restarts {DEFAULT_RESTARTS}, or minimal-linker")


def _answer_line(r: dict) -> str:
    """The answer in words: only a layout found says "fits"; a run at the criterion says
    borderline; one that found none says so, with its numbers and what to run next
    (docs/model/verdict.md#answer)."""
    word = of_result(r)
    stretch, tol = r["max_bond_stretch"], r["params"]["stretch_tolerance"]
    n, graze = len(r.get("clashing_pairs") or []), len(r.get("grazing_pairs") or [])
    numbers = f"worst linker stretch {percent(stretch)}, tolerance {percent(tol)}"
    band = f"{100 * BORDERLINE_STRETCH:g} point"
    if word == FITS:
        return (f"answer: fits. This relaxation found a clash-free layout with intact linkers "
                f"({numbers}), which proves that one exists for this model.")
    if word == BORDERLINE and r["accommodated"]:
        return (f"answer: borderline (fits by the criterion). This relaxation found a clash-free "
                f"layout, but its worst linker stretch ({percent(stretch)}) is within {band} of "
                f"the {percent(tol)} tolerance; {NEXT}.")
    if word == BORDERLINE:
        what = (f"Its {n} clashing pairs only graze (overlap at most "
                f"{r['sphere_check']['tolerance']:.2f} Å, the globule mesh's resolution)"
                if n else "No globules clash")
        return (f"answer: borderline (no layout found in this run by the criterion). {what}; "
                f"{numbers}, within {band} of it. One relaxation is one random search; {NEXT}.")
    why = []
    if n:
        why.append(f"{n} globule pairs clash (deepest overlap {r['max_overlap']:.2f} Å"
                   + (f"; {graze} of them only graze" if graze else "") + ")")
    if not r["linker_intact"]:
        why.append(f"the linkers stretched beyond tolerance ({numbers})")
    return (f"answer: no layout found in this run: {' and '.join(why) or 'no verdict'}. One "
            f"relaxation is one random search: it cannot show that no layout exists; {NEXT}.")


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


FILE_LABELS = (("json", "result"), ("blend", "blend file"), ("pdb", "structure"),
               ("render", "picture"), ("movie", "movie"), ("envelope_plot", "envelope plot"),
               ("save_case", "case"))


def _file_lines(r: dict, files: dict | None) -> list[str]:
    """Every file the run wrote, one line (a failed one is named by its error instead)."""
    if not files:
        return []
    wrote = [f"{label} {files[key]}" for key, label in FILE_LABELS
             if key in files and str(files[key]) != "-"
             and "error" not in (r.get(key) if isinstance(r.get(key), dict) else {})]
    return [f"wrote: {', '.join(wrote)}"] if wrote else []


def bound_phrase(b: dict) -> str:
    """The bracket's proven side in words (docs/model/bound.md#derivation)."""
    if b["impossible_below"] <= 1:
        return f"the geometry alone rules out no linker (excluded volume over {b['over']})"
    return (f"no layout can exist below {b['impossible_below']} residues (proof: excluded "
            f"volume over {b['over']})")


def _bound_lines(r: dict) -> list[str]:
    b = r.get("bound")
    if not b:
        return []
    # a mixed fibril: the bound at its fraction, and the bracket on the fraction at this linker
    at = (f" at {100 * b['fraction']:.4g} % decorated" if "fraction" in b else "")
    on_fraction = ([f"bound on the fraction at linker {b['linker']}: {b['fraction_bracket']}"]
                   if "fraction_bracket" in b else [])
    if b["impossible_below"] <= 1:
        return [f"bound{at}: {bound_phrase(b)}"] + on_fraction
    where = ("this linker is below it: settled, impossible" if b.get("below")
             else "this linker is at or above it")
    return [f"bound{at}: {bound_phrase(b)}; {where}"] + on_fraction
