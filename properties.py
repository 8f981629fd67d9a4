"""scene.fibrilfit: the sidebar's parameters, made from the one parameter definition, and the
results of the last check.

One property per field of params.Params, with the same name, its default, min/max and doc.
1 Blender unit = 1 Å. Blender has no Ångström unit: its length unit would show "30 m" under the
default Metric system, so lengths are plain numbers with the unit in the label, and the twist
shows in degrees.
"""
import bpy
import numpy as np
from bpy.props import (BoolProperty, FloatProperty, FloatVectorProperty, IntProperty,
                       PointerProperty, StringProperty)

from . import params as P

# The sidebar's sections, in the tutorial's order. A field goes where its metadata says;
# a section this list does not know goes to "Simulation", so a new field is never hidden.
SECTIONS = ("Slab", "Anchor", "Linker", "Globule", "Layers", "Simulation", "Check")
BUILD_SECTIONS = SECTIONS[:5]  # what the build steps read; the bake and the check read the rest

# How a unit of the parameter definition shows in Blender; the ones named in labels have none.
_FLOAT_UNITS = {
    "rad": {"subtype": "ANGLE", "unit": "ROTATION"},
    "fraction": {"subtype": "FACTOR"},
}
_LABEL_UNITS = ("Å", "Å/frame", "Å/s²")
_UNIT_NOTES = {"Å": "Å, 1 Blender unit = 1 Å", "Å/frame": "Å per frame", "Å/s²": "Å/s²",
               "rad": "shown in degrees", "×": "", "fraction": "a fraction: 0.05 is 5 %"}


def section_of(field) -> str:
    section = field.metadata.get("section", "Simulation")
    return section if section in SECTIONS else "Simulation"


def fields_in(section: str) -> list:
    """Fields shown in `section`, in the definition's order."""
    return [f for f in P.fields() if f.metadata.get("ui", True) and section_of(f) == section]


def label(field) -> str:
    name = field.name.replace("_", " ").capitalize()
    unit = field.metadata["unit"]
    return f"{name} ({unit})" if unit in _LABEL_UNITS else name


def _description(field) -> str:
    meta = field.metadata
    note = _UNIT_NOTES.get(meta["unit"], meta["unit"])
    return f"{meta['doc']} ({note})" if note and meta["kind"] is not bool else meta["doc"]


def _param_property(field):
    meta, default = field.metadata, field.default
    common = {"name": label(field), "description": _description(field)}
    if meta["kind"] is bool:
        return BoolProperty(default=default, **common)
    if meta["kind"] is int:
        return IntProperty(default=default, min=meta["min"], max=meta["max"], **common)
    units = _FLOAT_UNITS.get(meta["unit"], {})
    limits = {"min": meta["min"], "max": meta["max"], "precision": 3}
    if isinstance(default, tuple):
        return FloatVectorProperty(default=default, size=len(default), subtype="XYZ",
                                   unit=units.get("unit", "NONE"), **limits, **common)
    return FloatProperty(default=default, **units, **limits, **common)


class FIBRILFIT_PG_settings(bpy.types.PropertyGroup):
    """The model's parameters (one per params.Params field) and the last check's result."""

    verdict: StringProperty(
        name="Verdict",
        description='"successful" when no two globules intersect at the last frame, '
                    '"intersection" otherwise; empty before a check')
    clash_count: IntProperty(
        name="Clashing pairs", min=0,
        description="Number of globule pairs that intersect at the last frame")
    max_bond_stretch: FloatProperty(
        name="Worst bond stretch", precision=3,
        description="Worst linker bond at the last frame: (distance - rest length) / rest length")
    linker_intact: BoolProperty(
        name="Linker intact", description="Every bond within the stretch tolerance")
    accommodated: BoolProperty(
        name="Accommodated",
        description="No intersection and every linker intact: the domains fit on the fibril")


RESULTS = tuple(FIBRILFIT_PG_settings.__annotations__)
_clash = set(RESULTS) & {f.name for f in P.fields()}
assert not _clash, f"result properties shadow parameters: {_clash}"
FIBRILFIT_PG_settings.__annotations__.update({f.name: _param_property(f) for f in P.fields()})
# The periodic cell's checkbox: on, `periodic` is the cell's M (0 = auto); off, periodic is 0.
FIBRILFIT_PG_settings.__annotations__["use_periodic"] = BoolProperty(
    name="Periodic cell",
    description="Simulate the interior of an infinite fibril: a screw-periodic cell of M layers "
                "whose images stand in for the rest (Layers and Score layers are then unused)")

CLASSES = (FIBRILFIT_PG_settings,)


def attach():
    bpy.types.Scene.fibrilfit = PointerProperty(type=FIBRILFIT_PG_settings)


def detach():
    del bpy.types.Scene.fibrilfit


# ---- reading and writing -----------------------------------------------------------------

def _plain(value):
    """A property's value as the decimal the user typed: Blender keeps floats in 32 bits,
    so 4.8 reads back as 4.800000190734863; the shortest float32 repr gives 4.8 again."""
    if isinstance(value, float):
        return float(str(np.float32(value)))
    if isinstance(value, (bool, int, str)):
        return value
    return tuple(_plain(v) for v in value)


def values(settings) -> dict:
    out = {f.name: _plain(getattr(settings, f.name)) for f in P.fields()}
    if not settings.use_periodic:
        out["periodic"] = 0
    else:  # the cell replaces the fibril's length and its ends
        out["periodic"] = out["periodic"] or "auto"
        out["layers"], out["score_layers"] = P.DEFAULTS.layers, 0
    return out


def read_params(settings) -> P.Params:
    """The panel's values as Params, validated (raises ParamError naming the parameter)."""
    return P.make_params(**values(settings))


def write_params(settings, p: P.Params) -> None:
    for name, value in p.to_dict().items():
        setattr(settings, name, value)
    settings.use_periodic = bool(p.periodic)


def changed_fields(settings, p: P.Params, sections=SECTIONS) -> list[tuple[str, object, object]]:
    """Fields of `sections` whose panel value differs from `p`: (name, value in p, panel value)."""
    now, then = values(settings), p.to_dict()
    if now["periodic"] == "auto":
        try:
            now["periodic"] = P.make_params(**now).periodic
        except P.ParamError:
            pass
    if then.get("periodic"):
        now["layers"] = then["layers"]  # a cell's layers follow from periodic
    out = []
    for f in P.fields():
        if section_of(f) in sections:
            old = tuple(then[f.name]) if isinstance(then[f.name], list) else then[f.name]
            if _plain(old) != now[f.name]:
                out.append((f.name, old, now[f.name]))
    return out


def store_result(settings, result: dict) -> None:
    settings.verdict = result["verdict"]
    settings.clash_count = len(result["clashing_pairs"])
    settings.max_bond_stretch = result["max_bond_stretch"]
    settings.linker_intact = result["linker_intact"]
    settings.accommodated = result["accommodated"]


def clear_result(settings) -> None:
    for name in RESULTS:
        settings.property_unset(name)
