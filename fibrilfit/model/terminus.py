"""A buried anchor's exit in the model's terms (docs/model/buried-terminus.md#model): how many
of a chain's linker residues its exit spends, where the free linker starts, and the verdict
"no exit" when the linker is too short to leave the core. Plain Python over a Params.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .answer import NO_EXIT
from .param_spec import SEALED


@dataclass(frozen=True)
class ChainExit:
    """One chain's way out of the core."""

    residues: int  # linker residues spent from the anchor to the surface (0: on the surface)
    start: tuple  # (x, y) Å, the layer's frame: where the free linker starts (the model's anchor)
    left: int  # the linker after the exit, counting the bead at the exit (Params.free_linker)
    path: np.ndarray | None  # (k, 3) the exit's path, the buried CA first; None on the surface

    @property
    def sealed(self) -> bool:
        """No path clear of the core's atoms leaves the anchor (exit_residues SEALED)."""
        return self.residues >= SEALED

    @property
    def no_exit(self) -> bool:
        """The linker ends before the surface (or nothing leaves): no layout can exist."""
        return self.left < 1


def chain_exit(p) -> ChainExit:
    """What a Params' chain spends on its exit and where its free linker starts: for a bound
    on the linker, the residues left after the exit (`left`) from `start` (protofilament 0's;
    with interface termini the most any protofilament spends, Params.exit_spent)."""
    path = None if p.exit_path is None else np.asarray(p.exit_path, dtype=float)
    return ChainExit(int(p.exit_spent), tuple(p.anchor_xy), int(p.free_linker), path)


def no_exit_result(p) -> dict:
    """The outcome of a run settled without a model: the linker cannot reach the surface, so no
    layout with intact linkers exists (a verdict, not an error; nothing is simulated)."""
    way = chain_exit(p)
    needs = ("no path clear of the core's atoms leaves the anchor" if way.sealed else
             f"the exit from the buried anchor to the core's surface needs {way.residues} "
             f"residue(s) beyond the anchor and the linker has {p.linker} (counting the "
             f"anchor): at least {way.residues + 1} are needed")
    return {"verdict": NO_EXIT, "answer": NO_EXIT, "accommodated": False, "linker_intact": False,
            "intersecting_faces": 0, "clashing_pairs": [], "grazing_pairs": [],
            "max_overlap": 0.0, "max_bond_stretch": None, "linker_stretch": None,
            "frames_simulated": 0,
            "cancelled": False, "no_exit": needs,
            "exit_needs": None if way.sealed else way.residues + 1, "warnings": []}
