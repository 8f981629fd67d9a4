"""Stacking contacts that are not layers: two protofilaments side by side whose residues of the
same number happen to lie 4.2-5.6 Å apart (docs/guide/structures.md#read-survey).

In a fibril a chain stacks on two others, the layers below and above it, over most of its
residues. When a chain stacks on more than two, the contacts over fewer than half as many
residues as the strongest contact of either chain (9KZO: 5-7 residues beside 21) are side
contacts between protofilaments, dropped and said in a note; if a chain still stacks on more than
two, which partners are its layers is not clear and the file is refused, naming the chain and its
partners. A file whose every chain stacks on at most two others is left as it is.
"""
from __future__ import annotations

from .errors import StructureError

WEAK = 0.5  # a contact over fewer than this fraction of either chain's strongest is a side one


def layers_only(pairs: dict, names: list, name: str, option: str, notes: list | None) -> dict:
    """`pairs` ({(i, j): stacked residues mask}) without the side contacts, when a chain stacks
    on more than two others; unchanged when none does."""
    count = {k: int(s.sum()) for k, s in pairs.items()}
    partners = {}
    for (i, j), n in count.items():
        partners.setdefault(i, []).append((n, j))
        partners.setdefault(j, []).append((n, i))
    if all(len(v) <= 2 for v in partners.values()):
        return pairs
    strongest = {i: max(v)[0] for i, v in partners.items()}
    side = {k for k, n in count.items() if n < WEAK * min(strongest[k[0]], strongest[k[1]])}
    kept = {k: s for k, s in pairs.items() if k not in side}
    left = {i: sorted(((n, j) for n, j in v if tuple(sorted((i, j))) not in side),
                      key=lambda nj: (-nj[0], nj[1])) for i, v in partners.items()}
    for i, v in left.items():
        if len(v) > 2:
            listed = ", ".join(f"{names[j]} ({n} residues)" for n, j in v)
            raise StructureError(option, f"{name}: the layers do not stack into protofilaments: "
                                         f"chain {names[i]} stacks on more than two others, "
                                         f"{listed} (a residue stacks when its CA lies 4.2-5.6 Å "
                                         "from the same residue's)")
    if notes is not None:
        most = max(count[k] for k in side)
        notes.append(f"{len(side)} contacts between protofilaments side by side, over {most} "
                     "residues or fewer (same-numbered CA 4.2-5.6 Å apart), are not layers: "
                     "dropped")
    return kept
