"""Report… in the sidebar: the panel's model through the same report as the command line's `report`
(search/report.py), into a folder the user picks; then the panel shows its numbers
(ui/report_summary.py) and Open report shows the page in the user's browser. Its restarts and
minimal-linker walk (minutes) run on worker processes, waited for on a thread
(search/background.py), so Blender stays live: the stage and runs in the status bar, Esc stops
it (the workers killed, nothing written: the report is made in a folder beside its own, moved
into place whole); the best layout, its pictures and the page are then made here (the modal
part is background.py's)."""
import json
import os
import pathlib
import webbrowser

import bpy

from ... import files, pipeline
from ...exits import UsageError
from ...api import reproduce_line as api_reproduce_line
from ...api.plans import ReportPlan
from ...batch.executors import make_executor
from ...builders.model import find_model
from ...model import cases, params as P
from ...structure import from_files
from ...search import fraction_plot, linker_map, report
from ...search.background import BackgroundReport
from ...search.plans import REPORT_SEARCH, plot_fractions, seed_range
from .. import minimal_summary, properties, provenance, report_summary, structure_trace
from ..plan_properties import plan_property
from . import common
from .background import BackgroundOperator

CASE = "case.toml"  # beside the report: what the page's command re-runs


class FIBRILFIT_OT_report(BackgroundOperator, bpy.types.Operator):
    bl_idname = "fibrilfit.report"
    bl_label = "Report…"
    bl_description = ("Write report.html and report.json for the panel's model: P(fit) over "
                      "restarts, the minimal linker, the best layout rendered and the envelope "
                      "(the same report as the command line's `report`; takes minutes on worker "
                      "processes, Esc cancels)")
    bl_options = {"REGISTER", "UNDO"}  # it builds the best layout in the scene
    directory: bpy.props.StringProperty(subtype="DIR_PATH", options={"SKIP_SAVE"})
    restarts: plan_property(REPORT_SEARCH, "restarts")
    max_linker: plan_property(REPORT_SEARCH, "max_linker")
    fraction_plot: plan_property(REPORT_SEARCH, "fraction_plot", options={"SKIP_SAVE"})
    replace: bpy.props.BoolProperty(
        name="Replace a report there", default=False, options={"SKIP_SAVE"},
        description="Write over the report already in the chosen folder (off: a folder that "
                    "holds one is refused, and Report… offers a new folder)")

    what, job_name = "report", "report"
    _out = None  # the folder the user picked
    _reproduce = ()  # the command that makes the report again (report.json's "command")
    _request = _block = None  # the structure files and their block (panel_model)
    _sources = None  # each value's source

    @classmethod
    def poll(cls, context):
        return context.scene is not None and not cls.running(context)

    def invoke(self, context, event):
        """The folder chooser, offering a new folder beside the last report's (never one that
        holds a report: free_folder), and the last restarts and longest linker of Report… or
        Minimal linker… (the same defaults, REPORT_SEARCH's)."""
        s = common.settings(context)
        if not self.directory:
            last = s.report_dir or (os.path.join(s.last_folder, "fibrilfit_report")
                                    if s.last_folder else "")
            self.directory = free_folder(last) if last else ""
        if not self.properties.is_property_set("restarts"):
            self.restarts = s.report_restarts
        if not self.properties.is_property_set("max_linker"):
            self.max_linker = s.report_max_linker
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def make_job(self, context) -> BackgroundReport:
        """The panel's model and the report's options checked, the structure files it was
        measured from measured again (their names, sha256 and each value's source: the file,
        the sidebar or the default; ui/provenance.py), the folder it is made in beside the
        chosen one, and its restarts and walk started on their thread."""
        out = pathlib.Path(bpy.path.abspath(self.directory or "//fibrilfit_report"))
        if (out / report.HTML).exists() and not self.replace:  # asked, not replaced unseen
            raise UsageError(f"{out} already holds a report: pick another folder, or tick "
                             f"Replace a report there")
        s = common.settings(context)
        p, request, block, self._sources = panel_model(context.scene, s)
        self._out, self._request, self._block = out, request, block
        search = REPORT_SEARCH.replace(restarts=self.restarts, max_linker=self.max_linker,
                                       fraction_plot=self.fraction_plot)
        plan = ReportPlan.make(model=p.to_dict(), search=search)
        plan = plan.replace(output=plan.output.replace(out=str(out), resume=True, quiet=True))
        self._reproduce = reproduce_line(out / CASE, ReportPlan.make(
            search=search, output=plan.output.replace(out=str(out), resume=False,
                                                      quiet=False)))
        report.need_packages(plan.executor)
        seed_range(p.seed, plan.search.restarts)
        fraction_plot.models(p, plot_fractions(plan.search.fraction_plot))  # refused here
        files.check_writable("directory", out / report.HTML, (".html",))
        work = BackgroundReport.folder_beside(out)
        job = BackgroundReport(plan, p, p.to_dict(), None, work)
        try:
            job.executor = make_executor(plan.executor, out=work, runs=plan.search.restarts,
                                         log_path=work / linker_map.LOG)
        except BaseException:
            job.discard()
            raise
        return job.start()

    @staticmethod
    def progress_text(p) -> tuple:
        step = report.STAGES.index(p.stage) + 1
        runs = f", {p.done} of {p.submitted} runs done" if p.submitted else ""
        return (f"{p.stage} (stage {step} of {len(report.STAGES)}){runs}",
                (step - 1 + (p.done / p.submitted if p.submitted else 0)) / len(report.STAGES))

    def finish(self, context) -> set:
        """The restarts and walk have ended: the best layout, its pictures and the page made
        here, the report moved into place and its numbers in the panel; or cancelled, or its
        error, with nothing written."""
        job = self._job
        if job.stopped:
            job.discard()
            self.report({"WARNING"}, f"Report cancelled after "
                                     f"{minimal_summary.runs(job.progress.done)}; nothing "
                                     f"written")
            return {"CANCELLED"}
        try:
            if job.error is not None:
                raise job.error
            return self._write(context, job)
        except BaseException:
            job.discard()
            raise

    def _write(self, context, job) -> set:
        out, p, s = self._out, job.p, common.settings(context)
        loaded = cases.from_dict(json.loads(s.case_metadata or "{}"))  # as Save case
        case = loaded.resolved(p, structure=self._request.to_case())
        best = {}

        def run_best(q):  # the best layout, built, baked and checked in the scene
            best.update(pipeline.run_model(q, context.scene))
            return best
        doc = report.write(job.plan, p, job.result, job.work, lambda name: None,
                           structure_block=self._block, case=case, sources=self._sources,
                           run_here=run_best, reproduce=self._reproduce)
        cases.write(job.work / CASE, case)  # what the page's command reproduces
        job.keep(out)
        model = find_model(context.scene)
        if model is not None and best:  # the scene holds the best layout: its verdict, framed
            common.record_check(context, model, best)
            common.show_model(context, model)
            # the panel's seed is the best layout's: the panel describes the model in the scene
            # (else a model the user never changed reads "Physics changed: Bake again", and
            # Check and the exports refuse it as stale)
            s.seed = best["seed"]
        s.report_dir = str(out)
        s.last_folder = str(out.parent)
        s.report_restarts, s.report_max_linker = self.restarts, self.max_linker
        s.report_summary = json.dumps(report_summary.summary_of(doc, str(out)))
        self.report({"INFO"}, f"{doc['answer']}: wrote {out / report.HTML}")
        return {"FINISHED"}

    def discard(self) -> None:
        if self._job is not None:
            self._job.join(10)  # its workers are killed: it ends within seconds
            self._job.discard()


def free_folder(path: str) -> str:
    """`path`, or when it holds a report the first of path-2, path-3, ... that does not (a
    folder path, ending in its separator as Blender's folder browser gives it)."""
    base = path.rstrip("/\\") or path
    candidate, n = base, 1
    while (pathlib.Path(bpy.path.abspath(candidate)) / report.HTML).exists():
        n += 1
        candidate = f"{base}-{n}"
    return os.path.join(candidate, "")


def panel_model(scene, s) -> tuple:
    """(Params, StructureRequest, structure block or None, sources) of a result made from the
    panel: its values checked, the files they were imported from measured again as the command
    line measures them, each value the panel holds as measured taking the file's value and
    source (ui/provenance.py)."""
    p = properties.read_params(s)
    request = structure_trace.request(scene, s)
    measured, block = {}, None
    if request.any:
        m = from_files.measure_files(request, every_exit=True)
        shape = {k: getattr(p, k) for k in ("domain_shape", "residue_radius", "residue_spacing")}
        measured, block = from_files.merged(m.fibril, m.domains, m.segmentation, shape)
    values, sources = provenance.panel_sources(p.to_dict(), measured, block)
    return P.make_params(**values), request, block, sources


def command_prefix() -> list[str]:
    """How this installation runs a command: Blender with the extension's command line
    (`blender -b -c fibrilfit`) when the panel is the installed extension, else pip's
    `fibrilfit` (docs/guide/install.md)."""
    if __package__.startswith("bl_ext."):
        return [bpy.app.binary_path or "blender", "-b", "-c", "fibrilfit"]
    return ["fibrilfit"]


def reproduce_line(case_path, plan) -> list[str]:
    """The command that makes the report again: the case written beside it (every value and the
    structure files), then the report's own options as api.reproduce_line gives them."""
    words = api_reproduce_line("report", plan)[2:]
    return [*command_prefix(), "report", "--case", str(case_path), *words]


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
