"""The proven upper bound on the fraction of decorated subunits (issue #44, item 4): at linker L
no layout of a mixed fibril is clash-free with intact linkers when more than `fraction_bound`
of its subunits carry the domain. Geometry alone, no simulation; plain numpy, no bpy.

The argument is the linker bound's (docs/model/bound.md#derivation), counted per decorated
subunit (written out for a referee: docs/model/bound.md#fraction):

1. A decorated subunit's domains lie, by their inner bodies, within ρ of its anchor, outside
   the eroded core, disjoint from every other domain's; an undecorated subunit has no domain
   (a bare tail only takes room, so leaving it out keeps the bound a bound).
2. So for a set P of protofilaments and a set of the chain's domains, the decorated subunits
   of P's judged chains need (their count) × (those domains' inner volume) ≤ vol(U_P), the
   room their anchors' balls leave outside the eroded core: the linker bound's own voxel room
   (`bound.Setting`), at this linker's ρ.
3. Infinite fibril (periodic cell): the room is per layer and the same for every layer (the
   screw); a pattern repeating every M layers puts f_j·M decorated subunits of protofilament j
   in every M layers, so Σ_{j∈P} f_j ≤ cap_P = vol(U_P per layer) / volume. Finite fibril:
   over the scored layers, the counts g_j ≤ the scored layers S, Σ_{j∈P} g_j ≤
   cap_P = ⌊vol(U_P) / volume⌋, and every unscored subunit may carry its domain (the verdict
   does not judge it).
4. Protofilaments may carry different fractions (a pattern counted along one of them), so the
   caps bind a sum over any grouping: for a partition of the protofilaments into groups,
   Σ_j f_j ≤ Σ_groups min(cap_group, |group|·S). The bound is the least such sum over every
   partition, over the subunits: f_B.

At L ≥ impossible_below every cap is full (the linker bound's inequalities are these at f = 1),
so f_B = 1 there and below it f_B < 1; a longer linker only enlarges the room, so f_B is
non-decreasing in L and `impossible_below_at(p, f)` (the first L with f ≤ f_B(L)) is the
linker bound at fraction f.
"""
from __future__ import annotations

import math

from . import bound

# A fraction within this of the bound counts as at it (float noise of room / volume, never a
# subunit: a cell of 10^6 subunits steps by 10^-6)
TOLERANCE = 1e-9


def partitions(items: list):
    """Every partition of `items` into non-empty groups (Bell(K) of them: 15 for four
    protofilaments)."""
    if not items:
        yield []
        return
    first, rest = items[0], items[1:]
    for part in partitions(rest):
        yield [[first]] + part
        for i in range(len(part)):
            yield part[:i] + [[first] + part[i]] + part[i + 1:]


def combine(cap: dict, K: int) -> tuple[float, list]:
    """The most decorated chains the caps allow (Σ_j f_j, or Σ_j g_j): for every partition of
    the K protofilaments into groups, Σ over groups of its cap (a cap is already at most the
    group's chains); the least such sum, and the partition that gives it. Protofilaments may
    carry different fractions, so a group's cap bounds only that group's share."""
    best, groups = None, None
    for part in partitions(list(range(K))):
        total = sum(cap[tuple(sorted(g))] for g in part)
        if best is None or total < best:
            best, groups = total, part
    return best, groups


def caps(s: bound.Setting, linker: int) -> dict:
    """Per set of protofilaments (a tuple), how many of its judged chains can carry the domain
    at this linker: a density per layer (periodic) or a count over the scored layers (finite),
    and the domains whose room sets it."""
    p, K, S = s.p, s.p.protofilaments, s.chains_per_pf
    out = {}
    for pfs in bound._subsets(K):
        full = len(pfs) * S
        if s.room is None or linker < s.first:  # no path leaves the core: nothing judged fits
            out[tuple(pfs)] = (0, None)
        elif linker >= s.impossible_below:  # every inequality of the linker bound holds
            out[tuple(pfs)] = (full, None)
        else:
            rho = bound.reach(p, s.terms, linker)
            own = None if p.pf_anchors is None else bound.pf_reach(p, s.terms, linker)
            cap, why = full, None
            for ds in bound._subsets(len(s.terms)):
                need = sum(s.volumes[k] for k in ds)  # one decorated subunit's
                have = s.room.volume(pfs, max(rho[k] for k in ds) if own is None else
                                     [own[j, ds].max() for j in pfs])
                if full * need <= have:
                    continue
                room = have / need if s.periodic else math.floor(have / need)
                if room < cap:
                    cap, why = room, {"domains": ds, "needed_A3": round(need, 1),
                                      "room_A3": round(have, 1)}
            out[tuple(pfs)] = (cap, why)
    return out


def fraction_limit(p, linker: int | None = None, budget: float = bound.GRID_BUDGET) -> dict:
    """The bound on the fraction at this linker (p's own if None), with how it was found:
    `fraction_bound` f_B (no layout has more than f_B of its subunits decorated), `count` and
    `of` (the most decorated subunits among the model's own: the periodic cell's M × K or the
    fibril's layers × K), and the grouping of protofilaments whose rooms set it
    (docs/model/bound.md#fraction)."""
    s = bound.setting(p, budget)
    L = p.linker if linker is None else int(linker)
    K, S = p.protofilaments, s.chains_per_pf
    cap = caps(s, L)
    best, groups = combine({pfs: c for pfs, (c, _) in cap.items()}, K)
    n = p.layers * K  # the model's subunits: a periodic cell's M × K, a fibril's layers × K
    if s.periodic:
        f = min(1.0, best / K)
        count = min(n, math.floor(f * n + TOLERANCE))
    else:
        count = min(n, int(best) + K * (p.layers - S))  # the unscored layers are free
        f = count / n
    binding = [{"protofilaments": sorted(g), "cap": round(float(cap[tuple(sorted(g))][0]), 4),
                **(cap[tuple(sorted(g))][1] or {})}
               for g in groups if cap[tuple(sorted(g))][0] < len(g) * S]
    return {
        "fraction_bound": f,
        "linker": L,
        "count": count,
        "of": n,
        "over": ("the infinite fibril (per layer; the cell's subunits for the count)"
                 if s.periodic else f"the scored layers {s.lo}-{s.hi - 1} (the others free)"),
        "binding": binding,
        "impossible_below": s.impossible_below,
        "method": "excluded volume per decorated subunit (docs/model/bound.md#fraction)",
    }


def fraction_bound(p, linker: int | None = None, budget: float = bound.GRID_BUDGET) -> float:
    """f_B at this linker (p's own if None): no clash-free layout with intact linkers has more
    than this fraction of its subunits decorated (docs/model/bound.md#fraction)."""
    return fraction_limit(p, linker, budget)["fraction_bound"]


def impossible_below_at(p, fraction: float, budget: float = bound.GRID_BUDGET) -> int:
    """The linker bound at this fraction: the shortest linker at which `fraction` of the
    subunits is not excluded (f ≤ f_B(L)); no layout with that many decorated exists at any
    shorter one. At fraction 1 it is `impossible_below`; bound.LONGEST + 1 if none."""
    if not 0.0 < fraction <= 1.0:
        raise ValueError(f"fraction must lie in (0, 1], not {fraction}")
    s = bound.setting(p, budget)
    if s.room is None:
        return bound.LONGEST + 1
    for L in range(1, s.impossible_below):  # monotone: the first that passes
        if fraction <= fraction_bound(p, L, budget) + TOLERANCE:
            return L
    return s.impossible_below


def _percent(x: float, up: bool) -> str:
    """x as a percentage to 0.1 %, rounded the way that keeps the sentence true."""
    v = (math.ceil if up else math.floor)(x * 1000.0 - (1e-6 if up else -1e-6)) / 10.0
    return f"{v:g} %"


def fraction_bracket(bound_fraction: float, found: float | None) -> str:
    """The bracket on the fraction, said once: "impossible above f_B (proof) / fits at f (a
    layout) / open between". `found`: the largest fraction at which a layout was found (None:
    none found). The bound is rounded up and the fit down, so each clause stays true."""
    above = f"impossible above {_percent(bound_fraction, up=True)} (proof)"
    if found is None:
        return f"{above} / no layout found / open up to {_percent(bound_fraction, True)}"
    if found > bound_fraction + TOLERANCE:
        return (f"{above} / a layout at {_percent(found, False)}, above the bound: outside the "
                "bound's assumptions (see core_entry, docs/model/bound.md#assumptions)")
    fits = f"fits at {_percent(found, up=False)} (a layout)"
    if found >= bound_fraction - TOLERANCE:
        return f"{above} / {fits} / closed"
    return (f"{above} / {fits} / open between "
            f"{_percent(found, False)} and {_percent(bound_fraction, True)}")
