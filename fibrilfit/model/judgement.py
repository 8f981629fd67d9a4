"""What one judgement of a layout decides, as plain rules over its numbers (no bpy): whether the
run found a layout (`accommodated`), which of the two clash checks' differences are grazing
contacts (`compare_checks`), and whether an inflate run goes on after a miss (`near_fit`,
`clear_miss`).

The verdict (analysis/verdict.py) and the inflate schedule (builders/growth.py) measure the
numbers in Blender and ask these rules; the unit tests and `make mutate` read the same rules
without Blender (docs/contributing/mutation.md). The one-word answer built on them is
model/answer.py's.
"""
from __future__ import annotations

# A BVH pair whose spheres are apart by less than this still counts as touching (float32 mesh
# coordinates, BVH epsilon 1e-5).
TOUCH_SLACK = 1e-4
# With polish_factor > 1 (off by default) a jammed layout is polished (held again with
# polish_factor times the substeps and solver iterations) when it is this near a fit: the usual
# miss in a cell is clash-free or grazing with linkers stretched 6-10 %
# (docs/model/search.md#polish)
POLISH_STRETCH = 3.0  # at most this many times the stretch tolerance
POLISH_OVERLAP = 1.0  # Å: the deepest globule overlap at most this


def accommodated(verdict: str, max_stretch: float, tolerance: float, tail_pairs: int = 0) -> bool:
    """The run's yes or no (docs/reference/glossary.md#outcome-words): the mesh test found no
    crossing ("successful"), the worst scored bond is within the stretch tolerance, and no
    undecorated subunit's bare tail is inside a domain (a mixed fibril's `tail_pairs`,
    docs/model/occupancy.md)."""
    return verdict == "successful" and max_stretch <= tolerance and tail_pairs == 0


def compare_checks(bvh_pairs, sphere_pairs, depth, band: float,
                   slack: float = TOUCH_SLACK) -> tuple[list, list]:
    """Match the BVH's pairs against the sphere check's (pairs deeper than `band`).

    `depth(i, j)` is the spheres' overlap in Å. A pair only the BVH names is a grazing contact
    when its depth lies in (0, band]: the faceted meshes may or may not cross there. Any other
    difference contradicts geometry and is a disagreement. Returns (grazing, disagreements),
    each a sorted list of (i, j, depth).
    """
    grazing, disagree = [], []
    for i, j in sorted(set(bvh_pairs) ^ set(sphere_pairs)):
        d = float(depth(i, j))
        if (i, j) in bvh_pairs and -slack < d <= band:
            grazing.append((i, j, d))
        else:
            disagree.append((i, j, d))
    return grazing, disagree


def near_fit(p, verdict: dict) -> bool:
    """A jammed layout worth polishing: shallow overlaps only, linkers stretched at most
    POLISH_STRETCH times the tolerance."""
    return (not verdict["accommodated"]
            and float(verdict.get("max_overlap") or 0.0) <= POLISH_OVERLAP
            and verdict["max_bond_stretch"] <= POLISH_STRETCH * p.stretch_tolerance)


def clear_miss(p, verdict: dict) -> bool:
    """A judgement that ends the run as a miss whatever cycle it is: not accommodated, not a near
    miss (near_fit), and at least clear_miss_pairs clashing pairs or its worst bond stretched at
    least clear_miss_stretch times the tolerance (0 turns either off). Measured before it was on:
    of 173 runs baked to their end, it would have stopped 85, none of which fitted later
    (docs/benchmarks.md#stopping-rule-gallery)."""
    if verdict["accommodated"] or near_fit(p, verdict):
        return False
    pairs = verdict["clashing_pairs"]
    pairs = pairs if isinstance(pairs, int) else len(pairs)
    return ((p.clear_miss_pairs > 0 and pairs >= p.clear_miss_pairs)
            or (p.clear_miss_stretch > 0
                and verdict["max_bond_stretch"] >= p.clear_miss_stretch * p.stretch_tolerance))
