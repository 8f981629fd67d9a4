"""Where the sidebar's values came from, and whether a kept result still belongs to them
(issue #45). Plain Python, no bpy: tests/unit/test_provenance.py reads it.

A result made from the panel (Report…) names each value's true source: the structure file it was
measured from (as the command line's `--fibril`/`--domain` says it: structure/from_files.py's
sources), the default, or the sidebar (set by hand). The panel keeps its numbers in 32 bits, so
a measured 4.8251234 Å reads back as 4.8251233: a value within that rounding of its measurement
is the measurement, and the result runs the measured value itself (as the command line would).

A result the panel keeps (the last report, the last minimal-linker map) records the values it was
made for; `changed_names` says which of them the panel no longer holds, so the panel can mark it
as belonging to earlier values rather than to the model on screen.
"""
from __future__ import annotations

import math

from ..model import params as P

SIDEBAR = "sidebar"  # a value set in the panel by hand (docs/guide/report.md's sources)
REL = 1e-6  # float32 keeps 7 significant digits: closer than this is the same value


def same_value(a, b) -> bool:
    """Whether two parameter values are one value: numbers within the panel's float32 rounding,
    sequences (tuples or lists: the panel and the files differ) item by item."""
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b))
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=REL, abs_tol=1e-9)
    return a == b


def panel_sources(panel: dict, measured: dict, block: dict | None) -> tuple[dict, dict]:
    """(values, sources) of a result made from the panel's `panel` values (properties.values):
    a value the panel holds as the structure files measured it (`measured`: from_files.merged's
    values with nothing explicit; `block`: its structure block) is the measured value, its source
    the file's ("6cu7.pdb.gz: measured over 36 layer pairs, ..."); else its source is "default"
    when it is the default (or a derived one left to its rule) and "sidebar" when set by hand."""
    said = (block or {}).get("sources", {})
    named = [m["file"] for m in ((block or {}).get("fibril"), (block or {}).get("domain")) if m]
    values, sources = dict(panel), {}
    for f in P.fields():
        name, value = f.name, panel.get(f.name)
        if name in measured and same_value(value, measured[name]):
            values[name] = measured[name]
            sources[name] = said.get(name) or f"{named[0] if named else 'a file'}: measured"
        elif value is None and f.metadata.get("derived"):
            sources[name] = f"default: {f.metadata['derived']}"
        elif same_value(value, getattr(P.DEFAULTS, name)):
            sources[name] = "default"
        else:
            sources[name] = SIDEBAR
    return values, sources


def changed_names(then: dict, now: dict, ignore=()) -> list[str]:
    """The parameters whose value in `now` (the panel's, properties.compared_values) differs
    from `then` (the values a kept result was made for), in the definition's order; `ignore`:
    those the result does not depend on (the minimal-linker map searches the linker)."""
    return [f.name for f in P.fields() if f.name in then and f.name not in ignore
            and not same_value(then[f.name], now.get(f.name))]
