"""The CI gate: --require "linker=6,globule_diameter=30:accommodated>=0.9".

A requirement is an optional selector (parameter=value pairs; seeds are pooled, so no seed) and
a condition on a summary metric. It must hold for every grid point the selector matches.
"""
from __future__ import annotations

import dataclasses
import math
import operator
import re

from ..model import params as P
from .grid import GridError
from .summary import columns, fmt_value

METRICS = {
    "accommodated": "fraction of seeds accommodated",
    "accommodated_low": "lower end of its 95 % Wilson interval",
    "accommodated_high": "upper end of its 95 % Wilson interval",
    "clash": "fraction of seeds ending with intersecting globules",
    "stretch": "median worst bond stretch (fraction)",
    "frames": "median frames baked",
    "outer_diameter": "median envelope outer diameter over the seeds, Å",
    "n": "runs with a verdict",
    "failed": "runs that failed twice",
}
OPERATORS = {">=": operator.ge, "<=": operator.le, "==": operator.eq, "!=": operator.ne,
             ">": operator.gt, "<": operator.lt}
_CONDITION = re.compile(r"^\s*([a-z_]+)\s*(>=|<=|==|!=|>|<)\s*([^\s<>=!]+)\s*$")
FORM = 'e.g. "linker=6,globule_diameter=30:accommodated>=0.9"'


@dataclasses.dataclass(frozen=True)
class Requirement:
    text: str
    selector: dict  # parameter -> number (or bool)
    metric: str
    op: str
    threshold: float

    def matches(self, values: dict) -> bool:
        for name, want in self.selector.items():
            have = values.get(name)
            if isinstance(want, bool) or isinstance(have, bool):
                if bool(have) != want:
                    return False
            elif have is None or not math.isclose(float(have), want, rel_tol=1e-9,
                                                  abs_tol=1e-12):
                return False
        return True

    def where(self) -> str:
        return ", ".join(f"{k}={v:g}" if not isinstance(v, bool) else f"{k}={v}"
                         for k, v in self.selector.items()) or "every grid point"


def _fail(text: str, why: str):
    raise GridError("--require", f"{text!r}: {why}; {FORM}")


def parse(text: str) -> Requirement:
    selector_text, _, condition = text.rpartition(":")
    m = _CONDITION.match(condition)
    if not m:
        _fail(text, "the condition must be METRIC OP NUMBER")
    metric, op, number = m.groups()
    if metric not in METRICS:
        _fail(text, f"unknown metric {metric!r}; known: {', '.join(METRICS)}")
    try:
        threshold = float(number)
    except ValueError:
        _fail(text, f"{number!r} is not a number")
    selector = {}
    for item in [i for i in selector_text.split(",") if i.strip()]:
        name, eq, value = item.partition("=")
        name = name.strip().replace("-", "_")
        if not eq or not value.strip():
            _fail(text, f"{item.strip()!r} must be PARAMETER=VALUE")
        if name == "seed":
            _fail(text, "seeds are pooled into each fraction and cannot be selected")
        if name not in P.Params.__dataclass_fields__ or name == "slab":
            _fail(text, f"{name!r} is not a parameter that can be selected")
        kind = P.field_spec(name)["kind"]
        value = value.strip()
        if kind is bool:
            if value.lower() not in ("true", "false", "1", "0", "yes", "no", "on", "off"):
                _fail(text, f"{name} must be true or false")
            selector[name] = value.lower() in ("true", "1", "yes", "on")
            continue
        try:
            selector[name] = float(value)
        except ValueError:
            _fail(text, f"{name}={value!r} is not a number")
    return Requirement(text, selector, metric, op, threshold)


def check(requirements: list[Requirement], rows) -> tuple[list[str], list[str]]:
    """Lines for the requirements met and for those failed (one line per failing point)."""
    met, failed = [], []
    shown = columns(rows)
    for req in requirements:
        hits = [r for r in rows if req.matches(r.values)]
        if not hits:
            failed.append(f"requirement failed: {req.text}: no grid point has {req.where()}")
            continue
        bad = []
        for r in hits:
            value = r.metric(req.metric)
            where = req.where() if len(hits) == 1 else ", ".join(
                f"{n}={fmt_value(r.values[n])}" for n in shown)
            if value is None:
                bad.append(f"requirement failed: {req.text}: {where}: no finished runs "
                           f"({r.failed} failed)")
            elif not OPERATORS[req.op](value, req.threshold):
                bad.append(f"requirement failed: {req.text}: {where}: {req.metric} "
                           f"{_show(req.metric, value, r)}, needs {req.op} {req.threshold:g}")
        if bad:
            failed += bad
        else:
            values = ", ".join(_show(req.metric, r.metric(req.metric), r) for r in hits)
            met.append(f"requirement met: {req.text}: {req.metric} {values}")
    return met, failed


def _show(metric: str, value, row) -> str:
    if metric == "accommodated":
        return f"{value:.3g} ({row.accommodated}/{row.n})"
    return f"{value:.3g}" if isinstance(value, float) else str(value)
