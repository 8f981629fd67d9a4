"""Sidebar properties generated from a plan's declarations (plans.py), as the command line's
options are (cli/parser.py): the same default, range, choices and help, said once."""
from __future__ import annotations

from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..plans import spec_of


def plan_property(plan, name: str, **extra):
    """The bpy property for field `name` of `plan` (a plan instance: its value is the default),
    named by the field's label; `extra` goes to the property as it is (options, subtype)."""
    meta = spec_of(type(plan), name)
    default = getattr(plan, name)
    label = meta["label"] or name.replace("_", " ").capitalize()
    text = meta["help"] + (f" ({meta['unit']})" if meta["unit"] else "")
    common = {"name": label, "description": text, **extra}
    if meta["kind"] is bool:
        return BoolProperty(default=bool(default), **common)
    if meta["choices"] is not None:
        return EnumProperty(items=[(c, c, "") for c in meta["choices"]], default=default,
                            **common)
    if meta["kind"] in (int, float):
        bounds = {k: v for k, v in (("min", meta["min"]), ("max", meta["max"])) if v is not None}
        kind = IntProperty if meta["kind"] is int else FloatProperty
        return kind(default=default if default is not None else bounds.get("min", 0),
                    **bounds, **common)
    return StringProperty(default=default or "", **common)
