"""The FibrilFit tab of the 3D View's sidebar, in the order of the user's question
(docs/guide/sidebar.md#the-panel): the structures (import a fibril and a domain, or load a case);
what the user asks about (linker, domain, protocol, layers or a periodic cell); Run all and the
verdict. Below it, collapsed: the step-by-step build (a sub-panel per step with its settings and
its button), the physics and the search. A setting shows only where it applies; labels are short
enough for the default sidebar width (tests/blender/test_ui.py measures them).

Over 400 lines (415, since the ensemble's button, its lines, the density volume's line and the
linkers' span joined the result box): one class per sidebar section, each thin; the result box
(its runs, report, minimal-linker, fraction and ensemble lines) is the seam for the next split,
into a module of its own."""
import json
import math

import bpy

from ..exports import ensemble_words
from ..model import helix, occupancy, params as P
from ..model.param_checks import NOT_WITH_PERIODIC
from . import (fraction_summary, minimal_summary, panel_words, properties, report_summary,
               result_words, structure_trace)
from .result_words import wrapped
from ..builders import model_stage
from ..builders.stored import params_of
from ..builders.scene import find_root
from .operators.common import reached

STATUS = {
    "": ("No model yet", "INFO"),
    "slab": ("Built: slab", "MESH_CUBE"),
    "anchor": ("Built: slab and anchor", "MESH_UVSPHERE"),
    "linker": ("Built: layer 0 to the linker", "LINKED"),
    "globule": ("Built: layer 0", "MESH_UVSPHERE"),
    "layers": ("Built: every layer; not baked", "MOD_ARRAY"),
    "baked": ("Baked; not checked", "PHYSICS"),
    "checked": ("Checked", "CHECKMARK"),
}

# The step-by-step sub-panels: (label, the parameter section it shows, its buttons); a button is
# (operator, the stage that shows it done). The bake's settings are under Physics.
STEPS = (
    ("Slab", "Slab", (("fibrilfit.build_slab", "slab"),)),
    ("Anchor", "Anchor", (("fibrilfit.build_anchor", "anchor"),)),
    ("Linker", "Linker", (("fibrilfit.build_linker", "linker"),)),
    ("Globule", "Globule", (("fibrilfit.build_globule", "globule"),)),
    ("Layers", "Layers", (("fibrilfit.replicate_layers", "layers"),)),
    ("Bake", None, (("fibrilfit.bake", "baked"),)),
    ("Check", "Check", (("fibrilfit.check_intersections", "checked"),
                        ("fibrilfit.join_globules", None), ("fibrilfit.render", None),
                        ("fibrilfit.export_pdb", None))),
)
# Settings of the question's domain drawn beside it (after the globule's diameter) rather than in
# the Globule step: the domain's shape is chosen next to the domain (issue #33).
BESIDE_DOMAIN = ("domain_shape",)


class _Sidebar:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "FibrilFit"


class FIBRILFIT_PT_main(_Sidebar, bpy.types.Panel):
    bl_idname = "FIBRILFIT_PT_main"
    bl_label = "FibrilFit"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = False
        layout.use_property_decorate = False
        draw_structures(layout.column(), context)
        layout.separator()
        draw_question(layout.column(), context.scene.fibrilfit,
                      structure_trace.measured(context.scene))
        layout.separator()
        draw_run(layout.column(), context)


# ---- the structures --------------------------------------------------------------------------

START = ("Start here: import a fibril and a domain, or Run all for the tutorial's model "
         "(docs: Tutorial)")


def draw_structures(col, context):
    s = context.scene.fibrilfit
    if is_empty(context.scene):
        wrapped(col, START, "HAND")
    row = col.row(align=True)
    row.operator("fibrilfit.import_fibril", icon="FILEBROWSER")
    row.operator("fibrilfit.import_domain", icon="FILEBROWSER")
    col.operator("fibrilfit.import_full_length", icon="FILEBROWSER")
    draw_domains(col, s)
    row = col.row(align=True)
    row.operator("fibrilfit.load_case", icon="FILE_FOLDER")
    row.operator("fibrilfit.save_case", icon="FILE_TICK")
    name = _case_name(s)
    if name:
        col.label(text=f"Case: {name}", icon="BOOKMARKS")
    for line in structure_lines(structure_trace.measured(context.scene)):
        col.label(text=line)


def is_empty(scene) -> bool:
    """Nothing yet (issue #45): no model, no structure imported, no domain, no case loaded."""
    s = scene.fibrilfit
    return (find_root(scene) is None and not structure_trace.measured(scene)
            and not len(s.domains) and not s.case_metadata)


def draw_domains(col, s):
    """Several domains per chain (docs/guide/sidebar.md#domains): the list, from the core
    outward, with each domain's linker to the next, and remove and move buttons; one domain (or
    none) keeps the single globule's look."""
    if len(s.domains) < 2:
        return
    col.label(text=f"{len(s.domains)} domains, core outward:")
    row = col.row()
    row.template_list("FIBRILFIT_UL_domains", "", s, "domains", s, "domain_index",
                      rows=min(len(s.domains), 5))
    side = row.column(align=True)
    side.operator("fibrilfit.domain_move", icon="TRIA_UP", text="").direction = "UP"
    side.operator("fibrilfit.domain_move", icon="TRIA_DOWN", text="").direction = "DOWN"
    side.operator("fibrilfit.domain_remove", icon="X", text="")
    if 0 <= s.domain_index < len(s.domains):  # the selected one, in full, and its linker
        i, e = s.domain_index, s.domains[s.domain_index]
        col.label(text=f"{i + 1}: {bpy.path.basename(e.filepath)} chain {e.chain}")
        if i < len(s.domains) - 1:
            col.prop(e, "linker", text="Linker to next (residues)")
        else:
            col.label(text="the outermost: no linker after it")


def _case_name(s) -> str:
    try:
        return json.loads(s.case_metadata or "{}").get("name", "")
    except ValueError:
        return ""


def structure_lines(measured: dict) -> list:
    """The panel's lines for the imported structures' measurements, each short enough for the
    default sidebar width."""
    lines = []
    f = measured.get("fibril")
    if f:
        lines.append(f"Fibril {f['file']}")
        lines.append(f"rise {f['rise']:.3f} Å, twist {math.degrees(f['twist']):+.3f}°")
        lines.append(f"{helix.handedness(f['twist'])}, {f['protofilaments']} protofilament(s)")
        pieces = f.get("core_segments") or [f["core_residues"]]
        lines.append("core " + ", ".join(f"{a}-{b}" for a, b in pieces)
                     + f", {f['layers']} layers in the file")
        if f.get("rungs", 1) > 1:  # docs/guide/structures.md#beta-solenoids
            lines.append(f"β-solenoid: {f['rungs']} rungs per molecule (layer)")
        for a in f["anchors"]:
            lines.append(f"anchor {a['chain']} {a['residue_name']}{a['residue']}: r "
                         f"{a['radius']:.1f} Å" + (", buried" if a["buried"] else ""))
    d = measured.get("domain")
    if d:
        lines.append(f"Domain {d['file']} chain {d['chain']}")
        lines.append(f"Rg {d['rg']:.2f} Å, globule {d['globule_diameter']:.1f} Å")
    return lines


# ---- the question ----------------------------------------------------------------------------

def draw_question(col, s, measured: dict | None = None):
    """Linker, domain, protocol, then the fibril: layers, or a periodic cell of M layers. Under
    the linker, after an import that did not give it, a note until it is set (`measured`:
    structure_trace.measured)."""
    for field in properties.question_fields():
        if field.name in ("layers", "periodic"):
            continue
        col.prop(s, field.name)
        if field.name == "linker":
            for line in linker_note(s.linker, (measured or {}).get("linker")):
                col.label(text=line, icon="INFO" if line.startswith("Not") else "BLANK1")
        if field.name == "globule_diameter":
            for name in BESIDE_DOMAIN:  # "Domain shape" would be cut beside its drop-down
                col.prop(s, name, text="Shape")
    col.prop(s, "use_periodic")
    col.prop(s, "periodic" if s.use_periodic else "layers")


def linker_note(linker: int, kept: dict | None) -> list:
    """The note under the linker (issue #45 item 8): after an import whose files did not give
    it (`kept`: what the import left, structure_trace's "linker"), while it still holds the
    value the import left."""
    if not kept or kept.get("from_files") or linker != kept.get("value"):
        return []
    return ["Not in the files: set the residues", "from the core's anchor to the domain"]


# ---- Run all and the verdict -----------------------------------------------------------------

def draw_run(col, context):
    scene = context.scene
    s = scene.fibrilfit
    row = col.row(align=True)
    row.scale_y = 1.6  # the panel's main action, taller than every other button
    row.operator("fibrilfit.run_all", icon="PLAY")
    row.operator("fibrilfit.clear", icon="TRASH")
    col.operator("fibrilfit.report", icon="FILE")  # the whole answer as one page (report.md)
    row = col.row(align=True)  # the two maps of walks, side by side
    row.operator("fibrilfit.minimal_linker", icon="SORTSIZE")
    row.operator("fibrilfit.largest_fraction", icon="MOD_ARRAY")
    stage = model_stage(scene)
    text, icon = STATUS[stage]
    col.label(text=text, icon=icon)
    if reached(stage, "layers"):
        _draw_changes(col, s, find_root(scene), stage)
    if stage == "checked" and s.verdict:
        box = col.box()
        draw_result(box, s, params_of(find_root(scene)))
        box.operator("fibrilfit.sample_ensemble", icon="OUTLINER_OB_POINTCLOUD")
        if s.ensemble_summary:
            for line in ensemble_words.lines(json.loads(s.ensemble_summary)):
                wrapped(box, line, "INFO")
    if s.report_summary:
        draw_report(col.box(), s)
    for kept, summary_module in MAPS:
        if getattr(s, kept):
            draw_map(col.box(), s, kept, summary_module)
    col.label(text="Lengths in Å (1 unit = 1 Å)")


def _draw_changes(col, s, root, stage):
    """Warn when the panel no longer matches the model a bake or check would use."""
    built, now = params_of(root), properties.compared_values(s)
    changed = properties.changed_fields(s, built, properties.BUILD_SECTIONS, now=now)
    if changed:
        names = panel_words.labels(name for name, _, _ in changed)
        wrapped(col, f"Changed since the build: {names}", "ERROR")
        wrapped(col, "Build again (Run all, or the steps) to apply", "BLANK1")
    elif reached(stage, "baked") and properties.changed_fields(s, built, ("Simulation",),
                                                                now=now):
        wrapped(col, "Physics changed: Bake again to apply", "ERROR")


def draw_result(box, s, p: P.Params | None = None):
    """The last check of the model `p` (the scene's): the answer first, then its evidence (the
    linkers' span in the printed result's words), in the glossary's words
    (ui/result_words.py; one failed run is "no layout found", never "does not fit")."""
    p = p or properties.read_params(s)
    for text, icon in result_words.run_lines(
            answer=s.answer, clashes=s.clash_count, stretch=s.max_bond_stretch,
            tolerance=p.stretch_tolerance, linker=p.linker, bound=s.bound,
            span=json.loads(s.linker_stretch) if s.linker_stretch else None):
        box.label(text=text, icon=icon)
    if s.clash_count:
        box.label(text="Red: clash; orange: graze", icon="INFO")


def draw_report(box, s):
    """The last report's answer, P(fit), minimal linker and bound, and Open report; greyed,
    without its ticks, when the panel's values are no longer those it answers
    (result_words.draw_kept)."""
    try:
        summary = json.loads(s.report_summary)
    except ValueError:
        return
    result_words.draw_kept(box, summary, report_summary.summary_lines(summary),
                           properties.compared_values(s), ignore=("seed",))
    box.operator("fibrilfit.open_report", icon="URL")


# The maps of walks the panel keeps: (scene setting, the module that makes and draws it)
MAPS = (("minimal_map", minimal_summary), ("fraction_map", fraction_summary))


def draw_map(box, s, kept: str, summary_module):
    """The last map kept in `kept` (Minimal linker…'s, per diameter; Largest fraction…'s, per
    diameter and linker with its bracket), or "cancelled"; greyed when the panel's values are
    no longer its own (result_words.draw_kept)."""
    try:
        summary = json.loads(getattr(s, kept))
    except ValueError:
        return
    result_words.draw_kept(box, summary, [], properties.compared_values(s),
                           ignore=summary_module.NOT_ASKED)
    summary_module.draw(box, summary)


# ---- the collapsed sub-panels ----------------------------------------------------------------

def shown(field, s) -> bool:
    """Whether a setting applies to the panel's model (docs/guide/sidebar.md#the-panel)."""
    name = field.name
    if field.metadata.get("question") or name in BESIDE_DOMAIN:
        return False  # at the top of the panel
    if _search(field):
        return s.protocol == "inflate"
    if name == "domain_linker" and len(s.domains):
        return False  # the list of domains has each linker (draw_domains)
    if name == "image_updates":
        return s.use_periodic
    pattern = next((k for k, names in occupancy.PATTERN_FIELDS.items() if name in names), None)
    if pattern is not None:  # a mixed fibril's settings: those of the pattern chosen
        return s.pattern == pattern
    if name in NOT_WITH_PERIODIC:
        return not s.use_periodic
    switch = name.split("_")[0]  # settle_speed, settle_frames: only with settle on
    if switch != name and isinstance(getattr(s, switch, None), bool):
        return getattr(s, switch)
    return True


def draw_fields(col, s, fields):
    """Settings, one per line (a derived one: its switch, then its value, greyed while off)."""
    for field in fields:
        if not shown(field, s):
            continue
        if field.metadata["kind"] == "points":
            _draw_outline(col, s, field)
        elif field.metadata.get("derived"):
            switch = properties.switch_name(field.name)
            col.prop(s, switch)
            sub = col.column()
            sub.active = getattr(s, switch)
            sub.prop(s, field.name)
        else:
            col.prop(s, field.name)


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


class _Closed(_Sidebar):
    bl_parent_id = "FIBRILFIT_PT_main"
    bl_options = {"DEFAULT_CLOSED"}


class FIBRILFIT_PT_steps(_Closed, bpy.types.Panel):
    """The tutorial's steps one by one: each sub-panel builds the model up to its part."""
    bl_idname = "FIBRILFIT_PT_steps"
    bl_label = "Step by step"

    def draw(self, context):
        wrapped(self.layout.column(), "Each step builds the model up to itself from the "
                                      "values above and below")


class _Step(_Sidebar):
    bl_parent_id = "FIBRILFIT_PT_steps"
    section = None
    buttons = ()

    def draw(self, context):
        layout, s = self.layout, context.scene.fibrilfit
        layout.use_property_split = False
        layout.use_property_decorate = False
        if self.section:
            draw_fields(layout.column(), s, properties.fields_in(self.section))
        stage = model_stage(context.scene)
        for idname, done_at in self.buttons:
            done = done_at is not None and reached(stage, done_at)
            layout.operator(idname, icon="CHECKMARK" if done else "NONE")


def _step_panel(label, section, buttons):
    name = f"FIBRILFIT_PT_step_{label.lower()}"
    return type(name, (_Step, bpy.types.Panel), {"bl_idname": name, "bl_label": label,
                                                 "section": section, "buttons": buttons})


def _search(field) -> bool:
    """The inflate schedule (params section "Search"; the bake reads it, so for the staleness
    checks it counts as "Simulation": properties.section_of)."""
    return field.metadata.get("section") == "Search"


class FIBRILFIT_PT_physics(_Closed, bpy.types.Panel):
    """The bake's settings: gravity and seed, time, substeps, settling (and a cell's images)."""
    bl_idname = "FIBRILFIT_PT_physics"
    bl_label = "Physics"

    def draw(self, context):
        self.layout.use_property_decorate = False
        draw_fields(self.layout.column(), context.scene.fibrilfit,
                    [f for f in properties.fields_in("Simulation") if not _search(f)])


class FIBRILFIT_PT_search(_Closed, bpy.types.Panel):
    """The inflate protocol's schedule; nothing to set under the tutorial's."""
    bl_idname = "FIBRILFIT_PT_search"
    bl_label = "Search"

    def draw(self, context):
        s = context.scene.fibrilfit
        self.layout.use_property_decorate = False
        if s.protocol != "inflate":
            wrapped(self.layout.column(), "The tutorial protocol has no settings here; "
                                          "Protocol: Inflate shows its schedule", "INFO")
            return
        draw_fields(self.layout.column(), s, [f for f in P.fields() if _search(f)])


STEP_PANELS = tuple(_step_panel(*step) for step in STEPS)
CLASSES = (FIBRILFIT_PT_main, FIBRILFIT_PT_steps, *STEP_PANELS, FIBRILFIT_PT_physics,
           FIBRILFIT_PT_search)
