"""The sidebar as a biologist walks it (issue #45): two domains imported, Run all, Step by step ›
Bake, Report…, Clear; results that belong to their run; the words the panel speaks.

New tests of issue #45 live here (tests/blender/test_ui.py keeps the older ones)."""
import json
import types

import bpy
import pytest
from helpers import ROOT

from fibrilfit.builders import find_model, model_stage
from fibrilfit.model import params as P
from fibrilfit.ui import panels, properties, structure_trace

DATA = ROOT / "tests" / "data"
SMALL = dict(layers=6, frames=10, seed=5)


@pytest.fixture
def ui(registered):
    properties.write_params(registered, P.make_params(**SMALL))
    return registered


def run(op: str, *args, **kw):
    return getattr(bpy.ops.fibrilfit, op)(*args, **kw)


def import_two_domains():
    assert run("import_domain", filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    assert run("import_domain", filepath=str(DATA / "1gfl.pdb.gz"), chain="A") == {"FINISHED"}


def main_labels(context=None):
    from test_ui import draw_all
    drawn = draw_all(context or bpy.context)
    return [t for kind, t in drawn["FIBRILFIT_PT_main"] if kind == "label"]


# ---- 1. two domains bake step by step ---------------------------------------------------------

def test_two_domains_run_all_then_bake_step_by_step(ui, scene):
    """Issue #45 item 1: with two domains in the list, the panel's domain_linker (a list) and the
    model's (a tuple) are the same value: no "changed since the build", and Bake runs."""
    import_two_domains()
    assert len(ui.domains) == 2
    assert run("run_all") == {"FINISHED"}
    assert not any("Changed since the build" in t for t in main_labels())
    assert properties.changed_fields(ui, find_model(scene).params) == []
    assert run("bake") == {"FINISHED"}
    assert model_stage(scene) == "baked"
    assert run("check_intersections") == {"FINISHED"} and ui.verdict
