"""The sweep's grid: parse list and range specs, take their product with the seeds, and validate
every point through params.make_params, so each error names the parameter and its range."""
from __future__ import annotations

import dataclasses
import itertools
import json
import math
from decimal import Decimal, InvalidOperation

from ..model import params as P
from ..model.param_checks import refuse_beside_periodic
from ..model.param_spec import ANGLE_UNITS
from ..model.param_values import split_unit

MAX_POINTS = 1_000_000
MAX_RANGE = 100_000
SPEC_HELP = "a list (2,4,6), an inclusive range (1:12 or 0.02:0.05:0.01), or both (1:4,8)"


class GridError(P.ParamError):
    """A malformed spec or an empty grid; `param` names the parameter (or option)."""


@dataclasses.dataclass(frozen=True)
class Point:
    """One run of the sweep: every parameter (validated) and the ones the sweep set."""

    params: dict
    point: dict

    @property
    def key(self) -> str:
        return point_key(self.params)


def point_key(params: dict) -> str:
    """Identity of a run: all of its parameters, so --resume never mixes different models."""
    return json.dumps(with_defaults(params), sort_keys=True)


def with_defaults(params: dict) -> dict:
    """A record's parameters with every parameter it predates at its default: a parameter is
    only ever added with a default that keeps the earlier model, so an older results.jsonl
    still resumes and summarises beside new runs."""
    return {**P.DEFAULTS.to_dict(), **params}


def _number(name: str, spec: str, text: str) -> Decimal:
    try:
        value = Decimal(text.strip())
    except InvalidOperation:
        raise GridError(name, f"{spec!r} is not {SPEC_HELP}") from None
    if not value.is_finite():
        raise GridError(name, f"{spec!r} is not {SPEC_HELP}")
    return value


def _text(value: Decimal) -> str:
    return format(value.normalize(), "f")


def _unit(name: str, spec: str, parts: list[str]) -> tuple[list[str], str]:
    """An angle's range may name its unit on any of its numbers (0.5deg:2deg:0.5 or
    0.5:2:0.5deg): the numbers without it, and the unit every value is then written with."""
    if not P.is_angle(name):
        return parts, ""
    split = [split_unit(part) for part in parts]
    units = {part[len(number):].strip() for part, (number, factor) in zip(parts, split)
             if factor is not None}
    if len({ANGLE_UNITS[u.lower()] for u in units}) > 1:
        raise GridError(name, f"range {spec!r} mixes units; give one (e.g. 0.5:2:0.5deg)")
    return [number for number, _ in split], (units.pop() if units else "")


def _range(name: str, spec: str, item: str) -> list[str]:
    parts = item.split(":")
    if len(parts) not in (2, 3):
        raise GridError(name, f"{spec!r} is not {SPEC_HELP}")
    parts, unit = _unit(name, spec, parts)
    start, stop = _number(name, spec, parts[0]), _number(name, spec, parts[1])
    step = _number(name, spec, parts[2]) if len(parts) == 3 else Decimal(1)
    if step <= 0:
        raise GridError(name, f"range {item!r} needs a positive step (got {_text(step)})")
    if start > stop:
        raise GridError(name, f"range {item!r} is empty: its start is above its stop, so the grid "
                              f"would be empty")
    count = int((stop - start) / step) + 1  # Decimal arithmetic: 0.02:0.05:0.01 has 4 values
    if count > MAX_RANGE:
        raise GridError(name, f"range {item!r} has {count} values; at most {MAX_RANGE}")
    return [_text(start + i * step) + unit for i in range(count)]


def parse_spec(name: str, spec) -> list[str]:
    """The values of one option, as strings in the order given (make_params checks each)."""
    text = str(spec).strip()
    if not text:
        raise GridError(name, f"empty value; give {SPEC_HELP}")
    values = []
    for item in text.split(","):
        if not item.strip():
            raise GridError(name, f"{spec!r} has an empty item; give {SPEC_HELP}")
        # a single value goes to make_params as typed, so its error names the allowed range
        values += _range(name, spec, item) if ":" in item else [item.strip()]
    return list(dict.fromkeys(values))


def seed_values(seeds: int | None, seed_spec: str | None) -> list[str]:
    """--seeds N means seeds 0..N-1; a list or range (--seed-list / --seed) gives them directly."""
    if seeds is not None and seed_spec is not None:
        raise GridError("seeds", "give either --seeds N or a seed list (--seed-list / --seed), "
                                 "not both")
    if seed_spec is not None:
        return parse_spec("seed", seed_spec)
    n = 1 if seeds is None else seeds
    if n < 1:
        raise GridError("seeds", f"must be at least 1 (got {n}), so the grid would be empty")
    return [str(s) for s in range(n)]


def build(specs: dict, seeds: list[str], *, force: bool = False,
          base: dict | None = None) -> list[Point]:
    """Every combination of `specs` (name -> list of values) for every seed, seed-major so an
    interrupted sweep has covered the whole grid evenly. Raises ParamError for any bad point.
    `base`: fixed values under every point (e.g. measured from --fibril), not sweep axes."""
    names = [f.name for f in P.fields() if f.name in specs and f.name != "seed"]
    lists = [list(specs[n]) for n in names]
    size = math.prod(len(v) for v in lists) * len(seeds)
    if size == 0:
        raise GridError("grid", "is empty")
    if size > MAX_POINTS:
        raise GridError("grid", f"has {size} runs; at most {MAX_POINTS}")
    points, seen = [], set()
    for seed in seeds:
        for combo in itertools.product(*lists):
            values = {**(base or {}), **dict(zip(names, combo)), "seed": seed}
            p = P.make_params(force=force, **values).to_dict()
            point = {n: p[n] for n in names} | {"seed": p["seed"]}
            pt = Point(p, point)
            if pt.key not in seen:  # "6" and "6.0" are one point
                seen.add(pt.key)
                points.append(pt)
    return points


def specs_from(values: dict) -> dict:
    """name -> list of value strings, for every parameter given (`values`: name -> the value as
    given, a list or range for a sweep; not seed)."""
    specs = {}
    for f in P.fields():
        value = values.get(f.name)
        if value is None or f.name == "seed":
            continue
        if f.metadata["kind"] is bool:
            specs[f.name] = [value]
        elif f.name == "slab" or f.metadata["size"]:  # one spec per coordinate: their product
            axes = [parse_spec(f"{f.name} {axis}", v) for axis, v in zip("XYZ", value)]
            specs[f.name] = [" ".join(c) for c in itertools.product(*axes)]
        elif f.metadata["kind"] == "points" and isinstance(value, (list, tuple)):
            specs[f.name] = [json.dumps(value)]  # inline points (from a case file)
        elif f.metadata["kind"] == "list":  # lists of numbers: the lists ';'-separated
            specs[f.name] = [",".join(str(v) for v in value)] if isinstance(
                value, (list, tuple)) else [item.strip() for item in str(value).split(";")]
        elif f.metadata["kind"] == "points":  # outline files (or 'box'), comma-separated
            specs[f.name] = [item.strip() for item in str(value).split(",")]
        else:
            specs[f.name] = parse_spec(f.name, value)
    refuse_beside_periodic(specs)
    return specs
