"""Each command's whole plan: the model's values as given, the structure request and the plans
of the rooms that do the work (plans.py has how a plan is declared and checked).

    RunPlan            run (with restarts: the seeds on the executor, the best kept; with
                       --ensemble, the model's ensemble sampled from its layout)
    MinimalLinkerPlan  minimal-linker (the walk for one or more domain diameters)
    LargestFractionPlan largest-fraction (the walk over the decorated count, per diameter and
                       linker)
    ReportPlan         report (restarts at the linker, the walk, the best layout and, with
                       --ensemble, its ensemble, the page)
    SweepPlan          sweep (a grid of models, the model's values as lists or ranges)
    InspectPlan        inspect (structure files measured, nothing built)

`make_plan(RunPlan, {"linker": 8, "fibril": "6cu7.pdb.gz", "restarts": 4})` routes each flat
name to where it is declared: a model parameter to `model`, a structure option to `structure`,
`restarts` to the restart plan, `executor` to the executor plan, and so on (a nested plan may
also be given whole: `executor=ExecutorPlan(workers=2)`). The command line turns its
arguments into a plan with it, the sidebar and the Python API too; a case file (`case=`) fills
what was not given, as `--case` does.
"""
from __future__ import annotations

import dataclasses
import typing

from ..batch.plans import ExecutorPlan
from ..batch.slurm import given as slurm_given
from ..ensemble.plans import EnsemblePlan
from ..exports.plans import OutputPlan, RenderLook
from ..model import cases, params as P
from ..model.param_spec import MAX_OBJECTS_UNFORCED, MAX_TWIST
from ..plans import Plan, PlanError, is_plan, option, option_fields
from ..search.plans import (FRACTION_OUTPUT, MINIMAL_OUTPUT, REPORT_OUTPUT, REPORT_SEARCH,
                            BatchOutput, RestartPlan, SearchPlan)
from ..structure.request import StructureRequest
from ..sweep.plans import SweepOptions

FORCE_HELP = (f"build models beyond {MAX_OBJECTS_UNFORCED} objects, or with a twist beyond "
              f"±{MAX_TWIST} rad per layer")
RUN = "run"


def _model():
    return dataclasses.field(default_factory=dict, metadata={"model": True})


def _nested(default):
    return dataclasses.field(default=default, metadata={"nested": True})


@dataclasses.dataclass(frozen=True)
class _CommandPlan(Plan):
    """A command's plan: the model's values as given (checked when the model is made, after the
    structure files are measured under them), and the nested plans."""

    def __post_init__(self):
        super().__post_init__()
        if not isinstance(self.model, dict):
            raise PlanError("model", "must be a mapping of parameter names to values")
        object.__setattr__(self, "model", dict(self.model))

    def given(self) -> dict:
        """The model's values as given (a copy)."""
        return dict(self.model)

    @classmethod
    def refuse(cls, nests: dict) -> None:
        """Combinations refused before the nested plans are made (`nests`: nested field -> the
        values given for it), so the command's own reason comes first."""


@dataclasses.dataclass(frozen=True)
class RunPlan(_CommandPlan):
    """`run`: one model built, baked and checked; with restarts, its seeds on the executor
    first and the best one run here."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    outputs: OutputPlan = _nested(OutputPlan())
    look: RenderLook = _nested(RenderLook())
    restarts: RestartPlan = _nested(RestartPlan())
    executor: ExecutorPlan = _nested(ExecutorPlan())
    sampling: EnsemblePlan = _nested(EnsemblePlan())
    stop_after: str = option("check", "stop after this step", choices=("build", "bake", "check"),
                             group=RUN)
    fail_on_intersection: bool = option(False, "exit 1 when the verdict is intersection",
                                        group=RUN)
    quiet: bool = option(False, "print only the verdict line", group=RUN)
    progress: bool = option(False, "print the bake's frame to stderr at its start and every 25 "
                                   "frames", group=RUN)
    force: bool = option(False, FORCE_HELP)

    @classmethod
    def refuse(cls, nests: dict) -> None:
        """The executor works only for restarts: a SLURM option without them is refused for
        that reason, before the executor plan says it needs --executor slurm."""
        if nests["restarts"].get("restarts") is not None:
            return
        given = nests["executor"]
        if given.get("executor") == "slurm":
            raise PlanError("executor", "only with --restarts")
        slurm = slurm_given(given)
        if slurm:
            raise PlanError(slurm[0], "only with --restarts")

    def check(self) -> None:
        if self.restarts.restarts is not None and self.stop_after != "check":
            raise PlanError("restarts", "judges every seed, so --stop-after must be check")
        if self.sampling.on and self.stop_after != "check":
            raise PlanError("ensemble", "starts from a checked layout, so --stop-after must be "
                                        "check")


@dataclasses.dataclass(frozen=True)
class MinimalLinkerPlan(_CommandPlan):
    """`minimal-linker`: for each domain diameter (model["globule_diameter"]: one, a list or a
    range), the shortest linker at which a restart finds a layout."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    search: SearchPlan = _nested(SearchPlan())
    output: BatchOutput = _nested(MINIMAL_OUTPUT)
    executor: ExecutorPlan = _nested(ExecutorPlan())
    force: bool = option(False, FORCE_HELP)

    def check(self) -> None:
        if self.search.interval_width is not None:
            raise PlanError("interval_width", "not a minimal-linker option (the report's)")
        if self.search.fraction_plot:
            raise PlanError("fraction_plot", "not a minimal-linker option (the report's)")


@dataclasses.dataclass(frozen=True)
class LargestFractionPlan(_CommandPlan):
    """`largest-fraction`: for each domain diameter and linker (model["globule_diameter"],
    model["linker"]: one, a list or a range), the largest fraction of subunits (random nested
    pattern) at which a restart finds a layout, with its bracket (search/fraction.py)."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    search: SearchPlan = _nested(SearchPlan())
    output: BatchOutput = _nested(FRACTION_OUTPUT)
    executor: ExecutorPlan = _nested(ExecutorPlan())
    force: bool = option(False, FORCE_HELP)

    def check(self) -> None:
        for name in ("interval_width", "known_fit"):
            if getattr(self.search, name) is not None:
                raise PlanError(name, "not a largest-fraction option")
        if self.search.fraction_plot:
            raise PlanError("fraction_plot", "not a largest-fraction option (the report's)")


@dataclasses.dataclass(frozen=True)
class ReportPlan(_CommandPlan):
    """`report`: P(fit) at the linker with restarts, the minimal linker, the best layout
    rendered, the envelope, as one page."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    search: SearchPlan = _nested(REPORT_SEARCH)
    output: BatchOutput = _nested(REPORT_OUTPUT)
    look: RenderLook = _nested(RenderLook())
    executor: ExecutorPlan = _nested(ExecutorPlan())
    sampling: EnsemblePlan = _nested(EnsemblePlan())
    force: bool = option(False, FORCE_HELP)

    def check(self) -> None:
        if self.search.known_fit is not None:
            raise PlanError("known_fit", "not a report option (minimal-linker's)")
        if self.sampling.ensemble_volume:
            raise PlanError("ensemble_volume", "not a report option (the report keeps no scene: "
                                               "run --ensemble N --ensemble-volume --blend F)")


@dataclasses.dataclass(frozen=True)
class SweepPlan(_CommandPlan):
    """`sweep`: a grid of models (each model value a list or range) and their statistics."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    sweep: SweepOptions = _nested(SweepOptions())
    executor: ExecutorPlan = _nested(ExecutorPlan())
    force: bool = option(False, FORCE_HELP)

    @property
    def seed(self):
        """The model's seed as given (the sweep's seeds: --seed, --seed-list or --seeds)."""
        return self.model.get("seed")


@dataclasses.dataclass(frozen=True)
class InspectPlan(_CommandPlan):
    """`inspect`: the structure files measured, nothing built."""

    model: dict = _model()
    structure: StructureRequest = _nested(StructureRequest())
    json: str | None = option(None, "write the measurements as JSON ('-': to standard output, "
                                    "the text then to standard error)", kind="path",
                              metavar="PATH", group="inspect")


COMMAND_PLANS = {"run": RunPlan, "minimal-linker": MinimalLinkerPlan,
                 "largest-fraction": LargestFractionPlan, "report": ReportPlan,
                 "sweep": SweepPlan, "inspect": InspectPlan}
# What a command finds, so a case cannot set it
SEARCHED = {"minimal-linker": ("linker",), "largest-fraction": ("occupancy",)}


def nested_fields(cls) -> list[dataclasses.Field]:
    """The nested plans of a command's plan (structure, executor, ...)."""
    return [f for f in dataclasses.fields(cls) if f.metadata.get("nested")]


def routes(cls) -> dict:
    """Flat name -> (nested field or None for the plan's own, leaf name), for every option of
    the command's plan but the model's."""
    out = {}
    for nest in nested_fields(cls):
        for f in option_fields(typing.get_type_hints(cls)[nest.name]):
            out[f.name] = (nest.name, f.name)
    for f in option_fields(cls):
        out[f.name] = (None, f.name)
    return out


def make_plan(cls, values: dict, *, case: str | None = None, command: str | None = None):
    """A command's plan from flat values (the command line's, the API's keywords): each name
    routed to where it is declared (module docstring); a model parameter's name goes to the
    model (checked when the model is made). `case`: a case file filling what is not given.
    Returns (plan, the loaded Case or None)."""
    values = {k: v for k, v in values.items() if v is not None or k in ("model",)}
    loaded = None
    if case:
        values, loaded = apply_case(cls, values, case, command or _name(cls))
    model = dict(values.pop("model", None) or {})
    hints = typing.get_type_hints(cls)
    nests = {f.name: {} for f in nested_fields(cls)}
    whole, own = {}, {}
    route = routes(cls)
    params = {f.name for f in P.fields()}
    for name, value in values.items():
        if name in nests and is_plan(value):
            whole[name] = value
        elif name in params:
            model[name] = value
        elif name in route:
            nest, leaf = route[name]
            (own if nest is None else nests[nest])[leaf] = value
        else:
            raise PlanError(name, f"not an option of {_name(cls)}")
    cls.refuse(nests)
    made = {}
    for name, given in nests.items():
        base = whole.get(name, cls.__dataclass_fields__[name].default)
        made[name] = base.replace(**given) if given else base
        if not isinstance(made[name], hints[name]):
            raise PlanError(name, f"must be a {hints[name].__name__}")
    return cls(model=model, **made, **own), loaded


def _name(cls) -> str:
    return next((k for k, v in COMMAND_PLANS.items() if v is cls), cls.__name__)


def apply_case(cls, values: dict, path, command: str) -> tuple[dict, "cases.Case"]:
    """Load the case at `path` and fill every value `values` leaves unset from it (model
    parameters, the [structure] options; for a sweep also its seeds). Returns (values, Case),
    the Case's `overridden` naming what was given beside it."""
    values = dict(values)
    case = cases.load(path)
    structure = {f.name for f in option_fields(StructureRequest)}
    takes_structure = any(f.name == "structure" for f in nested_fields(cls))
    for key, value in case.structure.items():
        if not takes_structure or key not in structure:
            raise cases.CaseError(f"{cases.STRUCTURE}.{key}", f"`{command}` takes no structure "
                                                              f"files")
        if key in values:
            case.overridden.append(key)
        else:
            values[key] = value
    sweep = cls is SweepPlan
    seeds_given = sweep and any(values.get(o) is not None for o in ("seeds", "seed_list", "seed"))
    overridden = []
    searched = SEARCHED.get(command, ())
    for name, value in case.params.items():
        if name in searched:  # the command's answer, e.g. minimal-linker's linker
            continue
        if values.get(name) is not None:
            overridden.append(name)
        elif not (name == "seed" and sweep and (seeds_given or case.seeds is not None)):
            values[name] = value
    if sweep and case.seeds is not None and not seeds_given:
        values["seed_list"] = ",".join(str(s) for s in case.seeds)
    case.overridden = sorted(case.overridden + overridden)
    return values, case
