"""β-solenoids: fibrils whose chains each make several rungs (HET-s(218-289), 2KJ3: two).

A one-rung fibril's chains stack on the same residue 4.2-5.6 Å apart. A solenoid's chain stacks
on itself: a residue's CA sits 4.2-5.6 Å along the axis over a residue of its own chain farther
along it (the next rung), so the same residue of the next molecule is n rungs up. Here: the
rung pairs of a chain, the rungs per molecule n that makes its molecules stack, and the rung's
spacing along the axis; the molecule is the model's layer (one domain and one anchor per
molecule). docs/guide/structures.md#beta-solenoids. Plain numpy; the caller (fibril.py) gives
the stacking window, so this module needs nothing above it.
"""
from __future__ import annotations

import math

import numpy as np

MIN_LOOP = 5  # residues: a rung stacks on a residue of its own chain at least this far along it
MAX_RUNGS = 8  # rungs per molecule tried
ALONG = math.cos(math.radians(30.0))  # a rung pair's step within 30° of the helical axis
# the share of a stack's rung pairs that must run along it: a solenoid's rungs stack along the
# axis (2KJ3: 59 % within 30° of its end-to-end step, a kinked stack); a globular β-sheet's
# neighbouring strands lie every way (1GFL's crystal dimer: 9 %)
MIN_ALONG = 0.3


def rung_pairs(ca: np.ndarray, residues: np.ndarray, window: tuple) -> tuple:
    """(i, j) index arrays into `residues` (i < j, at least MIN_LOOP apart in the numbering) of
    one chain's residue pairs whose CAs lie `window` Å apart: candidate rungs stacked on rungs."""
    d = np.linalg.norm(ca[:, None, :] - ca[None, :, :], axis=-1)
    far = (residues[None, :] - residues[:, None]) >= MIN_LOOP
    i, j = np.nonzero(far & (d >= window[0]) & (d <= window[1]))
    return i, j


def self_stacked(ca: np.ndarray, residues: np.ndarray, window: tuple, least: int) -> bool:
    """Every chain (ca: chains, residues, 3) has at least `least` rung pairs of its own."""
    return all(len(rung_pairs(c, residues, window)[0]) >= least for c in ca)


def windows(window: tuple):
    """(rungs, the same residue's window between neighbouring molecules) for 2..MAX_RUNGS rungs
    per molecule: n rungs stack that residue n times the rung's spacing apart."""
    for n in range(2, MAX_RUNGS + 1):
        yield n, (n * window[0], n * window[1])


def rung_mask(ca: np.ndarray, residues: np.ndarray, window: tuple) -> np.ndarray:
    """Residues (bool over `residues`) in a rung pair of their own chain in every chain: the
    residues of the solenoid's rungs (its loops and free termini are left out)."""
    keep = np.ones(len(residues), bool)
    for c in ca:
        i, j = rung_pairs(c, residues, window)
        mine = np.zeros(len(residues), bool)
        mine[i] = mine[j] = True
        keep &= mine
    return keep


def rung_rise(ca: np.ndarray, residues: np.ndarray, window: tuple, u: np.ndarray) -> list:
    """Every chain's rung pairs' steps along the axis u (Å, positive), those within 30° of it
    (a β-hairpin's strands, side by side in one rung, are not rungs on rungs)."""
    steps = []
    for c in ca:
        i, j = rung_pairs(c, residues, window)
        v = c[j] - c[i]
        along = np.abs(v @ u)
        steps += list(along[along >= ALONG * np.linalg.norm(v, axis=1)])
    return steps


def along_share(ca: np.ndarray, residues: np.ndarray, window: tuple, u: np.ndarray) -> float:
    """The share of every chain's rung pairs whose step lies within 30° of u."""
    total = along = 0
    for c in ca:
        i, j = rung_pairs(c, residues, window)
        v = c[j] - c[i]
        total += len(i)
        along += int((np.abs(v @ u) >= ALONG * np.linalg.norm(v, axis=1)).sum())
    return along / total if total else 0.0


def check(rungs: int, rise: float, steps: list) -> str | None:
    """Why the measured molecule rise and rung spacing disagree with `rungs`, or None: the
    molecule's rise must be a whole number of rungs (within a quarter rung)."""
    if len(steps) == 0:
        return "no rung pair of a chain runs along the axis"
    ratio = rise / float(np.mean(steps))
    if abs(ratio - rungs) > 0.25:
        return (f"one molecule per {rise:.2f} Å but a chain's rungs are {np.mean(steps):.2f} Å "
                f"apart along the axis ({ratio:.2f} rungs per molecule, not {rungs})")
    return None
