"""Report… in the sidebar: the panel's model through the same report as `headless.py report`
(search/report.py), into a folder the user picks; then the panel shows its numbers
(ui/report_summary.py) and Open report shows the page in the user's browser. Blender waits
while it runs (minutes: the restarts run on worker processes; the progress is in the system
console)."""
import json
import pathlib
import webbrowser

import bpy

from ... import files, pipeline
from ...builders.model import find_model
from ...exports import options
from ...model import cases
from ...model import params as P
from ...search import report
from .. import properties, report_summary
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
                                      min=1, max=P.field_spec("linker")["max"],
                                      description="the minimal-linker walk gives up beyond "
                                                  "this length")

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def invoke(self, context, event):
        """The folder chooser, offering the last report's folder and settings."""
        s = common.settings(context)
        if not self.directory and s.report_dir:
            self.directory = s.report_dir
        if not self.properties.is_property_set("restarts"):
            self.restarts = s.report_restarts
        if not self.properties.is_property_set("max_linker"):
            self.max_linker = s.report_max_linker
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return common.guarded(self, self._report, context)

    def _report(self, context):
        out = pathlib.Path(bpy.path.abspath(self.directory or "//fibrilfit_report"))
        s = common.settings(context)
        p = properties.read_params(s)
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
        best = {}

        def run_best(q):  # the best layout, built, baked and checked in the scene
            best.update(pipeline.run_model(q, context.scene))
            return best
        doc = report.make_report(args, p, p.to_dict(), structure_block=None, case=case,
                                 look=look, sources=sources, run_here=run_best)
        cases.write(case_path, case)  # what the page's command reproduces
        model = find_model(context.scene)
        if model is not None and best:  # the scene holds the best layout: its verdict, framed
            common.record_check(context, model, best)
            common.show_model(context, model)
        s.report_dir = str(out)
        s.report_restarts, s.report_max_linker = self.restarts, self.max_linker
        s.report_summary = json.dumps(report_summary.summary_of(doc, str(out)))
        self.report({"INFO"}, f"{doc['answer']}: wrote {out / report.HTML}")
        return {"FINISHED"}


def open_page(path: pathlib.Path) -> bool:
    """report.html in the user's browser (the test replaces this)."""
    return webbrowser.open(path.resolve().as_uri())


class FIBRILFIT_OT_open_report(bpy.types.Operator):
    bl_idname = "fibrilfit.open_report"
    bl_label = "Open report"
    bl_description = "Open the last report.html in your web browser"

    @classmethod
    def poll(cls, context):
        if context.scene is None or not context.scene.fibrilfit.report_summary:
            cls.poll_message_set("No report yet: Report… writes one")
            return False
        return True

    def execute(self, context):
        folder = json.loads(common.settings(context).report_summary)["folder"]
        page = pathlib.Path(folder) / report.HTML
        if not page.is_file():
            self.report({"ERROR"}, f"{page} is gone: Report… writes it again")
            return {"CANCELLED"}
        if not open_page(page):
            self.report({"ERROR"}, f"no web browser could be started: open {page} yourself")
            return {"CANCELLED"}
        self.report({"INFO"}, f"opened {page}")
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_report, FIBRILFIT_OT_open_report)
