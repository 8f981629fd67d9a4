"""scene.fibrilfit: the sidebar's parameters, made from the one parameter definition, and the
results of the last check.

One property per field of params.Params, with the same name, its default, min/max and doc.
1 Blender unit = 1 Å. Blender has no Ångström unit: its length unit would show "30 m" under the
default Metric system, so lengths are plain numbers with the unit in the label, and the twist
shows in degrees.
"""
import json

import bpy
import numpy as np
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty,
                       FloatVectorProperty, IntProperty, PointerProperty, StringProperty)

from ..model import params as P
from ..model.param_spec import SHOWN_IN
from ..search.plans import REPORT_SEARCH
from . import domain_list
from .plan_properties import plan_property

# The sidebar's sections, in the tutorial's order. A field goes where its metadata says;
# a section this list does not know goes to "Simulation", so a new field is never hidden.
SECTIONS = ("Slab", "Anchor", "Linker", "Globule", "Layers", "Simulation", "Check")
BUILD_SECTIONS = SECTIONS[:5]  # what the build steps read; the bake and the check read the rest

# How a unit of the parameter definition shows in Blender; the ones named in labels have none.
_FLOAT_UNITS = {
    "rad": {"subtype": "ANGLE", "unit": "ROTATION"},
    "fraction": {"subtype": "FACTOR"},
    "%": {"subtype": "PERCENTAGE"},
}
_LABEL_UNITS = ("Å", "Å/frame", "Å/s²")
_UNIT_NOTES = {"Å": "Å, 1 Blender unit = 1 Å", "Å/frame": "Å per frame", "Å/s²": "Å/s²",
               "rad": "shown in degrees", "×": "", "fraction": "a fraction: 0.05 is 5 %",
               "%": "in per cent, as the printed result shows it; the command line takes the "
                    "fraction: 5 % is 0.05"}


# What a field's tooltip adds for a panel user (issue #45 item 8): the linker's anchor
_PANEL_NOTES = {
    "linker": (". The anchor is the core residue the chain leaves the core from (the fibril's "
               "terminus, e.g. K97 of 6CU7), a passive bead: fixed on the core, it does not move "
               "in the simulation. It counts as the linker's first residue: from K97 to a domain "
               "starting at residue 128 the linker is 31. Import fibril… sets it from a modelled "
               "tail, Import domain… from the shared numbering; otherwise set it here"),
}


def section_of(field) -> str:
    section = field.metadata.get("section", "Simulation")
    return section if section in SECTIONS else "Simulation"


def fields_in(section: str) -> list:
    """Fields of `section`, in the definition's order (the question's among them)."""
    return [f for f in P.fields() if f.metadata.get("ui", True) and section_of(f) == section]


def question_fields() -> list:
    """What the user asks about (params: question=True), shown at the top of the panel."""
    return [f for f in P.fields() if f.metadata.get("ui", True) and f.metadata.get("question")]


def label(field) -> str:
    """The panel's name of a field: params' `label` or the field's name, with the unit where
    the value does not show it (short enough for the default sidebar width; a test checks)."""
    meta = field.metadata
    name = meta.get("label") or field.name.replace("_", " ").capitalize()
    unit = meta["unit"]
    if unit == "residues" and "residue" not in name.lower():  # Linker (residues): issue #45
        return f"{name} ({unit})"
    return f"{name} ({unit})" if unit in _LABEL_UNITS and not meta.get("shown_in") else name


def _scale(field) -> float:
    """The factor from the definition's unit to the one the panel shows (1: the same)."""
    shown = field.metadata.get("shown_in")
    return SHOWN_IN[shown][1] if shown else 1.0


JSON_KINDS = ("points", "rows")  # held as JSON text in the panel, read back exactly


def _description(field) -> str:
    meta = field.metadata
    if meta["kind"] == "rows":
        return f"{meta['doc']}. JSON rows; empty for {meta['derived']}"
    if meta["kind"] == "points":
        return (f"{meta['doc']}. JSON: [[x, y], ...] in Å; empty for {meta['derived']}. "
                f"Load one from a file with Load outline")
    note = _UNIT_NOTES.get(meta.get("shown_in") or meta["unit"], meta["unit"])
    if note and note in meta["doc"]:  # "Linker length in residues": said once
        note = ""
    text = f"{meta['doc']} ({note})" if note and meta["kind"] is not bool else meta["doc"]
    text += _PANEL_NOTES.get(field.name, "")
    return text + (f". Used when its switch is on; off: {meta['derived']}" if meta.get("derived")
                   else "")


def shown_default(name: str):
    """What a derived parameter (default None: worked out from others) shows until the user
    turns its "use_" switch on (off means None): the value the model works out at the defaults,
    the anchor's (21.75, 0) Å, and pf_rotation's at two protofilaments, the fewest where a
    turn between them means anything (π); the second domain's, A's at the defaults (B as
    large as A, on a linker as long)."""
    p = P.DEFAULTS if name != "pf_rotation" else P.make_params(protofilaments=2)
    return {"pf_rotation": p.pf_angle, "anchor": p.anchor_xy,
            "domain_b_diameter": p.globule_diameter, "linker_b": p.linker}[name]


def switch_name(name: str) -> str:
    """The BoolProperty that says a derived parameter is set by hand (off: its default)."""
    return "use_" + name


def derived_fields() -> list:
    return [f for f in P.fields() if f.metadata.get("derived")
            and f.metadata["kind"] not in JSON_KINDS]


def _param_property(field):
    meta, default = field.metadata, field.default
    common = {"name": label(field), "description": _description(field)}
    if meta["kind"] in (*JSON_KINDS, "list"):
        return StringProperty(default="", **common)
    if default is None:
        default = shown_default(field.name)
    if meta["kind"] is bool:
        return BoolProperty(default=default, **common)
    if "choices" in meta:  # a choice: the panel's drop-down, its items the choices
        return EnumProperty(items=[(c, c.capitalize(), "") for c in meta["choices"]],
                            default=default, name=common["name"], description=meta["doc"])
    if meta["kind"] is int:
        return IntProperty(default=default, min=meta["min"], max=meta["max"], **common)
    if meta["kind"] is str:  # free text (a pattern's letters): make_params reads and checks it
        return StringProperty(default=default, **common)
    units = _FLOAT_UNITS.get(meta.get("shown_in") or meta["unit"], {})
    k = _scale(field)
    limits = {"min": meta["min"] * k, "max": meta["max"] * k, "precision": 1 if k != 1 else 3}
    default = default * k if not isinstance(default, tuple) else default
    if isinstance(default, tuple):
        return FloatVectorProperty(default=default, size=len(default), subtype="XYZ",
                                   unit=units.get("unit", "NONE"), **limits, **common)
    return FloatProperty(default=default, **units, **limits, **common)


# The last check's result (RESULTS: what clear_result unsets and store_result writes).
_RESULT_PROPERTIES = {
    "verdict": StringProperty(
        name="Verdict",
        description='"successful" when no two globules intersect at the last frame, '
                    '"intersection" otherwise; empty before a check'),
    "clash_count": IntProperty(
        name="Clashing pairs", min=0,
        description="Number of globule pairs that intersect at the last frame"),
    "max_bond_stretch": FloatProperty(
        name="Worst bond stretch", precision=3,
        description="Worst linker bond at the last frame: (distance - rest length) / rest length"),
    "linker_intact": BoolProperty(
        name="Linker intact", description="Every bond within the stretch tolerance"),
    "linker_stretch": StringProperty(
        name="Linker span", options={"HIDDEN"},
        description="The result's linker_stretch (JSON): how far the linkers span of their full "
                    "length in the layout found; empty when no linker was scored"),
    "accommodated": BoolProperty(
        name="Accommodated",
        description="No intersection and every linker intact: the domains fit on the fibril"),
    "answer": StringProperty(
        name="Answer",
        description="What this one relaxation shows: fits, borderline (at the criterion) or no "
                    "layout found (in this run; restarts or minimal-linker say more)"),
    "bound": IntProperty(
        name="Impossible below", min=0,
        description="The proven lower bound: no clash-free layout with intact linkers exists "
                    "with fewer linker residues (geometry alone; 0 = not computed)"),
}
RESULTS = tuple(_RESULT_PROPERTIES)
_clash = set(RESULTS) & {f.name for f in P.fields()}
assert not _clash, f"result properties shadow parameters: {_clash}"

# What the next Report… and Minimal linker… offer: restarts and longest linker, from the
# report's own declaration (search/plans.py's REPORT_SEARCH)
_REPORT_OPTIONS = {"report_restarts": plan_property(REPORT_SEARCH, "restarts"),
                   "report_max_linker": plan_property(REPORT_SEARCH, "max_linker")}

# Every property of scene.fibrilfit, in the panel's (and the .blend file's) order.
_SETTINGS = {
    **_RESULT_PROPERTIES,
    **{f.name: _param_property(f) for f in P.fields()},
    **{switch_name(f.name): BoolProperty(name=f"Set {label(f)[:1].lower()}{label(f)[1:]}",
                                         description=f"Set by hand; off: {f.metadata['derived']}")
       for f in derived_fields()},
    "core_outline_file": StringProperty(
        name="Outline file", description="The file the core outline was last loaded from"),
    # The loaded case's metadata (name, citation, seeds, ...) as JSON, written back by Save case.
    # Not a result: a bake or check leaves it alone.
    "case_metadata": StringProperty(
        name="Case", description="Metadata of the case file loaded last (JSON)",
        options={"HIDDEN"}),
    # The periodic cell's checkbox: on, `periodic` is the cell's M (0 = auto); off, periodic is 0.
    "use_periodic": BoolProperty(
        name="Periodic cell",
        description="Simulate the interior of an infinite fibril: a screw-periodic cell of M "
                    "layers whose images stand in for the rest (Layers and Score layers are then "
                    "unused)"),
    # The last report (Report…): its folder and the numbers the panel shows (report_summary),
    # kept across checks; the restarts and longest linker the next Report… offers.
    # The folder a file was last read from or written to: where the next file browser starts
    "last_folder": StringProperty(
        name="Last folder", subtype="DIR_PATH", options={"HIDDEN"},
        description="Where the last file FibrilFit read or wrote is; the next file browser "
                    "starts there"),
    "report_dir": StringProperty(
        name="Report folder", subtype="DIR_PATH",
        description="Where Report… wrote report.html last; the next Report… offers it"),
    "report_summary": StringProperty(
        name="Report", description="The last report's answer, P(fit), minimal linker and bound "
                                   "(JSON)", options={"HIDDEN"}),
    **_REPORT_OPTIONS,
    # The checked layout's ensemble (Sample ensemble…; docs/model/ensemble.md#use), cleared by
    # the next check: the result's `ensemble` block without its radial density.
    "ensemble_summary": StringProperty(
        name="Ensemble", description="The checked layout's ensemble the panel shows (JSON)",
        options={"HIDDEN"}),
    # The last Minimal linker…'s map (ui/minimal_summary.py), or that it was cancelled.
    "minimal_map": StringProperty(
        name="Minimal linker", description="The last minimal-linker map the panel shows (JSON)",
        options={"HIDDEN"}),
    # The last Largest fraction…'s map (ui/fraction_summary.py), or that it was cancelled.
    "fraction_map": StringProperty(
        name="Largest fraction", description="The last largest-fraction map the panel shows "
                                             "(JSON)", options={"HIDDEN"}),
    # Several domains per chain: the list (ui/domain_list.py) and its active entry.
    "domains": CollectionProperty(
        type=domain_list.FIBRILFIT_PG_domain, name="Domains",
        description="The chain's domains from the core outward, each with the linker to the "
                    "next"),
    "domain_index": IntProperty(
        name="Domain", description="The list's selected domain", min=0),
}


class FIBRILFIT_PG_settings(bpy.types.PropertyGroup):
    """The model's parameters (one per params.Params field) and the last check's result."""

    __annotations__ = _SETTINGS


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


def _value(settings, field):
    if field.metadata["kind"] in JSON_KINDS:  # JSON text, read exactly: no float32 rounding
        text = getattr(settings, field.name).strip()
        if not text:
            return None
        try:
            return tuple(tuple(xy) for xy in json.loads(text))
        except (ValueError, TypeError):
            return text  # make_params refuses it, naming core_outline
    if field.metadata["kind"] == "list":  # "31, 30": the numbers, or the text if not numbers
        return list_value(getattr(settings, field.name), field.metadata["item"])
    if field.metadata.get("derived") and not getattr(settings, switch_name(field.name)):
        return None
    value = _plain(getattr(settings, field.name))
    k = _scale(field)
    return value if k == 1 else float(f"{value / k:.12g}")  # 5.0 % reads back as 0.05


def list_value(text: str, item=float):
    """A kind "list" parameter's text as a tuple (None when empty); the text itself when it is
    not a list of numbers (make_params then refuses it, naming the parameter)."""
    words = text.replace(",", " ").split()
    if not words:
        return None
    try:
        numbers = tuple(float(w) for w in words)
    except ValueError:
        return text
    if item is int and all(n == int(n) for n in numbers):
        return tuple(int(n) for n in numbers)
    return numbers


def values(settings) -> dict:
    out = {f.name: _value(settings, f) for f in P.fields()}
    out.update(domain_list.values_from_list(settings, out))  # several domains: the list's
    if not settings.use_periodic:
        out["periodic"] = 0
    else:  # the cell replaces the fibril's length and its ends
        out["periodic"] = out["periodic"] or P.NUMBER_WORDS["periodic"]  # "auto"
        out["layers"], out["score_layers"] = P.DEFAULTS.layers, 0
    return out


def read_params(settings) -> P.Params:
    """The panel's values as Params, validated (raises ParamError naming the parameter)."""
    return P.make_params(**values(settings))


def write_params(settings, p: P.Params) -> None:
    derived = {f.name for f in derived_fields()}
    scaled = {f.name: _scale(f) for f in P.fields() if _scale(f) != 1}
    for name, value in p.to_dict().items():
        if name in scaled:
            setattr(settings, name, value * scaled[name])
        elif name == "core_outline" or P.field_spec(name)["kind"] == "rows":
            setattr(settings, name, "" if value is None else json.dumps(value))
        elif P.field_spec(name)["kind"] == "list":
            setattr(settings, name, "" if value is None else ", ".join(f"{v:g}" for v in value))
        elif name in derived:
            setattr(settings, switch_name(name), value is not None)
            if value is not None:
                setattr(settings, name, value)
        else:
            setattr(settings, name, value)
    settings.use_periodic = bool(p.periodic)


def compared_values(settings, panel: P.Params | None = None) -> dict:
    """The panel's values (values()) with a cell of "auto" layers resolved: from `panel`, the
    panel's values already validated (read_params), else by validating them here (left "auto"
    when they are not valid)."""
    now = values(settings)
    if now["periodic"] == P.NUMBER_WORDS["periodic"]:
        try:
            now["periodic"] = (panel or P.make_params(**now)).periodic
        except P.ParamError:
            pass
    return now


def changed_fields(settings, p: P.Params, sections=SECTIONS, *,
                   now: dict | None = None) -> list[tuple[str, object, object]]:
    """Fields of `sections` whose panel value differs from `p`: (name, value in p, panel value).
    `now`: compared_values(settings), when the caller already has them (they are validated once
    per draw or operator, not once per comparison)."""
    now = dict(compared_values(settings) if now is None else now)
    then = p.to_dict()
    if then.get("periodic"):
        now["layers"] = then["layers"]  # a cell's layers follow from periodic
    out = []
    for f in P.fields():
        if section_of(f) in sections:
            old = then[f.name]
            if f.metadata["kind"] in JSON_KINDS:
                old = None if old is None else tuple(map(tuple, old))
                if old != now[f.name]:
                    out.append((f.name, old, now[f.name]))
                continue
            # a list (the domain list's domain_linker) and a tuple (Params') are one value
            old = tuple(old) if isinstance(old, list) else old
            new = tuple(now[f.name]) if isinstance(now[f.name], list) else now[f.name]
            if (None if old is None else _plain(old)) != new:
                out.append((f.name, old, new))
    return out


def store_result(settings, result: dict) -> None:
    settings.verdict = result["verdict"]
    settings.clash_count = len(result["clashing_pairs"])
    settings.max_bond_stretch = result["max_bond_stretch"]
    settings.linker_intact = result["linker_intact"]
    span = result.get("linker_stretch")  # docs/model/linker-integrity.md#linker-span
    settings.linker_stretch = json.dumps(span) if span else ""
    settings.accommodated = result["accommodated"]
    settings.answer = result.get("answer") or ""  # docs/model/verdict.md#answer
    settings.bound = (result.get("bound") or {}).get("impossible_below", 0)  # docs/model/bound.md#derivation


def clear_result(settings) -> None:
    for name in RESULTS:
        settings.property_unset(name)
