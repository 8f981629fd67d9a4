"""Load case / Save case: the sidebar's values from and to a case file (cases.py, the same
functions as --case and --save-case)."""
import json
import pathlib

import bpy

from ...model import cases, params as P
from ...model.param_checks import refuse_beside_periodic
from ... import files
from ...structure import from_files
from ...structure.request import from_case
from .. import panel_words, properties
from . import common, structures


class _CaseFile:
    filepath: bpy.props.StringProperty(subtype="FILE_PATH", options={"SKIP_SAVE"})
    filter_glob: bpy.props.StringProperty(default="*.toml", options={"HIDDEN"})

    def invoke(self, context, event):
        common.browse_from_last_folder(self, context, "case.toml")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return common.after_file(self, context, common.guarded(self, self._do, context),
                                 undo=self.bl_idname == "fibrilfit.load_case")


class FIBRILFIT_OT_load_case(_CaseFile, bpy.types.Operator):
    bl_idname = "fibrilfit.load_case"
    bl_label = "Load case"
    bl_description = ("Set every parameter from a case file (.toml), its structure files "
                      "measured as `run --case` measures them; parameters it leaves out take "
                      "their defaults. The model is not rebuilt: Run all to use them")
    bl_options = {"REGISTER"}  # its undo step pushed on success only (common.after_file)

    def _do(self, context):
        case = cases.load(bpy.path.abspath(self.filepath))
        # Every file read and measured, and the values checked, before the panel changes
        refuse_beside_periodic(case.params)
        request = from_case(case.structure)
        m = from_files.measure_files(request, every_exit=True) if request.any else None
        values, block = (from_files.merged(m.fibril, m.domains, m.segmentation,
                                           dict(case.params))
                         if m is not None else (case.params, {}))
        p = P.make_params(**values)  # as `run --case` (api/model.py's resolve)
        s = common.settings(context)
        s.domains.clear()  # the case's values are the domains now
        properties.write_params(s, p)
        if m is not None:
            structures.show_measured(context, m, p, request.terminus, request.anchor_residue)
        s.case_metadata = json.dumps(cases.metadata_of(case.resolved(p)))
        name = case.meta.get("name", case.path.name)
        measured = (f", those measured from {' and '.join(_files(m))}" if m is not None
                    else "")
        for warning in block.get("warnings", []):  # as `run --case` prints them
            self.report({"WARNING"}, panel_words.in_panel_words(warning))
        self.report({"INFO"}, f"Loaded case '{name}': {len(case.params)} parameters from the "
                              f"file{measured}, the rest at their defaults")
        return {"FINISHED"}


def _files(m) -> list:
    """The structure files a case named, once each, in the order it names them."""
    return list(dict.fromkeys(([m.fibril.file] if m.fibril is not None else [])
                              + [pathlib.Path(f).name for f, _, _ in m.specs]))


class FIBRILFIT_OT_save_case(_CaseFile, bpy.types.Operator):
    bl_idname = "fibrilfit.save_case"
    bl_label = "Save case"
    bl_description = ("Write the panel's parameters as a case file (.toml), with the metadata "
                      "of the case loaded last")
    bl_options = {"REGISTER"}

    def _do(self, context):
        path = files.check_writable("filepath", bpy.path.abspath(self.filepath),
                                     cases.SUFFIXES)
        s = common.settings(context)
        p = properties.read_params(s)
        meta = json.loads(s.case_metadata or "{}")
        case = cases.from_dict(meta)  # checked again: the JSON is the user's file to edit
        cases.write(path, case.resolved(p))
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_load_case, FIBRILFIT_OT_save_case)
