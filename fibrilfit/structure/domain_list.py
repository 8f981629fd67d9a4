"""Several domains per chain as the sidebar keeps them (docs/guide/sidebar.md#domains): a list of
measured domains in chain order from the core outward, each the command line's `--domain FILE`
(with its chain and residues) or one folded domain of a `--full-length` model, and the linker
from each to the next (`--domain-linker`). The model values come from the command line's own
functions (full_length.segment, from_files.merged, mapping.domain_gaps and
linker_from_numbering), so the panel's list gives the command line's Params for the same
options. Plain Python: no bpy.

A fibril, where one was imported, is its measurement as JSON (FibrilGeometry.to_dict(), the
outline left out): only its core residues, terminus, anchor and tail are read here.
"""
from __future__ import annotations

import json
from types import SimpleNamespace

from . import from_files, full_length, mapping
from .domain import DomainSize, measure as measure_domain
from .errors import StructureError

# The real-shape rows: taken from the list for the panel's domain_shape (none for the sphere,
# as the command line gives none); the diameters are the panel's own fields, filled from it.
SHAPE_PARAMS = tuple(k for k in mapping.DOMAIN_PARAMS
                     if k not in ("globule_diameter", "domain_diameters", "domain_linker"))
FULL_LENGTH = "Import full-length model…"


def side(fibril: dict | None) -> str:
    """The side of the core that carries the linker: "N" for a fibril imported with terminus N,
    else "C" (the command line's --terminus)."""
    return "N" if fibril and fibril.get("terminus") == "N" else "C"


def measure(path, *, chain: str | None = None, residues: str | None = None,
            option: str = "--domain", fibril: dict | None = None) -> DomainSize:
    """One domain of the list, measured as the command line measures it (structure.domain's
    measure). Always with its outgoing linker's point: which domain is last can change in the
    list, and the last one's point is never read (mapping.further_shapes)."""
    return measure_domain(path, chain=chain, residues=residues, option=option,
                          follows=side(fibril) == "C", outgoing=True)


def to_text(dom: DomainSize) -> str:
    """A measured domain as the JSON an entry of the list keeps, its real shape included."""
    return json.dumps({**dom.to_dict(), "geometry": dom.geometry})


def from_text(text: str) -> DomainSize:
    return DomainSize(**json.loads(text))


def full_length_domains(path, fibril: dict | None) -> tuple:
    """(Segmentation, [DomainSize]) of a predicted full-length model: its folded domains on the
    linker's side of the fibril's core, from the core outward, as `--full-length` finds them
    (structure/from_files.py's domain_specs and measure_files)."""
    if not fibril:
        raise StructureError(FULL_LENGTH, "import the fibril first (Import fibril…), whose "
                                          "core tells the model's domains from its core and "
                                          "which side carries the linker")
    seg = full_length.segment(path, fibril["core_residues"])
    picked = seg.chain_order(side(fibril))
    if not picked:
        raise StructureError(full_length.OPTION, full_length.no_domain(seg.file))
    doms = [measure(path, chain=seg.chain, residues=f"{d['first']}-{d['last']}",
                    option=full_length.OPTION, fibril=fibril) for d in picked]
    return seg, doms


def gaps(doms: list, fibril: dict | None) -> list | None:
    """Residues between consecutive domains from their numbering (mapping.domain_gaps), or None
    when it does not run outward (then the user sets each linker)."""
    return mapping.domain_gaps(doms, side(fibril))


def numbering_linker(fibril: dict | None, dom: DomainSize) -> int | None:
    """The linker (with the anchor) from the fibril's and the first domain's shared numbering,
    as the command line takes it (mapping.linker_from_numbering); None without it."""
    if not fibril:
        return None
    found = mapping.linker_from_numbering(SimpleNamespace(**fibril), dom)
    return None if found is None else found[0]


def shape_values(doms: list, linkers: list, *, shape: str, residue_radius: float,
                 residue_spacing: float) -> dict:
    """The domains' model values that `--domain` (each of `doms`) `--domain-linker` (`linkers`,
    one per gap) `--domain-shape shape` give beside the diameters: the real shape's rows,
    joints and exits (None where the shape takes none) and domain_linker."""
    explicit = {"domain_shape": shape, "residue_radius": residue_radius,
                "residue_spacing": residue_spacing}
    values, _ = from_files.merged(None, list(doms), None, explicit)
    out = {k: values.get(k) for k in SHAPE_PARAMS}
    out["domain_linker"] = list(linkers[:len(doms) - 1]) if len(doms) > 1 else None
    return out


def sizes(doms: list) -> dict:
    """The diameters the list fills: the first domain's globule_diameter and the others'
    domain_diameters (None with one domain)."""
    return {"globule_diameter": doms[0].globule_diameter,
            "domain_diameters": [d.globule_diameter for d in doms[1:]] or None}
