"""`inspect`: structure files measured, nothing built (no bpy)."""
from __future__ import annotations

from ..exits import UsageError
from ..structure import termini
from ..structure.from_files import measure_files
from .results import InspectResult


def inspect(plan) -> InspectResult:
    """The measurements of the files `plan.structure` names (an InspectPlan): the fibril's
    axis, rise, twist, protofilaments, outline and anchors; each domain's size and shape; the
    model values they give and where the linker's length comes from."""
    import gemmi
    from .. import structure
    from ..structure import inspect_text
    from ..structure.mapping import linker_source
    if not plan.structure.any:
        raise UsageError("inspect: give --fibril FILE, --domain FILE and/or --full-length FILE")
    m = measure_files(plan.structure, inspect=True)
    fib, doms, seg = m.fibril, m.domains, m.segmentation
    dom = doms[0] if doms else None
    values = structure.model_values(fib, dom, more_domains=doms[1:])
    sources = ({"linker": linker_source(fib, dom, explicit=False)} if fib or dom else {})
    doc = {"fibril": fib and fib.to_dict(), "domain": dom and dom.to_dict(),
           "model_values": values, "sources": sources, "gemmi_version": gemmi.__version__}
    if seg is not None:
        doc.update(full_length=seg.to_dict(), domains=seg.domains, linkers=seg.linkers)
    if len(doms) > 1:
        doc["domains_measured"] = [d.to_dict() for d in doms]
    text = inspect_text.text(fib, dom, values, segmentation=seg, more_domains=doms[1:])
    if fib is not None:  # what `run` will do with them (docs/guide/structures.md#deposited-survey)
        doc["run"] = termini.run_check(m)
        text += "\n" + termini.run_line(doc["run"])
    return InspectResult(doc, text=text)
