"""The FibrilFit tab of the 3D View's sidebar: Run all and Clear, the model's state and verdict,
then one section per tutorial step with its parameters and its button."""
import json
import math

import bpy

from ..model import params as P
from . import properties
from ..builders import model_stage, structure_trace
from ..builders.model import params_of
from ..builders.scene import find_root
from ..exports.summary import percent
from .operators.common import reached

STATUS = {
    "": ("No model yet: run the steps below in order, or Run all", "INFO"),
    "slab": ("Built: slab", "MESH_CUBE"),
    "anchor": ("Built: slab and anchor", "MESH_UVSPHERE"),
    "linker": ("Built: layer 0 up to the linker", "LINKED"),
    "globule": ("Built: layer 0", "MESH_UVSPHERE"),
    "layers": ("Built: every layer; not baked", "MOD_ARRAY"),
    "baked": ("Baked; not checked", "PHYSICS"),
    "checked": ("Checked", "CHECKMARK"),
}

# Section: (operator, the stage that shows it done), ...
BUTTONS = {
    "Slab": (("fibrilfit.build_slab", "slab"),),
    "Anchor": (("fibrilfit.build_anchor", "anchor"),),
    "Linker": (("fibrilfit.build_linker", "linker"),),
    "Globule": (("fibrilfit.build_globule", "globule"),),
    "Layers": (("fibrilfit.replicate_layers", "layers"),),
    "Simulation": (("fibrilfit.bake", "baked"),),
    "Check": (("fibrilfit.check_intersections", "checked"), ("fibrilfit.join_globules", None),
              ("fibrilfit.render", None), ("fibrilfit.export_pdb", None),
              ("fibrilfit.report", None)),
}


class _Sidebar:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "FibrilFit"


class FIBRILFIT_PT_main(_Sidebar, bpy.types.Panel):
    bl_idname = "FIBRILFIT_PT_main"
    bl_label = "FibrilFit"

    def draw(self, context):
        layout, scene = self.layout, context.scene
        s = scene.fibrilfit
        row = layout.row(align=True)
        row.scale_y = 1.3
        row.operator("fibrilfit.run_all", icon="PLAY")
        row.operator("fibrilfit.clear", icon="TRASH")
        _draw_case(layout, s)
        stage = model_stage(scene)
        text, icon = STATUS[stage]
        layout.label(text=text, icon=icon)
        if reached(stage, "layers"):
            _draw_changes(layout, s, find_root(scene), stage)
        if stage == "checked" and s.verdict:
            _draw_result(layout.box(), s)
        layout.label(text="Lengths in Å: 1 Blender unit = 1 Å")


def _draw_case(layout, s):
    row = layout.row(align=True)
    row.operator("fibrilfit.load_case", icon="FILE_FOLDER")
    row.operator("fibrilfit.save_case", icon="FILE_TICK")
    name = _case_name(s)
    if name:
        layout.label(text=f"Case: {name}", icon="BOOKMARKS")


def _case_name(s) -> str:
    try:
        return json.loads(s.case_metadata or "{}").get("name", "")
    except ValueError:
        return ""


def _draw_changes(layout, s, root, stage):
    """Warn when the panel no longer matches the model a bake or check would use."""
    built, now = params_of(root), properties.compared_values(s)
    changed = properties.changed_fields(s, built, properties.BUILD_SECTIONS, now=now)
    if changed:
        names = ", ".join(name for name, _, _ in changed)
        layout.label(text=f"Changed since the build: {names}", icon="ERROR")
        layout.label(text="Build again (Run all, or the steps) to apply")
    elif reached(stage, "baked") and properties.changed_fields(s, built, ("Simulation",),
                                                                now=now):
        layout.label(text="Simulation settings changed: Bake again to apply", icon="ERROR")


def _draw_result(box, s):
    ok = s.verdict == "successful"
    box.label(text=f"Verdict: {s.verdict}", icon="CHECKMARK" if ok else "ERROR")
    box.label(text=f"Clashing globule pairs: {s.clash_count}")
    box.label(text=f"Worst bond stretch: {percent(s.max_bond_stretch)} "
                   f"({'intact' if s.linker_intact else 'stretched'})")
    box.label(text=f"Accommodated: {'yes' if s.accommodated else 'no'}",
              icon="CHECKMARK" if s.accommodated else "CANCEL")


class _Section(_Sidebar):
    bl_parent_id = "FIBRILFIT_PT_main"
    section = ""

    def draw(self, context):
        layout, s = self.layout, context.scene.fibrilfit
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column()
        for field in properties.fields_in(self.section):
            if field.name == "periodic":  # its checkbox, then M (0 = auto)
                col.prop(s, "use_periodic")
            if field.metadata["kind"] == "points":
                _draw_outline(col, s, field)
                continue
            if field.metadata.get("derived"):  # a switch: off means its default, worked out
                switch = properties.switch_name(field.name)
                col.prop(s, switch)
                row = col.row()
                row.active = getattr(s, switch)
                row.prop(s, field.name)
                continue
            row = col.row()
            if field.name == "periodic":
                row.active = s.use_periodic
            elif field.name in P.NOT_WITH_PERIODIC:
                row.active = not s.use_periodic
            # settle_speed, settle_frames... only matter when the bool field they extend is on
            switch = field.name.split("_")[0]
            if switch != field.name and isinstance(getattr(s, switch, None), bool):
                row.active = getattr(s, switch)
            row.prop(s, field.name)
        stage = model_stage(context.scene)
        for idname, done_at in BUTTONS[self.section]:
            done = done_at is not None and reached(stage, done_at)
            layout.operator(idname, icon="CHECKMARK" if done else "NONE")


def _draw_outline(col, s, field):
    """The core outline: its JSON (editable), where it came from, the file picker, the box."""
    text = s.core_outline.strip()
    try:
        count = len(json.loads(text)) if text else 0
    except ValueError:
        count = -1
    what = ("Core: the slab's box" if not text else
            f"Core: outline of {count} points" if count >= 0 else "Core: outline is not JSON")
    col.label(text=what, icon="MESH_CUBE" if not text else "MOD_SOLIDIFY")
    if text and s.core_outline_file:
        col.label(text=f"from {bpy.path.basename(s.core_outline_file)}")
    col.prop(s, field.name)
    row = col.row(align=True)
    row.operator("fibrilfit.load_outline", icon="FILEBROWSER")
    row.operator("fibrilfit.clear_outline", icon="MESH_CUBE")


def _section_panel(section):
    name = f"FIBRILFIT_PT_{section.lower()}"
    return type(name, (_Section, bpy.types.Panel),
                {"bl_idname": name, "bl_label": section, "section": section})


class FIBRILFIT_PT_check(_Section, bpy.types.Panel):
    bl_idname = "FIBRILFIT_PT_check"
    bl_label = "Check"
    section = "Check"

    def draw(self, context):
        _Section.draw(self, context)
        space = context.space_data
        shading = getattr(space, "shading", None)
        if shading is not None and shading.type == "SOLID" and shading.color_type != "OBJECT":
            row = self.layout.row()
            row.label(text="Red clashes show with colour", icon="INFO")
            row.prop(shading, "color_type", text="")


class FIBRILFIT_PT_structures(_Sidebar, bpy.types.Panel):
    """Import fibril… / Import domain…, and what they measured."""
    bl_idname = "FIBRILFIT_PT_structures"
    bl_label = "Structures"
    bl_parent_id = "FIBRILFIT_PT_main"

    def draw(self, context):
        layout = self.layout
        row = layout.row(align=True)
        row.operator("fibrilfit.import_fibril", icon="FILEBROWSER")
        row.operator("fibrilfit.import_domain", icon="FILEBROWSER")
        for line in structure_lines(structure_trace.measured(context.scene)):
            layout.label(text=line)


def structure_lines(measured: dict) -> list:
    """The panel's lines for the imported structures' measurements."""
    lines = []
    f = measured.get("fibril")
    if f:
        hand = "right" if f["twist"] > 0 else "left"
        twist = math.degrees(f["twist"])
        lines.append(f"{f['file']}: rise {f['rise']:.3f} Å, twist {twist:+.3f}° ({hand}-handed)")
        lines.append(f"{f['protofilaments']} protofilament(s), core {f['core_residues'][0]}-"
                     f"{f['core_residues'][1]}, {f['layers']} layers in the file")
        for a in f["anchors"]:
            lines.append(f"anchor {a['chain']} {a['residue_name']}{a['residue']}: r "
                         f"{a['radius']:.1f} Å" + (" (buried)" if a["buried"] else ""))
    d = measured.get("domain")
    if d:
        lines.append(f"{d['file']} chain {d['chain']}: Rg {d['rg']:.2f} Å, globule "
                     f"{d['globule_diameter']:.1f} Å")
    return lines


SECTION_PANELS = tuple(_section_panel(sec) for sec in properties.SECTIONS if sec != "Check")
CLASSES = (FIBRILFIT_PT_main, *SECTION_PANELS, FIBRILFIT_PT_check, FIBRILFIT_PT_structures)
