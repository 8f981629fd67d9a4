"""Monte Carlo over a HardCore system's layouts, every valid layout equally likely
(docs/model/ensemble.md#sampler).

Moves, each a rigid rotation of part of one chain, drawn so that a move and its reverse are
equally likely (detailed balance with respect to the freely jointed chain's measure, the
product of uniform bond directions):
- pivot at member i (0 .. n-2): members i+1 .. n-1 turned about member i by θ about a uniform
  random axis (this is also the domain move: it swings the domain with the tail before it);
- crankshaft at member i (1 .. n-2): member i turned about the line through i-1 and i+1 by θ,
  which keeps both its bonds' lengths;
θ uniform in [-Δ, Δ], Δ one per (move, member), tuned during burn-in only and then fixed.
A move is accepted iff the moved chain overlaps nothing (hard core: no Metropolis factor).

Replicas: R copies of the system are moved at once, each its own Markov chain (its own chain,
member and angle each step), so numpy works on (R, ...) arrays; all start from one layout.
A start that overlaps a little (Bullet's resting contacts, bonds made rest length) is repaired
first: during burn-in a move is also accepted if it makes the moved chain's overlap no worse;
no sample is kept until every replica overlaps nothing (docs/model/ensemble.md#start).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .system import HardCore

SEED_SALT = 0xE75E  # keeps this stream apart from any other use of the run's seed
TARGET_ACCEPTANCE = 0.3  # what burn-in tunes each Δ towards
CRANK_SHARE = 0.5  # the share of crankshaft moves (chains of 3 or more members)
SEGMENT = 8  # consecutive members a bounding sphere holds in the overlap search
PRUNE_ABOVE = 300  # members in the cell (C·n) above which the overlap search is pruned
# (measured: the default model, 140, 0.45 ms a step either way; 420: 4.2 every pair, 3.3 pruned)
MARGIN = 1e-6  # Å added to the bounding spheres' test against rounding (it only adds pairs)


@dataclass
class Ensemble:
    """What a run of the sampler kept: `domains` (S, R, C, d, 3) the domain centres of every
    replica at every kept sweep, `final` (R, C, n, 3) every member's at the end, and how it ran."""

    domains: np.ndarray
    final: np.ndarray
    seed: int
    sweeps: int
    thin: int
    burn_in_sweeps: int
    acceptance: dict
    delta: np.ndarray
    seconds: float
    notes: dict = field(default_factory=dict)


def rotate(v: np.ndarray, axis: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """v (R, n, 3) turned by theta (R,) about unit axes (R, 3) (Rodrigues' formula)."""
    a = axis[:, None, :]
    c, s = np.cos(theta)[:, None, None], np.sin(theta)[:, None, None]
    return v * c + np.cross(a, v) * s + a * (v * a).sum(-1, keepdims=True) * (1.0 - c)


def segments(n: int) -> np.ndarray:
    """(S, SEGMENT) member indices of a chain of n cut into runs of SEGMENT consecutive members,
    the last run padded with -1."""
    j = np.arange(-(-n // SEGMENT) * SEGMENT).reshape(-1, SEGMENT)
    return np.where(j < n, j, -1)


def bounding(pts: np.ndarray, radii: np.ndarray) -> tuple:
    """Spheres (centre (..., 3), radius (...)) that hold every sphere of each group: pts (..., k,
    3) centres, radii (..., k) broadcasting."""
    centre = pts.mean(axis=-2)
    reach = np.sqrt(((pts - centre[..., None, :]) ** 2).sum(-1)) + radii
    return centre, reach.max(axis=-1)


def random_axes(rng: np.random.Generator, count: int) -> np.ndarray:
    """Unit vectors uniform on the sphere (normalised Gaussians)."""
    v = rng.standard_normal((count, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


class Sampler:
    """The kernel: `positions` (R, C, n, 3) move under `system`'s hard core."""

    def __init__(self, system: HardCore, positions: np.ndarray, rng: np.random.Generator):
        self.s, self.rng = system, rng
        self.x = np.array(positions, dtype=float)
        R, C, n, _ = self.x.shape
        if n != system.members:
            raise ValueError(f"positions have {n} members per chain, the system {system.members}")
        self.R, self.C, self.n = R, C, n
        self.rad_all = np.tile(system.radii, C)  # (C·n,)
        j = np.arange(C * n)
        self.target_chain, self.target_member = j // n, j % n
        # each move's Δ: row 0 pivots at member i, row 1 crankshafts at member i
        self.delta = np.full((2, n), 0.5)
        self.tried = np.zeros((2, n))
        self.taken = np.zeros((2, n))
        self.ar = np.arange(R)
        # the overlap search's segments (docs/model/ensemble.md#overlap-search): each chain cut
        # into runs of SEGMENT members, the last padded by repeating its last member (harmless
        # in a bounding sphere; masked out of the overlap's sum by seg_valid)
        seg = segments(n)
        valid = seg >= 0
        fill = np.where(valid, seg, seg.max(axis=1, keepdims=True))
        self.S = len(seg)
        self.prune = C * n > PRUNE_ABOVE  # below it, every pair summed is cheaper (fewer calls)
        self.seg_cols = (np.arange(C)[:, None, None] * n + fill[None]).reshape(C * self.S, -1)
        self.seg_valid = np.tile(valid, (C, 1))
        self.seg_chain = np.repeat(np.arange(C), self.S)
        self.refresh()

    # ---- overlap --------------------------------------------------------------------------
    def _images(self, pts: np.ndarray) -> list[np.ndarray]:
        return [img(pts) for img in self.s.images]

    def refresh(self) -> None:
        """The cell and its images as cached blocks (B, R, C·n, 3), block 0 the cell itself."""
        cell = self.x.reshape(self.R, self.C * self.n, 3)
        self.blocks = np.stack([cell, *self._images(cell)])
        self.centre, self.reach = bounding(self.blocks[:, :, self.seg_cols],
                                           self.rad_all[self.seg_cols])

    def _bound_chains(self, r: np.ndarray, c: np.ndarray) -> None:
        """Refresh the bounding spheres of chains c (k,) in replicas r (k,), every block."""
        seg = c[:, None] * self.S + np.arange(self.S)[None]  # (k, S)
        cols = self.seg_cols[seg]  # (k, S, SEGMENT)
        for b in range(len(self.blocks)):
            centre, reach = bounding(self.blocks[b][r[:, None, None], cols],
                                     self.rad_all[cols])
            self.centre[b][r[:, None], seg] = centre
            self.reach[b][r[:, None], seg] = reach

    def _overlap(self, moved, blocks, cols, centre, reach, allowed, *, own: bool) -> np.ndarray:
        """Per replica, the summed overlap depth of the moved runs `moved` (positions (R, G,
        SEGMENT, 3), rows, valid, bounding centres and reaches) with the segments `cols` (their
        members' columns in `blocks` (B, R, ·, 3), bounding spheres centre/reach (B, R, S·)),
        only where `allowed` (broadcasting (B, R, G, S·), None: everywhere). Anchor-anchor pairs
        left out; `own`: the blocks are the moved chain itself (its members' columns are its
        member indices), so bonded neighbours in block 0 are left out too."""
        s = self.s
        pts, rows, valid, q_centre, q_reach = moved
        gap = centre[:, :, None] - q_centre[None, :, :, None]  # (B, R, G, S·, 3)
        limit = q_reach[None, :, :, None] + reach[:, :, None] + abs(s.tolerance) + MARGIN
        near = (gap * gap).sum(-1) < limit * limit
        if allowed is not None:
            near &= allowed
        b, r, k, sg = np.nonzero(near)
        if not b.size:
            return np.zeros(self.R)
        col = cols[sg]  # (K, SEGMENT)
        diff = pts[r, k][:, :, None, :] - blocks[b[:, None], r[:, None], col][:, None]
        dist = np.sqrt((diff * diff).sum(-1))  # (K, SEGMENT, SEGMENT)
        rad = self.rad_all[col]
        depth = s.radii[rows[k]][:, :, None] + rad[:, None, :] - s.tolerance - dist
        member = (col % self.n)[:, None, :]
        keep = valid[k][:, :, None] & self.seg_valid[sg][:, None, :]
        keep &= ~((rows[k] == 0)[:, :, None] & (member == 0))
        if own:
            keep &= ~((b == 0)[:, None, None] & (np.abs(rows[k][:, :, None] - member) <= 1))
        return np.bincount(r, weights=np.where(keep, np.maximum(depth, 0.0), 0.0)
                           .sum(axis=(1, 2)), minlength=self.R)

    def violation(self, q: np.ndarray, c: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Per replica, the summed overlap depth (Å) of members `rows` of chain c, at positions
        q (R, n, 3) (the whole chain), with every other sphere of the cell and its images, with
        its own chain's members (bonded neighbours excluded) and images, and with the obstacle;
        anchor-anchor pairs excluded (both fixed)."""
        s, n = self.s, self.n
        qr = q[:, rows]  # (R, m, 3)
        ri = s.radii[rows]
        if not self.prune:
            total = self._every_pair(q, qr, ri, c, rows)
        else:
            total = self._pruned(q, qr, ri, c, rows)
        if s.obstacle is not None and (rows > 0).any():
            keep = rows > 0
            total += s.obstacle.depth(qr[:, keep], ri[keep]).sum(axis=1)
        return total

    def _every_pair(self, q, qr, ri, c, rows) -> np.ndarray:
        """violation's sum over every pair (the cell, its images, the own chain)."""
        s, n = self.s, self.n
        anchor_row = (rows == 0)[None, :, None]
        diff = qr[None, :, :, None, :] - self.blocks[:, :, None, :, :]
        dist = np.sqrt((diff * diff).sum(-1))  # (B, R, m, C·n)
        depth = np.maximum(ri[None, None, :, None] + self.rad_all - s.tolerance - dist, 0.0)
        own = (self.target_chain[None, :] == c[:, None])[None, :, None, :]
        skip = own | (anchor_row & (self.target_member == 0))[None]
        total = np.where(skip, 0.0, depth).sum(axis=(0, 2, 3))
        j = np.arange(n)
        for b, block in enumerate((q, *self._images(q))):
            diff = qr[:, :, None, :] - block[:, None, :, :]
            dist = np.sqrt((diff * diff).sum(-1))  # (R, m, n)
            depth = np.maximum(ri[:, None] + s.radii[None] - s.tolerance - dist, 0.0)
            skip = (rows == 0)[:, None] & (j == 0)[None]
            if b == 0:
                skip = skip | (np.abs(rows[:, None] - j[None]) <= 1)
            total += np.where(skip[None], 0.0, depth).sum(axis=(1, 2))
        return total

    def _pruned(self, q, qr, ri, c, rows) -> np.ndarray:
        """violation's sum over the pairs whose runs' bounding spheres overlap (the same sum)."""
        s = self.s
        # pruned exactly (docs/model/ensemble.md#overlap-search): the moved rows in runs of
        # SEGMENT, each run's bounding sphere tested against every segment's; a pair of spheres
        # can overlap only if their segments' spheres do
        g = segments(len(rows))
        g_valid = g >= 0
        g = np.where(g_valid, g, len(rows) - 1)
        moved = (qr[:, g], rows[g], g_valid, *bounding(qr[:, g], ri[g]))
        # the rest of the cell and of its images (the own chain left out)
        others = self.seg_chain[None, None, None, :] != c[None, :, None, None]
        total = self._overlap(moved, self.blocks, self.seg_cols, self.centre, self.reach,
                              others, own=False)
        # the own chain, new, and its images (bonded neighbours left out in the chain itself)
        own = np.stack([q, *self._images(q)])  # (B, R, n, 3)
        centre, reach = bounding(own[:, :, self.seg_cols[:self.S]],
                                 s.radii[self.seg_cols[:self.S]])
        total += self._overlap(moved, own, self.seg_cols[:self.S], centre, reach, None,
                               own=True)
        return total

    def total_violation(self) -> np.ndarray:
        """Per replica, the overlap summed over every chain (each pair counted from both sides)."""
        rows = np.arange(self.n)
        return sum(self.violation(self.x[:, c], np.full(self.R, c), rows)
                   for c in range(self.C))

    # ---- moves ----------------------------------------------------------------------------
    def propose(self):
        """One move per replica, the kind and member shared by all replicas this step (chosen
        independently of the state), the chain, axis and angle each replica's own: (chain,
        kind, member, moved rows, new chain positions (R, n, 3))."""
        R, n, rng = self.R, self.n, self.rng
        c = rng.integers(0, self.C, R)
        crank = n >= 3 and rng.random() < CRANK_SHARE
        i = int(rng.integers(1, n - 1)) if crank else int(rng.integers(0, n - 1))
        q = self.x[self.ar, c]
        if crank:
            origin = q[:, i - 1]
            axis = q[:, i + 1] - origin
            axis = axis / np.linalg.norm(axis, axis=1, keepdims=True)
            rows = np.array([i])
        else:
            origin, axis = q[:, i], random_axes(rng, R)
            rows = np.arange(i + 1, n)
        kind = int(crank)
        theta = rng.uniform(-1.0, 1.0, R) * self.delta[kind, i]
        new = q.copy()
        new[:, rows] = origin[:, None, :] + rotate(q[:, rows] - origin[:, None, :], axis, theta)
        return c, kind, i, rows, new

    def step(self, repairing: np.ndarray | None = None) -> np.ndarray:
        """One move per replica; returns which were accepted. `repairing` (R,) bool: those
        replicas may also take moves that make their overlap no worse (burn-in only)."""
        c, kind, i, rows, new = self.propose()
        v_new = self.violation(new, c, rows)
        ok = v_new <= 0.0
        if repairing is not None and repairing.any():
            ok |= repairing & (v_new <= self.violation(self.x[self.ar, c], c, rows))
        r = self.ar[ok]
        if r.size:
            self.x[r, c[ok]] = new[ok]
            cols = c[ok][:, None] * self.n + np.arange(self.n)[None]
            self.blocks[0][r[:, None], cols] = new[ok]
            for b, img in enumerate(self._images(new[ok]), start=1):
                self.blocks[b][r[:, None], cols] = img
            if self.prune:
                self._bound_chains(r, c[ok])
        self.tried[kind, i] += self.R
        self.taken[kind, i] += int(ok.sum())
        return ok

    def tune(self) -> None:
        """Burn-in only: move each Δ towards TARGET_ACCEPTANCE (then reset the tallies)."""
        tried = self.tried > 0
        rate = np.where(tried, self.taken / np.maximum(self.tried, 1), TARGET_ACCEPTANCE)
        self.delta = np.clip(self.delta * np.exp(rate - TARGET_ACCEPTANCE), 0.02, np.pi)
        self.tried[:] = 0
        self.taken[:] = 0


def sample(system: HardCore, start: np.ndarray, *, seed: int, replicas: int = 32,
           sweeps: int = 200, thin: int = 1, burn_in: int = 50, max_repair: int = 2000,
           ) -> Ensemble:
    """Sample `system` from `start` (C, n, 3), or K starts (K, C, n, 3) taken in turn by the
    replicas (bonds made rest length first): `replicas` Markov chains, first repaired while any
    replica overlaps (up to `max_repair` sweeps), then `burn_in` sweeps with no overlap
    anywhere (Δ tuned throughout), then `sweeps` sweeps with Δ fixed, keeping the domain centres
    every `thin` sweeps. A sweep: C·(n-1) moves per replica. Raises ValueError when a replica
    still overlaps after max_repair sweeps (the start is too far from a valid layout)."""
    t0 = time.perf_counter()
    rng = np.random.default_rng([SEED_SALT, int(seed)])
    start = system.with_rest_bonds(np.asarray(start, dtype=float))
    starts = start[None] if start.ndim == 3 else start
    x = starts[np.arange(replicas) % len(starts)].copy()  # replica r starts from r mod K
    k = Sampler(system, x, rng)
    per_sweep = k.C * (k.n - 1)
    dirty = k.total_violation() > 0
    done = clean = repair = 0  # sweeps in all, since every replica overlaps nothing, repairing
    while clean < burn_in:
        if repair >= max_repair:
            raise ValueError(f"{int(dirty.sum())} of {replicas} replicas still overlap after "
                             f"{max_repair} sweeps: the start is too far from a valid layout")
        was_dirty = bool(dirty.any())
        for _ in range(per_sweep):
            k.step(dirty if was_dirty else None)
        done += 1
        if was_dirty:
            repair += 1
            dirty = k.total_violation() > 0
        else:
            clean += 1
        if done % 5 == 0:
            k.tune()
    k.tried[:] = 0
    k.taken[:] = 0
    kept = []
    for sweep in range(1, sweeps + 1):
        for _ in range(per_sweep):
            k.step()
        if sweep % thin == 0:
            kept.append(k.x[:, :, list(system.domains)].copy())
    rates = k.taken / np.maximum(k.tried, 1)
    acceptance = {"pivot": rates[0].round(3).tolist(), "crankshaft": rates[1].round(3).tolist(),
                  "overall": round(float(k.taken.sum() / max(k.tried.sum(), 1)), 3)}
    return Ensemble(np.asarray(kept), k.x.copy(), int(seed), sweeps, thin, done, acceptance,
                    k.delta.copy(), time.perf_counter() - t0, {"repair_sweeps": repair})
