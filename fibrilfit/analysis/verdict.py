"""The verdict at the current frame: clashes by both checks, linker stretch, accommodation.

Two of a result's three outcome words are computed here (docs/reference/glossary.md#outcome-words):
`verdict` is the tutorial's mesh test alone ("intersection" when BVH faces of scored globules
cross, else "successful"; nothing about linkers); `accommodated` is the run's yes or no: verdict
successful and the worst scored bond within the stretch tolerance. The third, `answer`
(model/answer.py), words `accommodated` with its margin: fits, borderline or no layout found.
"""
from __future__ import annotations

import numpy as np

from ..model import bound, gravity, helix, hetero, occupancy, start_layout
from ..model.answer import answer
from ..model.judgement import TOUCH_SLACK, accommodated, compare_checks
from ..builders.readback import MatrixReader
from ..builders.scene import LAYER, PROTOFILAMENT
from .clashes import bounding_radius, bvh_clashes, reach_from_axis, sphere_band
from .exact import EXACT_CHECKS
from .envelope import envelope
from .leaks import members_inside_core
from ..builders.exit_path import model_chain_paths
from .stretch import bond_ends, ends_stretch, linker_spans, linker_stretch_block



def _chain_reader(model) -> MatrixReader:
    return MatrixReader([ob for members in model.chain for ob in members], model.root.children)


def chain_positions(model) -> np.ndarray:
    """World centres of every chain member now, shape (chains, linker + 1, 3)."""
    return _chain_reader(model).positions().reshape(len(model.chain), -1, 3)


def chain_matrices(model) -> np.ndarray:
    """World matrices of every chain member now, shape (chains, linker + 1, 4, 4)."""
    return _chain_reader(model).matrices().reshape(len(model.chain), -1, 4, 4)


def world_matrices(objects, collections=()) -> np.ndarray:
    """(n, 4, 4) world matrices, read with foreach_get from `collections` if they hold them all."""
    return MatrixReader(objects, collections).matrices()


def scored_range(p) -> tuple[int, int]:
    """Layers [lo, hi) that count towards the verdict: all but `score_layers` at each end."""
    return p.score_layers, p.layers - p.score_layers


def scored_chains(p) -> np.ndarray:
    """bool per chain of the model (a mixed fibril: its decorated subunits') whether its layer
    is scored."""
    lo, hi = scored_range(p)
    layer, _ = occupancy.model_chain_layers(p)
    return (layer >= lo) & (layer < hi)


def matrices_with_images(p, matrices: np.ndarray, mesh_radius: float) -> tuple[np.ndarray, int]:
    """The cell's globule matrices followed by their images S^m for m = 1 .. cells, each m as a
    block, so that globule j of image m has index j + m·n (its chain in the infinite fibril).

    Only m ≥ 1: a pair of the infinite fibril is one cell globule with a cell globule or with
    an image above; the same pair seen from below (m < 0) is that pair shifted, counted once.
    `cells` comes from where the globules stand now, so every image that can touch is there.
    """
    cells = helix.check_cells(p, matrices[:, 2, 3], mesh_radius)
    blocks = [matrices] + [helix.apply_matrices(p, m, matrices) for m in range(1, cells + 1)]
    return np.concatenate(blocks), cells


def check_model(model) -> dict:
    """Judge the model as it stands in the scene now (call at the last baked frame).

    Layers outside the scored range are still simulated and still collide; only pairs with at
    least one scored globule count, and only scored layers' linkers. A periodic cell counts
    every pair of the infinite fibril once, recomputing the images from the originals now.
    """
    p = model.params
    lo, hi = scored_range(p)
    kept = scored_chains(p)
    matrices = chain_matrices(model)
    positions = matrices[..., :3, 3]
    clashes = _clash_checks(model)
    n, scored, clashing = clashes["n"], clashes["scored"], clashes["clashing"]
    warnings = list(clashes["warnings"])
    bonds = bond_ends(p, matrices[kept], hetero.rest_lengths_by_chain(p)[kept])
    stretch = ends_stretch(*bonds)
    max_stretch = float(stretch.max()) if stretch.size else 0.0
    domains = len(p.domains)
    chain_clash, layer_clash = _clashes_by_chain_and_layer(p, clashing, scored[:n:domains], lo,
                                                           hi, domains)
    verdict = "intersection" if clashes["faces"] > 0 else "successful"
    intact = max_stretch <= p.stretch_tolerance
    tails = (tail_clashes(model, clashes["centres"], np.repeat(kept, domains)) if model.tails
             else None)  # a mixed fibril's bare tails against the decorated domains
    periodic = {"periodic": periodic_block(model, clashes["cells"])} if p.periodic else {}
    chains = _chain_blocks(p, clashing, chain_clash, n, domains)
    if domains > 1:
        chains.update(_domain_blocks(p, clashing, clashes["centres"], scored[:n],
                                     clashes["reach"]))
    warnings += _cell_warnings(p)
    if p.core_outline is not None:  # (the tutorial's box core: no key, its JSON as before)
        chains["inside_core"] = members_inside_core(p, positions)
        if chains["inside_core"]:
            warnings.append(f"{len(chains['inside_core'])} chain member(s) inside a core "
                            f"([chain, member]: {chains['inside_core'][:5]})")
    # the bound's third assumption, measured on this layout (docs/model/bound.md#assumptions)
    entry = bound.core_entry(p, matrices[kept], (hetero.globule_radii_by_chain(p)[kept]
                                                 / p.globule_radius)
                             if occupancy.is_hetero(p) else None)
    if entry > bound.CORE_ENTRY:
        warnings.append(f"a domain enters the core by {entry:.2f} Å, more than the "
                        f"{bound.CORE_ENTRY} Å the linker bound assumes: this layout is not one "
                        f"the bound speaks of")
    centres = clashes["centres"]
    reach = None if clashes["reach"] is None else clashes["reach"][scored[:n]]
    if occupancy.is_hetero(p):  # each globule's farthest point from the axis: A's or B's
        reach = (np.hypot(centres[:, 0], centres[:, 1])
                 + hetero.globule_radii_by_chain(p))[scored[:n]]
    overall = chains.pop("envelope", None) or envelope(centres[scored[:n]], p.globule_radius,
                                                       reach)
    return {
        "verdict": verdict,
        "intersecting_faces": clashes["faces"],
        "clashing_pairs": clashing,
        "max_overlap": max((d for *_, d in clashing), default=0.0),
        "grazing_pairs": [[i, j, round(d, 4)] for i, j, d in clashes["grazing"]],
        "sphere_check": {
            "verdict": "intersection" if clashes["spheres"] else "successful",
            "clashing_pairs": [[i, j, round(d, 4)] for i, j, d in clashes["spheres"]],
            "tolerance": round(clashes["band"], 4),
            **({"shape": p.shape.name} if p.shape.real else {}),
        },
        "checks_agree": not clashes["disagree"],
        "warnings": warnings,
        "max_bond_stretch": round(max_stretch, 6),
        "core_entry": entry,
        "linker_intact": bool(intact),
        # how far each linker spans of its length (docs/model/linker-integrity.md#linker-span)
        "linker_stretch": linker_stretch(p, kept, *bonds),
        "accommodated": accommodated(verdict, max_stretch, p.stretch_tolerance,
                                     tail_pairs=len((tails or {}).get("pairs", ()))),
        # fits, borderline or no layout found (docs/model/verdict.md#answer)
        "answer": answer(clashing=len(clashing) + len((tails or {}).get("pairs", ())),
                         grazing=len(clashes["grazing"]),
                         max_stretch=max_stretch, tolerance=p.stretch_tolerance),
        "scored_layers": [lo, hi - 1],
        "layer_clashes": layer_clash,
        **chains,
        "globule_centres": np.round(centres, 4).tolist(),
        "envelope": overall,
        **periodic,
        **({"tail_clashes": tails} if tails is not None else {}),
    }


def linker_stretch(p, kept: np.ndarray, starts, ends, rest) -> dict | None:
    """The result's `linker_stretch` over the scored chains (`kept`, bond_ends's `starts`, `ends`
    and `rest` of those): each domain's linker end to end over its contour, a buried anchor's
    exit included from its CA; the worst linker named by its chain, layer and protofilament."""
    paths = [path for path, k in zip(model_chain_paths(p), kept.tolist()) if k]
    exit_start = np.full((len(paths), 3), np.nan)
    exit_length = np.zeros(len(paths))
    for c, path in enumerate(paths):
        if path is not None:  # the fixed path, then on to the anchor's bead
            exit_start[c] = path[0]
            exit_length[c] = (np.linalg.norm(np.diff(path, axis=0), axis=1).sum()
                              + np.linalg.norm(starts[c, 0] - path[-1]))
    block = linker_stretch_block(*linker_spans(p, starts, ends, rest, exit_start, exit_length))
    if block is not None:
        chain = int(np.flatnonzero(kept)[block["worst_linker"]["chain"]])
        layer, pf = occupancy.model_chain_layers(p)
        block["worst_linker"].update(chain=chain, layer=int(layer[chain]),
                                     **({"protofilament": int(pf[chain])}
                                        if p.protofilaments > 1 else {}))
    return block


def tail_clashes(model, centres: np.ndarray, scored: np.ndarray) -> dict:
    """A mixed fibril's bare tails against the scored domains (spheres: param_checks refuses
    bare tails beside real shapes): every (globule, tail bead) overlapping by more than the
    sphere check's tolerance, as [globule, [layer, protofilament, bead], depth]. A domain that
    sits on an undecorated subunit's tail does not fit, as one on another domain does not
    (docs/model/occupancy.md#the-model).

    A periodic cell counts every pair of the infinite fibril once: each cell globule against
    the cell's beads and their images S^m, m = -cells .. cells (below as well as above: a
    globule and a bead are not alike, so a pair seen from below is not one already counted),
    as far as the heights now can reach; an image bead's layer is its original's + m·M."""
    p = model.params
    beads = MatrixReader([ob for t in model.tails for ob in t], model.root.children).positions()
    where = [(t[0][LAYER], t[0].get(PROTOFILAMENT, 0), i)
             for t in model.tails for i in range(len(t))]
    shifts = [0]
    if p.periodic:
        touch = (max(d.radius for d in p.domains) + p.residue_radius) / 2.0
        cells = helix.check_cells(p, np.concatenate([centres[:, 2], beads[:, 2]]), touch)
        shifts = [m for m in range(-cells, cells + 1)]
        beads = np.concatenate([helix.apply_points(p, m, beads) for m in shifts])
        where = [(k + m * p.layers, j, i) for m in shifts for k, j, i in where]
    radius = np.array([d.radius for d in p.domains])[np.arange(len(centres)) % len(p.domains)]
    tol = sphere_band(p.globule_radius)
    depth = (radius[:, None] + p.residue_radius
             - np.linalg.norm(centres[:, None] - beads[None], axis=-1))
    hits = np.argwhere((depth > tol) & scored[:, None])
    return {"tolerance": round(tol, 4), "beads": len(where) // len(shifts),
            "pairs": [[int(g), [int(x) for x in where[b]], round(float(depth[g, b]), 4)]
                      for g, b in hits.tolist()],
            "max_depth": round(float(depth.max()), 4) if depth.size else 0.0,
            **({"cells": len(shifts) // 2} if p.periodic else {})}


def _clash_checks(model) -> dict:
    """Both clash checks over the scored globules (and, in a periodic cell, their images): the
    BVH's intersecting faces and pairs, the shape's exact check's pairs (EXACT_CHECKS), the
    pairs that only graze, and any disagreement beyond the mesh's resolution (warned)."""
    p = model.params
    kept = scored_chains(p)
    globules = model.globules
    domains = len(p.domains)  # globule g: domain g % D of chain g // D
    exact = EXACT_CHECKS[p.shape.name]
    # a real shape: each domain its own mesh (docs/guide/atoms-and-domains.md#shapes-of-several-domains),
    # globule g (and its images, blocks of n) domain g % D; spheres share domain 1's, scaled
    meshes = [globules[d].data for d in range(domains if p.shape.real else 1)]
    band = exact.band(p, meshes)
    matrices = world_matrices(globules, model.root.children)
    n = len(matrices)
    cells = 0
    if p.periodic:
        matrices, cells = matrices_with_images(p, matrices,
                                               bounding_radius(meshes, matrices) + band)
    everything = matrices[:, :3, 3]  # the cell's globules, then their images
    # further domains share the mesh, scaled: its facets' sag scales with them; an image's
    # radius is its original's (blocks of n: globule g is domain g % D)
    radius = (p.globule_radius if domains == 1 else
              np.tile(np.asarray([d.radius for d in p.domains]), len(everything) // domains))
    if occupancy.is_hetero(p):  # A's and B's (one domain a chain), an image its original's
        radius = np.tile(hetero.globule_radii_by_chain(p), len(everything) // n)
    each = np.ndim(radius) > 0
    scored = np.zeros(len(everything), dtype=bool)
    scored[:n] = True if p.periodic else np.repeat(kept, domains)

    def centre_depth(i, j):
        touch = radius[i] + radius[j] if each else 2 * p.globule_radius
        return touch - float(np.linalg.norm(everything[i] - everything[j]))

    kinds = np.arange(len(everything)) % len(meshes)
    faces, bvh_pairs = bvh_clashes(meshes, matrices, keep=scored, kinds=kinds)
    found, band, slack, depth = exact.clashes(p, meshes, matrices, kinds, everything, radius, band)
    depth = depth or centre_depth
    spheres = [(i, j, d) for i, j, d in found if scored[i] or scored[j]]
    sphere_pairs = {(i, j) for i, j, _ in spheres}
    grazing, disagree = compare_checks(bvh_pairs, sphere_pairs, depth, band, slack or TOUCH_SLACK)
    warnings = []
    if disagree:
        warnings.append(
            "checks disagree beyond the mesh's resolution: "
            + ", ".join(f"({i}, {j}) {'BVH' if (i, j) in bvh_pairs else 'spheres'} only, "
                        f"overlap {d:.3f} Å" for i, j, d in disagree[:10]))
    # a real shape: each domain's farthest point from the axis, for the envelope
    reach = reach_from_axis(meshes, kinds[:n], matrices[:n]) if p.shape.real else None
    return {"n": n, "cells": cells, "band": band, "scored": scored, "faces": faces, "reach": reach,
            "centres": everything[:n], "spheres": spheres, "grazing": grazing,
            "disagree": disagree, "warnings": warnings,
            "clashing": [[i, j, round(depth(i, j), 4)] for i, j in sorted(bvh_pairs)]}


def _clashes_by_chain_and_layer(p, clashing, scored, lo: int, hi: int,
                                domains: int = 1) -> tuple[list, list]:
    """Whether each chain's globules clash (None: not scored), and each layer's. `scored`:
    per chain; pair indices are globules (domain g % D of chain g // D)."""
    n = len(scored)
    layer_of, _ = occupancy.model_chain_layers(p)
    chain_clash = [False if s else None for s in scored.tolist()]  # None: not scored
    for i, j, _ in clashing:
        for c in (i // domains % n, j // domains % n):  # a periodic cell: an image's globule
            # is its original's
            if scored[c]:
                chain_clash[c] = True
    layer_clash = [None if not lo <= k < hi else False for k in range(p.layers)]
    for c, hit in enumerate(chain_clash):
        if hit:
            layer_clash[int(layer_of[c])] = True
    return chain_clash, layer_clash


def _chain_blocks(p, clashing, chain_clash, n: int, domains: int = 1) -> dict:
    """With several protofilaments, pair indices are chains (globules: domain g % D of chain
    g // D): each clashing globule's layer and protofilament, and each chain's clash."""
    if p.protofilaments <= 1:
        return {}
    layer_of, pf_of = occupancy.model_chain_layers(p)
    # an image's chain c + m·n is layer (its layer + m·M) of the infinite fibril
    name = lambda g: [int(layer_of[g % n // domains]) + g // n * p.layers,  # noqa: E731
                      int(pf_of[g % n // domains])]
    return {"clashing_chains": [[name(i), name(j), d] for i, j, d in clashing],
            "chain_clashes": chain_clash}


def _domain_blocks(p, clashing, centres, scored, reach=None) -> dict:
    """Several domains per chain: which domain of which chain clashes (layer, protofilament,
    domain from the core outward, 0 first), and the envelope of each domain and of all."""
    domains = len(p.domains)
    layer_of, pf_of = occupancy.model_chain_layers(p)

    n = len(centres)

    def name(g):  # a periodic cell: image m of chain c lies in layer (its layer + m·M)
        c, m = g % n // domains, g // n
        return {"chain": int(c), "layer": int(layer_of[c]) + m * p.layers,
                "protofilament": int(pf_of[c]), "domain": int(g % domains)}

    which = np.arange(len(centres)) % domains
    widest = max(d.radius for d in p.domains)
    if reach is not None:  # real shapes: each body's farthest point
        return {
            "clashing_domains": [[name(i), name(j), d] for i, j, d in clashing],
            "domain_envelopes": [envelope(centres[scored & (which == d.index)], d.radius,
                                          reach[scored & (which == d.index)])
                                 for d in p.domains],
            "envelope": envelope(centres[scored], widest, reach[scored]),
        }
    return {
        "clashing_domains": [[name(i), name(j), d] for i, j, d in clashing],
        "domain_envelopes": [envelope(centres[scored & (which == d.index)], d.radius)
                             for d in p.domains],
        "envelope": envelope(centres[scored], widest),
    }


def _cell_warnings(p) -> list[str]:
    margin = helix.base_cell_layers(p)
    if p.periodic and p.periodic < margin:
        return [f"a cell of {p.periodic} layers is shorter than the measured margin "
                f"({margin}): cells this short were not measured against long "
                f"fibrils (docs/notebook/periodic-cell.md#agreement)"]
    return []


def periodic_block(model, cells: int) -> dict:
    """The JSON's "periodic": the cell, the images simulated, and how far up the check looked."""
    images = model.root.get("fibrilfit_images")
    images = images.to_dict() if hasattr(images, "to_dict") else dict(images or {})
    return {"cell_layers": model.params.periodic,
            "auto_cell_layers": helix.auto_cell_layers(model.params),
            "lattice_rows": start_layout.lattice_columns(model.params), "chains": len(model.chain),
            "images": {"moving": int(images.get("moving", 0)), "static": int(images.get("static", 0)),
                       "cells": [int(m) for m in images.get("cells", [])]},
            "check_cells": cells,
            "scene_frames_per_frame": model.params.image_updates,
            "gravity": "axial" if gravity.axial_gravity(model.params) else "whole"}


def clash_kinds(result: dict) -> tuple[list[int], list[int]]:
    """(deep, grazing): chains to paint as clashing, and chains whose every pair only grazes
    (a BVH pair within the mesh's resolution, `grazing_pairs`: docs/model/verdict.md#two-checks).
    A chain in any deep pair is deep. Both empty unless the verdict is intersection."""
    chains = clashing_layers(result)
    if not chains:
        return [], []
    grazing = {(int(i), int(j)) for i, j, *_ in result.get("grazing_pairs") or []}
    deep_pairs = [[i, j] for i, j, *_ in result.get("clashing_pairs", [])
                  if (int(i), int(j)) not in grazing]
    deep = set(clashing_layers({**result, "clashing_pairs": deep_pairs})) if deep_pairs else set()
    return sorted(deep), sorted(set(chains) - deep)


def clashing_layers(result: dict) -> list[int]:
    """Chains (= layers with one protofilament) to show red: both globules of every pair in
    `clashing_pairs` (the BVH's pairs, so none under a successful verdict), including an end
    layer that clashes with a scored one.
    """
    if result.get("verdict") != "intersection":
        return []
    n = len(result.get("globule_centres") or []) if result.get("periodic") else 0
    cell = (lambda k: k % n) if n else (lambda k: k)  # an image's globule is its original's
    domains = 1 + len(result.get("params", {}).get("domain_diameters") or ())
    return sorted({cell(k) // domains for i, j, *_ in result.get("clashing_pairs", [])
                   for k in (i, j)})
