"""Read fibril and domain structures (PDB / mmCIF, via gemmi) and measure what the model needs.

Geometry only: no bpy. gemmi is imported only when a file is read.

    fib = measure_fibril("6cu7.pdb")          # FibrilGeometry: rise, twist, outline, anchors, ...
    dom = measure_domain("1ubq.pdb")          # DomainSize: rg, globule_diameter
    model_values(fib, dom)                    # {"rise": ..., "twist": ..., "globule_diameter": ...}
"""
from .domain import DomainSize, body_frame, measure as measure_domain, parse_range
from .errors import StructureError
from .fibril import FibrilGeometry, measure as measure_fibril
from .mapping import model_values

__all__ = ["DomainSize", "FibrilGeometry", "StructureError", "body_frame", "measure_domain",
           "measure_fibril",
           "model_values", "parse_range"]
