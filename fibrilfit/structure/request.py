"""Which structure files to read, and how: the structure request, declared once for `inspect`,
`run`, `report`, `minimal-linker`, `sweep`, a case's [structure] and the Python API.

    --fibril FILE  --domain FILE (repeatable)  --full-length FILE  --terminus N|C
    --anchor-residue R  --domain-chain C  --domain-residues A-B

Measuring the files and merging the measured values under the explicit ones is from_files.py's.
Plain Python: no bpy.
"""
from __future__ import annotations

import dataclasses

from ..plans import Plan, option

TERMINUS = "C"  # the core terminus that carries the linker unless --terminus says otherwise
GROUP = "structure files (PDB/mmCIF, optionally .gz)"


@dataclasses.dataclass(frozen=True)
class StructureRequest(Plan):
    """The structure files a model is measured from (all optional)."""

    fibril: str | None = option(None, "a fibril structure: fills rise, twist, protofilaments, "
                                      "core outline, anchor", kind="path", metavar="FILE",
                                group=GROUP)
    domain: tuple = option((), "a domain structure: fills globule_diameter from its Rg; repeat "
                               "it for several domains on one chain, in chain order from the "
                               "core outward", kind="path", repeat=True, metavar="FILE",
                           group=GROUP)
    full_length: str | None = option(None, "a predicted model of the whole chain in the "
                                           "fibril's numbering (pLDDT in the B-factor column): "
                                           "its folded domains and linkers (instead of --domain)",
                                     kind="path", metavar="FILE", group=GROUP)
    terminus: str = option(TERMINUS, "the core terminus that carries the linker",
                           choices=("N", "C"), group=GROUP)
    anchor_residue: int | None = option(None, "anchor on this residue instead of the core's "
                                              "terminus", kind=int, metavar="R", group=GROUP,
                                noun="a residue number")
    domain_chain: tuple = option((), "the domain's chain [default: first]; once for every "
                                     "--domain, or once for all", kind=str, repeat=True,
                                 metavar="C", group=GROUP)
    domain_residues: tuple = option((), "the domain's residues [default: all]; once for every "
                                        "--domain, or once for all", kind=str, repeat=True,
                                    metavar="A-B", group=GROUP)

    @property
    def any(self) -> bool:
        """Whether a file is named at all."""
        return bool(self.fibril or self.domain or self.full_length)

    def to_case(self) -> dict:
        """The request as a case's [structure] (model/cases.py): only what is set, a field
        given once as one value; the terminus only beside a fibril."""
        if not self.any:
            return {}
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value in (None, ()):
                continue
            out[f.name] = value[0] if isinstance(value, tuple) and len(value) == 1 else (
                list(value) if isinstance(value, tuple) else value)
        if not self.fibril:
            out.pop("terminus", None)
        return out


def from_case(structure: dict) -> StructureRequest:
    """A case's [structure] (cases.Case.structure, files absolute) as the request it stands for."""
    return StructureRequest.make(**{k: v for k, v in structure.items() if v is not None})
