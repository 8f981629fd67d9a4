"""Pool the seeds of each grid point: accommodated fraction with its Wilson interval, clash
fraction, median stretch and frames; the CSV, the printed table and the minimal linker.

A fraction here is the fraction of seeds whose relaxation found a clash-free layout with intact
linkers. A seed that ended in a clash does not prove that no such layout exists.
"""
from __future__ import annotations

import csv
import dataclasses
import hashlib
import io
import json
import statistics

from ..model import params as P
from .grid import with_defaults
from .stats import wilson

MEANING = ("accommodated = the fraction of seeds whose relaxation found a clash-free layout with "
           "intact linkers (95 % Wilson interval).\nA seed that ended in a clash does not prove "
           "that no clash-free layout exists, so this is a lower bound on what fits.")
ALWAYS = ("linker", "globule_diameter")


@dataclasses.dataclass
class Row:
    """One grid point (all parameters but the seed) over its seeds."""

    values: dict
    n: int = 0  # runs that finished with a verdict
    failed: int = 0  # runs that failed twice (or gave no verdict)
    accommodated: int = 0
    clashes: int = 0
    stretches: list = dataclasses.field(default_factory=list)
    frames: list = dataclasses.field(default_factory=list)
    diameters: list = dataclasses.field(default_factory=list)  # envelope outer_diameter, Å

    @property
    def fraction(self) -> float | None:
        return self.accommodated / self.n if self.n else None

    @property
    def interval(self) -> tuple[float, float] | tuple[None, None]:
        return wilson(self.accommodated, self.n) if self.n else (None, None)

    @property
    def clash_fraction(self) -> float | None:
        return self.clashes / self.n if self.n else None

    @property
    def median_stretch(self) -> float | None:
        return statistics.median(self.stretches) if self.stretches else None

    @property
    def median_frames(self) -> float | None:
        return statistics.median(self.frames) if self.frames else None

    @property
    def diameter(self) -> tuple[float, float, float] | tuple[None, None, None]:
        """The envelope's outer diameter over the seeds: median, min, max (Å)."""
        d = self.diameters
        return (statistics.median(d), min(d), max(d)) if d else (None, None, None)

    def metric(self, name: str):
        """The value a --require condition names (see gate.METRICS)."""
        low, high = self.interval
        return {"accommodated": self.fraction, "accommodated_low": low,
                "accommodated_high": high, "clash": self.clash_fraction,
                "stretch": self.median_stretch, "frames": self.median_frames,
                "n": self.n, "failed": self.failed, "outer_diameter": self.diameter[0]}[name]


def _group_key(params: dict) -> str:
    return json.dumps({k: v for k, v in params.items() if k != "seed"}, sort_keys=True)


def rows(records: list[dict]) -> list[Row]:
    groups: dict[str, Row] = {}
    for r in records:
        params = with_defaults(r["params"])
        row = groups.setdefault(_group_key(params), Row({k: v for k, v in params.items()
                                                         if k != "seed"}))
        if r.get("status", "ok") != "ok" or "accommodated" not in r:
            row.failed += 1
            continue
        row.n += 1
        row.accommodated += bool(r["accommodated"])
        row.clashes += r.get("verdict") == "intersection"
        if r["max_bond_stretch"] is not None:  # None: "no exit", nothing simulated
            row.stretches.append(r["max_bond_stretch"])
        row.frames.append(r["frames_simulated"])
        outer = (r.get("envelope") or {}).get("outer_diameter")
        if outer is not None:
            row.diameters.append(outer)
    return sorted(groups.values(), key=lambda row: _sort_key(row.values))


def order_key(value):
    """Sorts any parameter value: None (a derived default) first, then numbers, then lists
    (sizes, anchors), then outlines (lists of points), so mixed axes never compare a list to None."""
    if value is None:
        return (0, 0)
    if isinstance(value, list):
        if value and isinstance(value[0], list):
            return (3, json.dumps(value))
        return (2, tuple(value))
    return (1, value)


def _sort_key(values: dict):
    return tuple(order_key(v) for _, v in sorted(values.items()))


def varied(rows_: list[Row]) -> list[str]:
    """Parameters (but the seed) that take more than one value, in the parameter order."""
    names = []
    for f in P.fields():
        values = {json.dumps(r.values.get(f.name)) for r in rows_}
        if f.name != "seed" and len(values) > 1:
            names.append(f.name)
    return names


def columns(rows_: list[Row]) -> list[str]:
    """The parameters a table shows: linker and globule diameter always, then what varies."""
    return list(ALWAYS) + [n for n in varied(rows_) if n not in ALWAYS]


def fmt_value(value) -> str:
    if value is None:
        return "auto"  # a derived default: 2π/K, the slab's box, the tutorial's anchor
    if isinstance(value, list) and value and isinstance(value[0], list):  # a core outline
        digest = hashlib.sha1(json.dumps(value).encode()).hexdigest()[:6]
        return f"{len(value)}-point outline {digest}"
    if isinstance(value, list):
        return "x".join(f"{v:g}" for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _num(x, digits: int) -> str:
    return "" if x is None else f"{round(x, digits) + 0.0:.{digits}f}"  # + 0.0: no "-0.000"


CSV_FIELDS = ("n", "failed", "accommodated", "accommodated_fraction", "wilson95_low",
              "wilson95_high", "clash_fraction", "median_stretch", "median_frames",
              "outer_diameter_median", "outer_diameter_min", "outer_diameter_max")


def csv_text(rows_: list[Row]) -> str:
    names = columns(rows_)
    # the protocol on every row (last, unless it varies): it explains why a sweep (tutorial by
    # default) and minimal-linker (inflate) can disagree
    tail = [] if "protocol" in names else ["protocol"]
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(names + list(CSV_FIELDS) + tail)
    for r in rows_:
        low, high = r.interval
        writer.writerow([fmt_value(r.values[n]) for n in names] + [
            r.n, r.failed, r.accommodated, _num(r.fraction, 4), _num(low, 4), _num(high, 4),
            _num(r.clash_fraction, 4), _num(r.median_stretch, 6),
            "" if r.median_frames is None else f"{r.median_frames:g}",
            *(_num(d, 1) for d in r.diameter)] + [r.values.get("protocol") for _ in tail])
    return buf.getvalue()


@dataclasses.dataclass
class Minimal:
    """The shortest linker reaching the target, for one combination of the other parameters."""

    group: dict
    row: Row | None  # None: no linker in the sweep reaches the target
    best: Row | None


def minimal_linkers(rows_: list[Row], target: float) -> list[Minimal]:
    others = [n for n in columns(rows_) if n != "linker"]
    groups: dict[str, list[Row]] = {}
    for r in rows_:
        groups.setdefault(json.dumps([r.values[n] for n in others]), []).append(r)
    found = []
    for members in groups.values():
        members.sort(key=lambda r: r.values["linker"])
        scored = [r for r in members if r.n]
        hit = next((r for r in scored if r.fraction >= target), None)
        best = max(scored, key=lambda r: (r.fraction, -r.values["linker"]), default=None)
        found.append(Minimal({n: members[0].values[n] for n in others}, hit, best))
    return found


def _label(values: dict) -> str:
    return ", ".join(f"{n} {fmt_value(v)}" for n, v in values.items())


def _ci(row: Row) -> str:
    low, high = row.interval
    return f"{row.accommodated}/{row.n}, 95 % CI {low:.2f}-{high:.2f}"


def seeds_to_show(target: float, most: int = 100_000) -> int | None:
    """The fewest seeds, all accommodated, whose 95 % Wilson interval lies at or above `target`
    (73 for 0.95); None if no number up to `most` does (a target of 1)."""
    n = 1
    while n <= most:
        if wilson(n, n)[0] >= target:
            return n
        n = n * 2 if wilson(n * 2, n * 2)[0] < target else n + 1
    return None


def shown(row: Row, target: float) -> str:
    """What a row's seeds show about P(fit) against `target`: 'k of n seeds (95 % CI a-b)' and,
    when the interval's low end is below the target, that too few seeds ran to show it."""
    low, high = row.interval
    count = (f"all {row.n} of {row.n} seeds" if row.accommodated == row.n
             else f"{row.accommodated} of {row.n} seeds")
    text = f"{count} accommodated, 95 % CI {low:.2f}-{high:.2f}"
    if low >= target:
        return text + f"; P(fit) ≥ {target:g} shown"
    need = seeds_to_show(target)
    return text + (f"; {row.n} seeds cannot show P(fit) ≥ {target:g}"
                   + (f" (that needs the interval's low end there: at least {need} seeds, all "
                      f"accommodated)" if need else ""))


def _setting(rows_: list[Row]) -> str:
    """The protocol(s) and seeds per point behind a sweep's fractions."""
    protocols = sorted({str(r.values.get("protocol", P.DEFAULTS.protocol)) for r in rows_})
    seeds = sorted({r.n for r in rows_ if r.n})
    per = (f"{seeds[0]}" if len(seeds) == 1 else f"{seeds[0]}-{seeds[-1]}") if seeds else "0"
    return f"protocol {', '.join(protocols)}, {per} seeds per point"


def minimal_lines(rows_: list[Row], target: float) -> list[str]:
    lines = [f"minimal linker with an accommodated fraction of at least {target:g} "
             f"({_setting(rows_)}):"]
    for m in minimal_linkers(rows_, target):
        if m.row is not None:
            lines.append(f"  {_label(m.group)}: linker {m.row.values['linker']} "
                         f"({shown(m.row, target)})")
        elif m.best is not None:
            lines.append(f"  {_label(m.group)}: none in this sweep (best: linker "
                         f"{m.best.values['linker']}, {_ci(m.best)})")
        else:
            lines.append(f"  {_label(m.group)}: no finished runs")
    return lines


def _diameter_text(r: Row) -> str:
    mid, low, high = r.diameter
    return "-" if mid is None else f"{mid:.0f} ({low:.0f}-{high:.0f})"


def table(rows_: list[Row], target: float) -> str:
    names = columns(rows_)
    head = names + ["n", "failed", "accommodated", "95 % CI", "clash", "stretch", "frames",
                    "outer Å"]
    body = []
    for r in rows_:
        low, high = r.interval
        body.append([fmt_value(r.values[n]) for n in names] + [
            str(r.n), str(r.failed), _num(r.fraction, 2) or "-",
            f"{low:.2f}-{high:.2f}" if r.n else "-", _num(r.clash_fraction, 2) or "-",
            _num(r.median_stretch, 3) or "-",
            "-" if r.median_frames is None else f"{r.median_frames:g}",
            _diameter_text(r)])
    widths = [max(len(h), *(len(b[i]) for b in body)) if body else len(h)
              for i, h in enumerate(head)]
    lines = ["  ".join(h.rjust(w) for h, w in zip(head, widths))]
    lines += ["  ".join(c.rjust(w) for c, w in zip(b, widths)) for b in body]
    lines += ["clash = fraction of seeds ending with intersecting globules; stretch = median of "
              "the worst bond stretch (fraction); frames = median frames baked; outer = the envelope's "
              "outer diameter, median (range) over the seeds.", MEANING, ""]
    return "\n".join(lines + minimal_lines(rows_, target))
