"""The list of a chain's domains (docs/guide/sidebar.md#domains): remove one, move one up or
down, and Import full-length model… (its folded domains and linkers, segmented as
`--full-length` does). Thin over ui/domain_list.py and structure/domain_list.py."""
import bpy

from .. import domain_list, panel_words, structure_trace
from ...structure import domain_list as logic
from . import common
from .structures import _ImportBase


def _fibril(context):
    return structure_trace.measured(context.scene).get("fibril")


def _refuse_index(op, s) -> bool:
    if not 0 <= s.domain_index < len(s.domains):
        op.report({"ERROR"}, "No domain selected: import one (Import domain…) and select it in "
                             "the list")
        return True
    return False


class FIBRILFIT_OT_domain_remove(bpy.types.Operator):
    bl_idname = "fibrilfit.domain_remove"
    bl_label = "Remove domain"
    bl_description = "Remove the selected domain from the chain"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        s = common.settings(context)
        if _refuse_index(self, s):
            return {"CANCELLED"}
        first = s.domain_index == 0
        e = s.domains[s.domain_index]
        structure_trace.remove_traces(context.scene, "domain",
                                      structure_trace.entry_key(e.filepath, e.chain, e.residues))
        s.domains.remove(s.domain_index)
        s.domain_index = min(s.domain_index, max(len(s.domains) - 1, 0))
        domain_list.filled(s, _fibril(context), first_changed=first)
        return {"FINISHED"}


class FIBRILFIT_OT_domain_move(bpy.types.Operator):
    bl_idname = "fibrilfit.domain_move"
    bl_label = "Move domain"
    bl_description = ("Move the selected domain one place towards the core (up) or outward "
                      "(down); its linker to the next moves with it")
    bl_options = {"REGISTER", "UNDO"}
    direction: bpy.props.EnumProperty(items=(("UP", "Up", "Towards the core"),
                                             ("DOWN", "Down", "Outward")), default="UP")

    def execute(self, context):
        s = common.settings(context)
        if _refuse_index(self, s):
            return {"CANCELLED"}
        i = s.domain_index
        j = i - 1 if self.direction == "UP" else i + 1
        if not 0 <= j < len(s.domains):
            self.report({"ERROR"}, f"The domain is already the {'first' if j < 0 else 'last'} "
                                   f"of the chain")
            return {"CANCELLED"}
        s.domains.move(i, j)
        s.domain_index = j
        domain_list.filled(s, _fibril(context), first_changed=0 in (i, j))
        return {"FINISHED"}


class FIBRILFIT_OT_import_full_length(_ImportBase, bpy.types.Operator):
    bl_idname = "fibrilfit.import_full_length"
    bl_label = "Import full-length model…"
    bl_description = ("Segment a predicted model of the whole chain (pLDDT in the B-factor "
                      "column, the fibril's numbering) as --full-length does: its folded domains "
                      "on the linker's side of the core and the linkers between them replace "
                      "the chain's domains. Import the fibril first")

    def _import(self, context):
        path, fibril = bpy.path.abspath(self.filepath), _fibril(context)
        seg, doms = logic.full_length_domains(path, fibril)  # refused before the list changes
        s = common.settings(context)
        s.domains.clear()
        structure_trace.remove_traces(context.scene, "domain")  # the list's domains replaced
        for dom in doms:
            domain_list.add(s, path, dom, option="--full-length")
        s.domain_index = 0
        domain_list.set_gaps(s, fibril)
        names = domain_list.filled(s, fibril, first_changed=True)
        structure_trace.store(context.scene, "full_length", seg.to_dict())
        gaps = [e.linker for e in s.domains][:-1]
        self.report({"INFO"}, f"{seg.file}: {len(doms)} domain(s)" + _said(doms, gaps, names))
        return {"FINISHED"}


def _said(doms, gaps, names) -> str:
    ranges = ", ".join(f"{d.residues[0]}-{d.residues[1]}" for d in doms)
    between = f", linkers between {', '.join(map(str, gaps))}" if gaps else ""
    return f" ({ranges}){between}; set {panel_words.labels(names)}"


CLASSES = (FIBRILFIT_OT_domain_remove, FIBRILFIT_OT_domain_move,
           FIBRILFIT_OT_import_full_length)
