"""Report… in the sidebar: the panel's model through the same report as `headless.py report`
(search/report.py), into a folder the user picks. Blender waits while it runs (minutes: the
restarts run on worker processes; the progress is in the system console)."""
import pathlib

import bpy

from ... import files, pipeline
from ...exits import UsageError
from ...exports import options
from ...model import cases
from ...search import report
from .. import properties
from . import common


class FIBRILFIT_OT_report(bpy.types.Operator):
    bl_idname = "fibrilfit.report"
    bl_label = "Report…"
    bl_description = ("Write report.html and report.json for the panel's model: P(fit) over "
                      "restarts, the minimal linker, the best layout rendered and the envelope "
                      "(the same report as `headless.py report`; takes minutes)")
    bl_options = {"REGISTER", "UNDO"}  # it builds the best layout in the scene
    directory: bpy.props.StringProperty(subtype="DIR_PATH", options={"SKIP_SAVE"})
    restarts: bpy.props.IntProperty(name="Restarts", default=report.DEFAULT_RESTARTS, min=1,
                                    max=1000, description="seeds run at each linker length")
    max_linker: bpy.props.IntProperty(name="Longest linker", default=report.DEFAULT_MAX_LINKER,
                                      min=1, max=200, description="the minimal-linker walk "
                                      "gives up beyond this length")

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        try:
            return common.guarded(self, self._report, context)
        except UsageError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}

    def _report(self, context):
        out = pathlib.Path(bpy.path.abspath(self.directory or "//fibrilfit_report"))
        p = properties.read_params(common.settings(context))
        case_path = out / "case.toml"
        args = report.options(out=str(out), restarts=self.restarts, max_linker=self.max_linker,
                              resume=True, command_line=[
                                  "headless.py", "report", "--case", str(case_path),
                                  "--restarts", str(self.restarts), "--max-linker",
                                  str(self.max_linker), "--out", str(out)])
        report.check_options(args)
        files.check_writable("directory", out / report.HTML, (".html",))
        case = cases.Case({}, {}).resolved(p)
        size = tuple(int(v) for v in options.DEFAULT_SIZE.split("x"))
        look = {"size": size, "aspect": size[0] / size[1], "samples": options.DEFAULT_SAMPLES,
                "engine": "cycles"}
        sources = {name: "sidebar" for name in p.to_dict()}
        doc = report.make_report(args, p, p.to_dict(), structure_block=None, case=case,
                                 look=look, sources=sources,
                                 run_here=lambda q: pipeline.run_model(q, context.scene))
        cases.write(case_path, case)  # what the page's command reproduces
        self.report({"INFO"}, f"{doc['answer']}: wrote {out / report.HTML}")
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_report,)
