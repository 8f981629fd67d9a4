"""Several real-shaped domains per chain start bent (docs/guide/atoms-and-domains.md#shapes-of-several-domains):
each domain's terminals (domain_terminals), the chain laid out bond by bond with every domain
turned so that its exit leans towards the chain's heading (bent_layout), the turn that leaves
the chain clearest of itself (real_chain_layout, chain_clearance), and full-size covering
spheres spread chain by chain (spread_chains). Pure numpy (no bpy).
"""
from __future__ import annotations

import numpy as np

from ..geom import shape
from ..geom.rigid import joint_rotations, turn_about
from ..geom.shape import directions
from .start_layout import (SPREAD_DIRECTIONS, SPREAD_OUTWARD, SPREAD_ROUNDS, _choose,
                           _keep_outward, _unit, fan_frames)


# ---- several real-shaped domains per chain: a bent start layout --------------------------------
# (docs/guide/atoms-and-domains.md#shapes-of-several-domains)
EXIT_STRAIGHT = 2    # bonds the outgoing linker runs along its exit's outward normal
EXIT_TURN = 2        # bonds over which it then turns towards the chain's heading
EXIT_OUTWARD = 0.3   # every later bond keeps at least this cosine with the exit's normal
ROLLS = 12           # rolls of the domains about their incoming bond tried (30° apart)
CLEAR_DIRECTIONS = 400  # directions a separating plane is looked for in (clearance)


def spread_chains(p, rest: np.ndarray, rounds: int = SPREAD_ROUNDS
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """spread_layout for chains of several `spheres` domains under the tutorial protocol: each
    chain's first bond straight out, then its bent layout (bent_layout) heading along the
    candidate direction that leaves its domains' covering spheres and its beads clear of the
    other chains', or least deep in them, among the headings that lay the chain out clear of
    itself (all of them if none does); the first is real_chain_layout's (straight out, turned
    to clear itself). Full-size compounds started inside each other lock: a 10-layer chain of
    ubiquitin then GFP (linker 10, 4 residues between) from the unspread start ended with two
    compounds 14.3 Å into each other (docs/guide/atoms-and-domains.md#shapes-of-several-domains).
    Returns positions, pivots and the domains' turns, as real_chain_layout."""
    rest = np.asarray(rest, dtype=float)
    n, m, _ = rest.shape
    frames = domain_terminals(p)
    members = [d.member for d in p.domains]
    u = fan_frames(rest)[0]
    cand = directions(SPREAD_DIRECTIONS)
    base = real_chain_layout(p, rest)  # straight out, the turn that clears it: option 0
    options, spheres = [], []
    for c in range(n):
        dirs = cand[cand @ u[c] >= SPREAD_OUTWARD]
        wanted = np.repeat(dirs[:, None], m - 1, axis=1)
        wanted[:, 0] = u[c]
        layout = bent_layout(p, np.repeat(rest[c:c + 1], len(dirs), axis=0), wanted, frames)
        layout = [np.concatenate([b[c:c + 1], a]) for a, b in zip(layout, base)]
        clear = chain_clearance(p, layout[0], layout[2], frames) > 0
        keep = clear if clear.any() else np.ones(len(dirs), dtype=bool)
        layout = [a[keep] for a in layout]
        world = [np.concatenate([np.einsum("kij,sj->ksi", layout[2][:, d], f["rows"])
                                 + layout[0][:, i, None], np.broadcast_to(
                                     f["reach"][None, :, None], (int(keep.sum()),
                                                                 len(f["reach"]), 1))], axis=-1)
                 for d, (i, f) in enumerate(zip(members, frames))]
        beads = [i for i in range(1, m) if i not in members]  # and its beads
        world.append(np.concatenate([layout[0][:, beads], np.full(
            (int(keep.sum()), len(beads), 1), p.residue_radius)], axis=-1))
        options.append(layout)
        spheres.append(np.concatenate(world, axis=1))
    choice = _choose(spheres, rounds)
    return tuple(np.stack([options[c][a][choice[c]] for c in range(n)]) for a in range(3))


def domain_terminals(p) -> list[dict]:
    """Per domain of a real-shaped chain (0 nearest the core): its shape rows [x, y, z, r]
    in its body frame, each row's reach beyond its centre (hull: the grown points'; spheres:
    the radius), the incoming joint and the outward normal of the surface nearest it, and
    (all but the last) the exit and its normal (geom.shape.outward; union_exit for the
    non-convex union of spheres)."""
    out = []
    for d in p.domains:
        rows = d.rows
        if d.shape.compound:  # a union of spheres: not convex
            normal = lambda q: shape.union_exit(rows, q)[0]  # noqa: E731
            reach = rows[:, 3]
        else:
            normal = lambda q: shape.outward(rows, q)  # noqa: E731
            reach = rows[:, 3] + shape.grow(rows[:, 3])
        entry = {"rows": rows[:, :3], "reach": reach, "joint": d.joint,
                 "joint_out": normal(d.joint)}
        if d.exit is not None:
            entry.update(exit=d.exit, exit_out=normal(d.exit))
        out.append(entry)
    return out


def _turn_towards(rot, d, normal, heading):
    """rot (n, 3, 3) turned about d (n, 3) so that rot @ normal leans as far as it can towards
    heading (n, 3)."""
    n0 = rot @ normal
    perp = n0 - (n0 * d).sum(1, keepdims=True) * d
    want = heading - (heading * d).sum(1, keepdims=True) * d
    ok = (np.linalg.norm(perp, axis=1) > 1e-6) & (np.linalg.norm(want, axis=1) > 1e-6)
    angle = np.where(ok, np.arctan2((np.cross(perp, want) * d).sum(1), (perp * want).sum(1)), 0.0)
    return turn_about(d, angle) @ rot


def bent_layout(p, rest: np.ndarray, wanted: np.ndarray, frames: list[dict], roll: float = 0.0,
                turn: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start positions (n, m, 3), bond pivots (n, m - 1, 3) and each domain's turn
    (n, D, 3, 3) of chains of real-shaped domains, bond i pointing along wanted[:, i] (unit)
    except where a domain bends the chain:

    - a domain's incoming bond ends at its joint (its terminal CA, one residue spacing from the
      bead before it, the bond's pivot), and the domain is turned so that the surface nearest
      the joint faces back along the bond (as one domain: builders.layers), then about that
      bond so that its exit's normal leans towards the chain's heading, plus `roll` (rad);
    - the outgoing linker leaves from the exit (the pivot), one residue spacing to its first
      bead, along the exit's outward normal for EXIT_STRAIGHT bonds, then turns towards the
      heading over EXIT_TURN bonds, never below EXIT_OUTWARD along the normal, so that its
      beads move away from the surface they left (`turn` False: straight along the normal to
      the next domain, the fallback for a short linker whose turn swings the next domain back
      into the one it left)."""
    rest = np.asarray(rest, dtype=float)
    n, m, _ = rest.shape
    members = [d.member for d in p.domains]
    dom_of = {i: k for k, i in enumerate(members)}
    spacing, bead = p.residue_spacing, p.residue_radius
    pos = np.empty_like(rest)
    pos[:, 0] = rest[:, 0]
    pivots = np.empty((n, m - 1, 3))
    rot = np.tile(np.eye(3), (n, len(members), 1, 1))
    normal, since = None, 0
    for i in range(m - 1):
        h = wanted[:, i]
        if i in dom_of:  # leaving a domain at its exit
            f, r = frames[dom_of[i]], rot[:, dom_of[i]]
            start = pos[:, i] + r @ f["exit"]
            normal, since = r @ f["exit_out"], 0
            pivots[:, i] = start
        else:
            start = pos[:, i]
        if normal is None:
            d = h
        else:
            w = min(1.0, max(0.0, (since - EXIT_STRAIGHT + 1) / EXIT_TURN)) if turn else 0.0
            d = _keep_outward(_unit((1.0 - w) * normal + w * h), normal, EXIT_OUTWARD)
            since += 1
        if i + 1 in dom_of:  # into a domain at its joint
            k = dom_of[i + 1]
            f = frames[k]
            joint = start + spacing * d
            r = joint_rotations(f["joint_out"], d)
            if "exit" in f:
                ahead = wanted[:, i + 1] if i + 1 < m - 1 else h
                r = turn_about(d, roll) @ _turn_towards(r, d, f["exit_out"], ahead)
            rot[:, k] = r
            pos[:, i + 1] = joint - r @ f["joint"]
            pivots[:, i] = joint
            normal = None
        else:
            pos[:, i + 1] = start + spacing * d
            if i not in dom_of:
                pivots[:, i] = start + bead * d
    return pos, pivots, rot


def _support(points, reach, u):
    """max over rows of x·u + reach, per direction u (k, 3): a convex body's support."""
    return (points @ u.T + reach[:, None]).max(axis=0)


def chain_clearance(p, pos: np.ndarray, rot: np.ndarray, frames: list[dict]) -> np.ndarray:
    """Per chain, the smallest gap (Å) between two of its bodies that are not bonded: domain
    with domain, domain with anchor or bead. For hulls a gap is the widest of CLEAR_DIRECTIONS
    planes between the two bodies' convex hulls (and the line of their centres): positive
    proves them apart; zero or less means no separating plane was found among them. For
    spheres it is exact: the closest two balls."""
    members = [d.member for d in p.domains]
    dom_of = {i: k for k, i in enumerate(members)}
    u = directions(CLEAR_DIRECTIONS)
    n, m, _ = pos.shape
    beads = [i for i in range(m) if i not in dom_of]
    gaps = np.full(n, np.inf)
    balls = p.shape.compound  # a union of spheres: exact, ball by ball
    for c in range(n):
        world = []
        for k, i in enumerate(members):
            f = frames[k]
            pts = f["rows"] @ rot[c, k].T + pos[c, i]
            world.append((pts, f["reach"]))
        for a, ia in enumerate(members):
            pa, ra = world[a]
            if balls:
                others = [world[b] for b in range(a + 1, len(members))]
                others += [(pos[c, [i]], np.array([p.residue_radius])) for i in beads
                           if abs(i - ia) > 1]
                for pb, rb in others:
                    d = np.linalg.norm(pa[:, None] - pb[None], axis=-1)
                    gaps[c] = min(gaps[c], float((d - ra[:, None] - rb[None]).min()))
                continue
            for b in range(a + 1, len(members)):
                pb, rb = world[b]
                axis = _unit(pos[c, members[b]] - pos[c, ia])[None]
                dirs = np.vstack([u, axis])
                gap = (-_support(pb, rb, -dirs) - _support(pa, ra, dirs)).max()
                gaps[c] = min(gaps[c], gap)
            near = [i for i in beads if abs(i - ia) > 1]  # bonded neighbours do not collide
            if near:
                centres = pos[c, near]
                s = _support(pa, ra, u)  # (dirs,)
                gap = (-(centres @ (-u).T) - p.residue_radius - s[None]).max(axis=1)
                gaps[c] = min(gaps[c], float(gap.min()))
    return gaps


def real_chain_layout(p, rest: np.ndarray, wanted: np.ndarray | None = None
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """bent_layout with the roll about each domain's incoming bond that leaves every chain
    clear of itself: the best-leaning roll first, then ROLLS - 1 others 30° apart, then the
    same with the outgoing linkers straight along their exits' normals (bent_layout's `turn`);
    a chain that none clears takes the layout with the widest gap. Measured: GFP then
    ubiquitin, 2 residues between, met each other by 0.1-1.8 Å at every turn when the linker
    turned, and no longer straight. `wanted`: each bond's direction,
    default every bond straight out (the tutorial's rest direction, anchor to the outermost
    member). Returns positions, pivots and the domains' turns (n, D, 3, 3)."""
    rest = np.asarray(rest, dtype=float)
    n, m, _ = rest.shape
    if wanted is None:
        wanted = np.repeat(fan_frames(rest)[0][:, None], m - 1, axis=1)
    frames = domain_terminals(p)
    best, best_gap = None, np.full(n, -np.inf)
    for turn, t in [(True, t) for t in range(ROLLS)] + [(False, t) for t in range(ROLLS)]:
        layout = bent_layout(p, rest, wanted, frames, roll=2 * np.pi * t / ROLLS, turn=turn)
        gap = chain_clearance(p, layout[0], layout[2], frames)
        if best is None:
            best = [a.copy() for a in layout]
        better = (best_gap <= 0) & (gap > best_gap)
        for a, b in zip(best, layout):
            a[better] = b[better]
        best_gap = np.where(better, gap, best_gap)
        if (best_gap > 0).all():
            break
    return tuple(best)
