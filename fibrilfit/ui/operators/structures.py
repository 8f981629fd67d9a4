"""Import fibril… / Import domain…: file browsers over structure.measure_* that fill the panel's
parameters, keep the measurements and put the fibril's CA trace on the model's core (same
axis, same layer phase: structure/trace.py's on_model)."""
import bpy
import numpy as np

from ...model import params as P
from ...builders.model import find_model
from ...exports.dressing import model_points
from .. import domain_list, panel_words, properties, structure_trace
from ...structure import domain_list as domain_list_logic, from_files, measure_fibril, trace
from ..view import frame_points
from . import common

GLOB = "*.pdb;*.ent;*.cif;*.mmcif;*.mcif;*.gz"


def _fill(context, fib, dom) -> list:
    """Write the measured values into the panel. Returns the names written."""
    current = common.panel_params(context)
    # The domain's real shape is kept whatever the panel's Domain shape is now, so that choosing
    # hull or spheres later needs no new import (the sphere ignores it).
    applied, block = from_files.split(fib, dom, explicit=set(),
                                      known={f.name for f in P.fields()},
                                      residue_radius=current.residue_radius, shape="hull")
    properties.write_params(common.settings(context), current.replace(**applied))
    return sorted(applied), block["not_in_model"]


def _on_model(p: P.Params, path, fib) -> list:
    """The file's CA trace on the panel's model: its layers on the model's layers, centred in
    its stack (or its periodic cell)."""
    chains = trace.ca_trace(path, fib)
    moved, _ = trace.on_model(chains, trace.relative_layers(fib), p.periodic or p.layers,
                              p.rise, p.twist)
    return moved


def _show_fibril(context, path, fib, p: P.Params, terminus: str = "C",
                 anchor_residue: int | None = None) -> None:
    """The fibril's CA trace on the model `p`, and its measurement kept (the outline counted),
    with the file's path, terminus and anchor residue as asked: what a report made from the panel
    names and measures again (structure_trace.request)."""
    ob = structure_trace.add_trace(context.scene, _on_model(p, path, fib), fib.file)
    structure_trace.place_fibril(ob, trace.relative_layers(fib), p)
    summary = {k: v for k, v in fib.to_dict().items() if k != "core_outline"}
    summary["outline_points"] = len(fib.core_outline)
    summary["asked"] = {"path": str(path), "terminus": terminus,
                        "anchor_residue": anchor_residue}
    structure_trace.store(context.scene, "fibril", summary)


def _show_domain(context, entry, dom, p: P.Params) -> None:
    """The CA trace of the list's domain `entry` beside the globule of the model `p`, after the
    other domains' (structure_trace.place_domains), and its measurement kept."""
    residues = entry.residues or None
    chains = trace.domain_ca(entry.filepath, chain=entry.chain or None, residues=residues,
                             option=entry.option)
    key = structure_trace.entry_key(entry.filepath, entry.chain, entry.residues)
    ob = structure_trace.add_trace(context.scene, chains, dom.file, kind="domain", entry=key)
    ob[structure_trace.REACH] = max(float(np.linalg.norm(xyz, axis=1).max())
                                    for _, _, xyz in chains)
    structure_trace.place_domains(context.scene, p)
    structure_trace.store(context.scene, "domain", dom.to_dict())


def frame_structures(context) -> None:
    """The imported structures (and the model, if built) framed in the window's 3D Views; none
    in the background or without a 3D View (ui/view.py)."""
    pts = structure_trace.points(context.scene)
    model = find_model(context.scene)
    if model is not None:
        pts = np.concatenate([pts, model_points(model)])
    frame_points(context, pts)


def show_measured(context, m, p: P.Params, terminus: str = "C",
                  anchor_residue: int | None = None) -> None:
    """A case's [structure] as Import fibril…, Import domain… and Import full-length model…
    leave the panel (Load case; `m`: structure.from_files.Measured, `p` the case's Params,
    already in the panel): the chain's domains in the list with their linkers to the next
    (p.domain_linker), the imported structures' traces and measurements in place of any before."""
    s = common.settings(context)
    structure_trace.remove_all(context.scene)
    domain_list.replace(s, [(f, d) for (f, _, _), d in zip(m.specs, m.domains)], m.option,
                        p.domain_linker)
    if m.fibril is not None:
        _show_fibril(context, m.fibril_path, m.fibril, p, terminus, anchor_residue)
    if m.segmentation is not None:
        structure_trace.store(context.scene, "full_length", m.segmentation.to_dict())
    for e, dom in zip(s.domains, m.domains if m.segmentation is None else ()):
        _show_domain(context, e, dom, p)  # each domain's trace, as importing them leaves them
    frame_structures(context)


def linker_said(context, set_now: bool) -> str:
    """After an import: whether the files gave the linker (a modelled tail, the shared
    numbering), kept for the panel's note (panels.linker_note); the note's words for the
    import's report when they did not."""
    s = common.settings(context)
    kept = structure_trace.measured(context.scene).get("linker") or {}
    given = set_now or (kept.get("from_files") and kept.get("value") == s.linker)
    structure_trace.store(context.scene, "linker", {"from_files": bool(given),
                                                    "value": s.linker})
    return "" if given else (f"; Linker stays {s.linker} residues: the files do not give it, "
                             f"set it (the anchor counts as one)")


class _ImportBase:
    bl_options = {"REGISTER"}  # its undo step pushed on success only (common.after_file)
    filepath: bpy.props.StringProperty(subtype="FILE_PATH", options={"SKIP_SAVE"})
    filter_glob: bpy.props.StringProperty(default=GLOB, options={"HIDDEN"})

    def invoke(self, context, event):
        common.browse_from_last_folder(self, context)
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return common.after_file(self, context, common.guarded(self, self._import, context))


class FIBRILFIT_OT_import_fibril(_ImportBase, bpy.types.Operator):
    bl_idname = "fibrilfit.import_fibril"
    bl_label = "Import fibril…"
    bl_description = ("Measure a fibril structure (PDB/mmCIF): rise, twist, protofilaments, core "
                      "outline and anchor fill the parameters; its CA trace goes on the model's "
                      "core")
    terminus: bpy.props.EnumProperty(name="Terminus", items=(
        ("C", "C-terminus", "The linker leaves the core's last residue"),
        ("N", "N-terminus", "The linker leaves the core's first residue")), default="C")
    anchor_residue: bpy.props.IntProperty(name="Anchor residue", default=0,
                                          description="Anchor on this residue (0: the terminus)")

    def _import(self, context):
        path = bpy.path.abspath(self.filepath)
        fib = measure_fibril(path, terminus=self.terminus,
                             anchor_residue=self.anchor_residue or None)
        names, missing = _fill(context, fib, None)
        s = common.settings(context)
        if len(s.domains) and "linker" in domain_list.filled(s, fib.to_dict(), first_changed=True):
            names = sorted({*names, "linker"})  # from the fibril's and the domain's numbering
        _show_fibril(context, path, fib, common.panel_params(context), self.terminus,
                     self.anchor_residue or None)
        structure_trace.place_domains(context.scene, common.panel_params(context))
        frame_structures(context)
        for w in fib.warnings:
            self.report({"WARNING"}, panel_words.in_panel_words(w))
        self.report({"INFO"}, f"{fib.file}: set {panel_words.labels(names)}"
                    + (f"; not in this model: {', '.join(missing)}" if missing else "")
                    + linker_said(context, "linker" in names))
        return {"FINISHED"}


class FIBRILFIT_OT_import_domain(_ImportBase, bpy.types.Operator):
    bl_idname = "fibrilfit.import_domain"
    bl_label = "Import domain…"
    bl_description = ("Measure a globular domain (PDB/mmCIF) and add it to the chain's domains, "
                      "outermost: the globule's diameter from its radius of gyration, "
                      "2·√(5/3)·Rg, and its shape")
    chain: bpy.props.StringProperty(name="Chain", default="",
                                    description="The domain's chain (empty: the first)")
    residues: bpy.props.StringProperty(name="Residues", default="",
                                       description="a-b (empty: all)")

    def _import(self, context):
        path = bpy.path.abspath(self.filepath)
        s, fibril = common.settings(context), structure_trace.measured(context.scene).get("fibril")
        dom = domain_list_logic.measure(path, chain=self.chain or None,
                                        residues=self.residues or None, fibril=fibril)
        domain_list.add(s, path, dom)
        if len(s.domains) > 1:
            domain_list.set_gaps(s, fibril, len(s.domains) - 2)
        names = domain_list.filled(s, fibril, first_changed=len(s.domains) == 1)
        _show_domain(context, s.domains[-1], dom, common.panel_params(context))
        frame_structures(context)
        more = (f"; domain {len(s.domains)} of the chain, {s.domains[-2].linker} residues after "
                f"the one before (set it in the list)" if len(s.domains) > 1 else "")
        self.report({"INFO"}, f"{dom.file}: Rg {dom.rg:.2f} Å, set {panel_words.labels(names)}"
                              f"{more}" + linker_said(context, "linker" in names))
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_import_fibril, FIBRILFIT_OT_import_domain)
