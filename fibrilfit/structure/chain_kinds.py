"""Why a fibril file's chains share too few residues to stack: the kinds of chain it holds, each
by its residue numbers (docs/guide/structures.md#read-survey).

A heteromeric fibril (two proteins, such as TDP-43 with annexin A11) or one molecule deposited as
several chains, one per ordered segment, has chains whose residue numbers do not overlap: the
layers of one kind of chain are not copies of the other's, and FibrilFit's fibril is made of one.
"""
from __future__ import annotations

SHOWN = 4  # chain names shown per kind


def kinds(chains) -> list:
    """[(first, last, [chain names])] per distinct residue range, most chains first."""
    by = {}
    for c in chains:
        by.setdefault((int(c.residues[0]), int(c.residues[-1])), []).append(c.name)
    return sorted(((a, b, names) for (a, b), names in by.items()), key=lambda k: -len(k[2]))


def why(chains, shared: int) -> str:
    """The refusal's reason when the chains share `shared` residue numbers (too few)."""
    found = kinds(chains)
    if len(found) < 2:
        return f"the chains share {shared} residue numbers: the layers do not stack"
    parts = [f"residues {a}-{b}: {len(names)} chains, {', '.join(names[:SHOWN])}"
             + (", …" if len(names) > SHOWN else "") for a, b, names in found]
    return (f"the chains share {shared} residue numbers: they are of {len(found)} kinds ("
            + "; ".join(parts) + "): a heteromeric fibril, or one molecule's segments in "
            "separate chains; FibrilFit reads a fibril of one kind of chain")
