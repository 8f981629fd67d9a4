"""Typed options declared once: how a command's options are described, bounded and checked.

A plan is a frozen dataclass whose fields are declared with `option()`: each field's default,
help, unit, range or choices, as `Params` declares the model's (model/param_spec.py). The
command line (cli/parser.py) and the sidebar (ui/) generate their options and properties from
these declarations and turn their input into a plan once, at the edge; every room below them
takes plans, never an argparse namespace. The plans themselves live in the rooms whose question
they answer: where the runs happen (batch/plans.py), the structure files to read
(structure/request.py), the pictures and outputs (exports/plans.py), a sweep (sweep/plans.py),
the restarts, the minimal-linker walk and the report (search/plans.py); a command's whole plan
is api/plans.py's.

A bad value raises PlanError, one line naming the option as the command line spells it
(`--restarts: must be at least 1 (got 0)`); `PlanError.field` names the field, for a caller
that speaks other words (the sidebar's labels). Plain Python: no bpy, no argparse.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Callable

from .exits import UsageError


class PlanError(UsageError):
    """A bad option value: `field` is the plan's field, `reason` what is wrong with it."""

    def __init__(self, field: str, reason: str):
        super().__init__(f"{flag(field)}: {reason}")
        self.field, self.reason = field, reason


def flag(name: str) -> str:
    """A field's command-line option: `max_linker` -> `--max-linker`."""
    return "--" + name.replace("_", "-")


def option(default: Any, help: str, *, kind: Any = None, lo=None, hi=None, unit: str = "",
           choices=None, metavar: str | None = None, repeat: bool = False,
           check: Callable[[Any], str | None] | None = None, label: str | None = None,
           group: str = "", cli: bool = True, default_text: str | None = None,
           noun: str | None = None):
    """A plan's field. `kind`: int, float, str, bool or "path" (default: the default's type;
    str for None); `lo`/`hi`: the allowed range, inclusive (None: open); `choices`: the allowed
    words; `repeat`: given any number of times, a tuple; `check(value)`: a reason the value is
    wrong, or None; `label`: the sidebar's name for it; `group`: the command line's argument
    group; `cli`: offered on the command line; `default_text`: the help's default when the
    default alone does not say it; `noun`: what a value of the wrong type should have been
    ("a residue number"; default: "an integer" or "a number")."""
    if kind is None:
        kind = bool if isinstance(default, bool) else type(default) if default is not None \
            else str
    meta = {"help": help, "kind": kind, "min": lo, "max": hi, "unit": unit,
            "choices": tuple(choices) if choices is not None else None, "metavar": metavar,
            "repeat": repeat, "check": check, "label": label, "group": group, "cli": cli,
            "noun": noun,
            "default_text": default_text}
    if repeat:
        default = tuple(default or ())
    return dataclasses.field(default=default, metadata=meta)


def is_plan(cls_or_value) -> bool:
    cls = cls_or_value if isinstance(cls_or_value, type) else type(cls_or_value)
    return dataclasses.is_dataclass(cls) and issubclass(cls, Plan)


@dataclasses.dataclass(frozen=True)
class Plan:
    """Base of every plan: checked when made (`make`, or the constructor: __post_init__), so a
    plan that exists is valid; `replace` makes a checked copy; `to_dict` gives plain values."""

    def __post_init__(self):
        for f in option_fields(type(self)):
            value = _typed(f, getattr(self, f.name))
            object.__setattr__(self, f.name, value)
        self.check()

    def check(self) -> None:
        """Combinations of fields that are refused (a plan adds its own); each field alone is
        checked from its declaration."""

    @classmethod
    def make(cls, **values):
        """A plan from keyword values (unknown names refused in one line)."""
        known = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(values) - known)
        if unknown:
            raise PlanError(unknown[0], f"not an option of {cls.__name__}; known: "
                                        f"{', '.join(sorted(known))}")
        return cls(**values)

    def replace(self, **changes):
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if is_plan(value):
                value = value.to_dict()
            elif isinstance(value, tuple):
                value = list(value)
            elif isinstance(value, dict):
                value = dict(value)
            out[f.name] = value
        return out


def option_fields(cls) -> list[dataclasses.Field]:
    """The fields declared with option() (not the nested plans of a command's plan)."""
    return [f for f in dataclasses.fields(cls) if "help" in f.metadata]


def spec_of(cls, name: str) -> dict:
    """Field `name`'s declaration (help, kind, range, ...) and its default."""
    f = cls.__dataclass_fields__[name]
    return {**f.metadata, "default": f.default}


def _typed(f: dataclasses.Field, value):
    """`value` as the field's kind, checked against its range, choices and check."""
    meta = f.metadata
    if meta["repeat"]:
        if value is None:
            value = ()
        items = [value] if isinstance(value, (str, int, float)) else list(value)
        return tuple(_one(f.name, meta, v) for v in items)
    if value is None:
        return None
    return _one(f.name, meta, value)


def _one(name: str, meta: dict, value):
    kind = meta["kind"]
    if kind is bool:
        if not isinstance(value, bool):
            raise PlanError(name, f"must be true or false (got {value!r})")
        return value
    if kind is int:
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise PlanError(name, f"must be {meta['noun'] or 'an integer'} (got {value!r})")
        try:
            number = float(value)
            if not number.is_integer():
                raise ValueError
            value = int(number)
        except (ValueError, OverflowError):
            raise PlanError(name, f"must be {meta['noun'] or 'an integer'} "
                                  f"(got {value!r})") from None
    elif kind is float:
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise PlanError(name, f"must be {meta['noun'] or 'a number'} (got {value!r})") from None
        if not math.isfinite(value):
            raise PlanError(name, f"must be a finite number (got {value!r})")
    elif kind in (str, "path"):
        value = str(value)
    if meta["choices"] is not None and value not in meta["choices"]:
        raise PlanError(name, f"must be one of {', '.join(map(str, meta['choices']))} "
                              f"(got {value!r})")
    lo, hi = meta["min"], meta["max"]
    shown = f"{value:g}" if isinstance(value, float) else value
    unit = f" {meta['unit']}" if meta["unit"] else ""
    if lo is not None and hi is not None and not lo <= value <= hi:
        what = "an integer " if kind is int else ""  # as the model's (param_values.describe_range)
        raise PlanError(name, f"must be {what}from {lo} to {hi}{unit} (got {shown})")
    if lo is not None and value < lo:
        raise PlanError(name, f"must be at least {lo}{unit} (got {shown})")
    if hi is not None and value > hi:
        raise PlanError(name, f"must be at most {hi}{unit} (got {shown})")
    if meta["check"] is not None:
        reason = meta["check"](value)
        if reason:
            raise PlanError(name, reason)
    return value


def help_text(cls_or_plan, name: str) -> str:
    """The field's help with its default ('[default 5]'), for the command line and tooltips;
    from a plan instance, that instance's value is the default shown."""
    cls = cls_or_plan if isinstance(cls_or_plan, type) else type(cls_or_plan)
    meta = cls.__dataclass_fields__[name].metadata
    default = (getattr(cls_or_plan, name) if not isinstance(cls_or_plan, type)
               else cls.__dataclass_fields__[name].default)
    if meta["default_text"] is not None:
        said = meta["default_text"]
    elif meta["kind"] is bool or default in (None, ()):
        said = ""
    else:
        said = f"default {default}"
    return meta["help"] + (f" [{said}]" if said else "")
