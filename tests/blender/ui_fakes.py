"""The sidebar's stand-ins, shared by test_ui.py and the other sidebar tests: the `ui` fixture
(the add-on registered, SMALL in scene.fibrilfit), the operators run by name, an operator's
methods detached from Blender's event loop, a strict stand-in for UILayout (which exists only
while Blender draws), a label's width in pixels, and the status bar's stand-ins. Moved here from
test_ui.py as they were (issue #46)."""
import json
import types

import bpy
import pytest

from fibrilfit.model import params as P
from fibrilfit.ui import panels, properties, registration
from fibrilfit.builders import find_model
from fibrilfit.ui.operators import common

STEPS = ("build_slab", "build_anchor", "build_linker", "build_globule", "replicate_layers",
         "bake", "check_intersections")
# Small, and with clashes on both bpy versions: the colouring has something to show.
SMALL = dict(layers=8, linker=3, frames=80, seed=5)


@pytest.fixture
def ui(scene, ff):
    """The add-on registered on an empty scene; scene.fibrilfit holds SMALL."""
    ff.register()
    properties.write_params(scene.fibrilfit, P.make_params(**SMALL))
    yield scene.fibrilfit
    ff.unregister()


def run(op: str, *args, **kw):
    return getattr(bpy.ops.fibrilfit, op)(*args, **kw)


def run_steps(steps=STEPS):
    for op in steps:
        assert run(op) == {"FINISHED"}, op


def stored_result(scene) -> dict:
    return json.loads(find_model(scene).root[common.RESULT])


def _op_exists(idname: str) -> bool:
    mod, name = idname.split(".")
    try:
        getattr(getattr(bpy.ops, mod), name).get_rna_type()
        return True
    except (KeyError, AttributeError):
        return False


def detached(op_class):
    """The operator's own methods on a plain object: bpy-as-module has no event loop to call
    modal(), and an Operator cannot be instantiated from Python."""
    ns = {}
    for klass in reversed(op_class.__mro__):
        if klass.__module__.startswith(registration.__package__):
            ns.update({k: v for k, v in vars(klass).items() if not k.startswith("__")})
    op = type("Detached" + op_class.__name__, (), ns)()
    op.reports = []
    op.report = lambda kind, text: op.reports.append((set(kind), text))
    op.TICK_SECONDS = 0.0  # one frame per timer tick
    return op


def event(kind):
    return types.SimpleNamespace(type=kind, value="PRESS")


UI_RNA = bpy.types.UILayout.bl_rna


class FakeLayout:
    """Stands in for UILayout, which only exists while Blender draws a region (never in
    bpy-as-module). Strict: it checks every argument and attribute against UILayout's RNA."""

    def __init__(self, log):
        object.__setattr__(self, "log", log)

    def __setattr__(self, name, value):
        assert name in UI_RNA.properties, f"UILayout has no attribute {name}"

    def _check(self, function, kw):
        params = UI_RNA.functions[function].parameters
        for key, value in kw.items():
            assert key in params, f"{function}() has no argument {key}"
            if key == "icon":
                assert value in params["icon"].enum_items, f"no icon {value}"

    def _sub(self, function, kw):
        self._check(function, kw)
        return FakeLayout(self.log)

    def row(self, **kw):
        return self._sub("row", kw)

    def column(self, **kw):
        return self._sub("column", kw)

    def box(self):
        return FakeLayout(self.log)

    def separator(self, **kw):
        self._check("separator", kw)

    def label(self, **kw):
        self._check("label", kw)
        self.log.append(("label", kw.get("text", "")))

    def prop(self, data, name, **kw):
        self._check("prop", kw)
        assert name in data.bl_rna.properties, f"{data} has no property {name}"
        self.log.append(("prop", name))

    def template_list(self, listtype_name, list_id, dataptr, propname, active_dataptr,
                      active_propname, **kw):
        self._check("template_list", kw)
        assert propname in dataptr.bl_rna.properties and listtype_name in dir(bpy.types)
        assert active_propname in active_dataptr.bl_rna.properties
        self.log.append(("template_list", propname))

    def operator(self, idname, **kw):
        self._check("operator", kw)
        assert _op_exists(idname), idname
        self.log.append(("operator", idname))
        return types.SimpleNamespace()


def draw_all(context):
    """Every panel's draw(); returns what each drew."""
    drawn = {}
    for cls in panels.CLASSES:
        log = []
        panel = types.SimpleNamespace(layout=FakeLayout(log), section=getattr(cls, "section", ""),
                                      buttons=getattr(cls, "buttons", ()))
        cls.draw(panel, context)
        drawn[cls.__name__] = log
    return drawn


# Blender's UI font is 11 px at the default resolution scale; the default sidebar is 291 px
# wide (measured under Xvfb, Blender 4.3.2: tests/realblender/gui_probe.py), of which a field
# gets about 230 px once the tabs, the panel's margins and the field's padding are taken.
FIELD_PX, TEXT_PX = 230, 11


def _text_px(text: str) -> float:
    import blf
    blf.size(0, TEXT_PX)
    return blf.dimensions(0, text)[0]


class _Workspace:
    def __init__(self):
        self.status = []

    def status_text_set(self, value):
        self.status.append(value)


class _Progress:
    def __init__(self):
        self.drawn = []

    def row(self):
        return self

    def progress(self, **kw):
        self.drawn.append(kw)
