"""A parameter's value as typed (CLI, panel, case file, JSON) made into the model's: numbers in
range, angles with their unit, lists, rows, vectors. Each raises ParamError naming the parameter
and what it accepts.
"""
from __future__ import annotations

import json
import math
import pathlib
from typing import Any

import numpy as np

from ..geom import polygons
from .param_spec import (ANGLE_UNITS, DERIVED_WORDS, MAX_COORDINATE, MAX_OUTLINE_POINTS,
                         MAX_SHAPE_ROWS, NUMBER_WORDS, ParamError)


def field_value(name: str, value: Any, meta: dict):
    """Parameter `name`'s value (its spec `meta`) as given, made into the model's: score_layers'
    word ('all') is 0; a derived parameter's word (DERIVED_WORDS) or None asks for its default
    (None); anything else is read as its kind (typed_value). (periodic's word, 'auto', is
    make_params': it needs the other values.)"""
    if name == "score_layers" and isinstance(value, str) \
            and value.strip().lower() == NUMBER_WORDS[name]:
        value = 0
    if meta["derived"] and (value is None or (isinstance(value, str)
                                              and value.strip().lower() in DERIVED_WORDS)):
        return None
    return typed_value(name, value, meta)


def plain(value):
    """A parameter's value with its tuples (and their tuples) as lists, as JSON holds it."""
    return [plain(v) for v in value] if isinstance(value, (tuple, list, np.ndarray)) else value


def typed_value(name: str, value: Any, meta: dict):
    """Parameter `name`'s value as its spec (`meta`) reads it: rows, an outline's points (a JSON
    list, or a file naming one), a list, a vector, or one number, word or angle (coerce)."""
    if meta["kind"] == "rows":
        return None if value is None else rows_value(name, value, meta)
    if meta["kind"] == "points":
        if isinstance(value, str) and value.strip().startswith("["):
            try:
                value = json.loads(value)
            except ValueError:
                raise ParamError(name, f"is not a JSON list of [x, y] points "
                                       f"(got {value[:40]!r})") from None
        return (read_outline(value) if isinstance(value, (str, pathlib.Path))
                else outline_value(value))
    if meta["kind"] == "list":
        return list_value(name, value, meta)
    if name == "slab" or meta["size"]:
        return vector_value(name, value, meta, meta["size"] or 3)
    return coerce(name, value, meta)


def read_outline(path) -> tuple:
    """A core outline from a JSON file: a list of [x, y] in Å. Raises ParamError."""
    try:
        text = pathlib.Path(path).expanduser().read_text(encoding="utf-8")
        data = json.loads(text)
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise ParamError("core_outline", f"cannot read '{path}' as a JSON list of [x, y] points "
                                         f"({' '.join(str(reason).split())})") from None
    return outline_value(data, f" in '{path}'")


def outline_value(value, where: str = "") -> tuple:
    """A core outline (core_outline) from a list of [x, y] points, cleaned and checked."""
    try:
        points = polygons.clean_outline(value)
    except polygons.GeometryError as exc:
        raise ParamError("core_outline", f"the outline{where} {exc}") from None
    if len(points) > MAX_OUTLINE_POINTS:
        raise ParamError("core_outline", f"the outline{where} has {len(points)} points; at most "
                                         f"{MAX_OUTLINE_POINTS}")
    if np.abs(points).max() > MAX_COORDINATE:
        raise ParamError("core_outline", f"the outline{where} reaches {np.abs(points).max():g} Å "
                                         f"from the axis; coordinates must be from "
                                         f"{-MAX_COORDINATE:g} to {MAX_COORDINATE:g} Å")
    return tuple((float(x), float(y)) for x, y in points)


def coerce(name: str, value: Any, meta: dict):
    kind = meta["kind"]
    if meta["unit"] == "rad":
        value = angle_value(name, value, meta)
    if kind is bool:
        if isinstance(value, bool):
            return value
        if isinstance(value, str) and value.lower() in ("1", "true", "yes", "on", "0", "false", "no", "off"):
            return value.lower() in ("1", "true", "yes", "on")
        if isinstance(value, (int, float)) and value in (0, 1):
            return bool(value)
        raise ParamError(name, f"must be true or false (got {value!r})")
    if kind is str and "choices" not in meta:  # free text (a pattern's letters)
        if not isinstance(value, str):
            raise ParamError(name, f"must be text (got {value!r})")
        return value.strip()
    if "choices" in meta:
        text = value.strip().lower() if isinstance(value, str) else value
        if text not in meta["choices"]:
            raise ParamError(name, f"{describe_range(meta)} (got {value!r})")
        return text
    per = 1.0  # a fraction shown in % (SHOWN_IN) may be typed so too: '30%' is 0.3
    typed = value
    if meta.get("shown_in") == "%" and isinstance(value, str) and value.strip().endswith("%"):
        value, per = value.strip()[:-1], 100.0
    try:
        if isinstance(value, bool):
            raise TypeError
        if isinstance(value, str):
            number = float(value.strip()) / per
        else:
            number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParamError(name, f"{describe_range(meta)} (got {value!r})") from None
    if not math.isfinite(number):
        raise ParamError(name, f"{describe_range(meta)} (got {value!r})")
    if kind is int:
        if number != int(number):
            raise ParamError(name, f"{describe_range(meta)} (got {value!r})")
        number = int(number)
    if not meta["min"] <= number <= meta["max"]:
        raise ParamError(name, f"{describe_range(meta)} (got {typed!r})")
    return number

def list_value(name: str, value, meta: dict) -> tuple | None:
    """A kind "list" parameter: numbers, comma-separated in text; none (None) when empty."""
    if value is None or (isinstance(value, str) and value.strip().lower() in DERIVED_WORDS):
        return None
    items = value.replace(",", " ").split() if isinstance(value, str) else value
    try:
        items = list(items)
    except TypeError:
        items = [items]
    item_meta = {**meta, "kind": meta["item"]}
    out = tuple(meta["item"](coerce(name, v, item_meta)) for v in items)
    return out or None

def rows_value(name: str, value, meta: dict) -> tuple:
    """A list of rows of meta["size"] numbers each (kind "rows"), as a tuple of tuples; one
    row may be given flat."""
    size = meta["size"]
    if isinstance(value, str):
        try:
            value = json.loads(value)
        except ValueError:
            raise ParamError(name, f"is not a JSON list of rows of {size} numbers "
                                   f"(got {value[:40]!r})") from None
    try:
        rows = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParamError(name, f"must be a list of rows of {size} numbers") from None
    if rows.ndim == 1 and rows.size == size:
        rows = rows[None]
    if rows.ndim != 2 or rows.shape[1] != size or not 1 <= len(rows) <= MAX_SHAPE_ROWS:
        raise ParamError(name, f"must be a list of 1 to {MAX_SHAPE_ROWS} rows of {size} numbers "
                               f"(got shape {rows.shape})")
    if not np.isfinite(rows).all() or np.abs(rows).max() > meta["max"]:
        raise ParamError(name, f"every number must be finite, from {meta['min']:g} to "
                               f"{meta['max']:g} {meta['unit']}")
    return tuple(tuple(float(x) for x in row) for row in rows)

def vector_value(name: str, value, meta: dict, size: int) -> tuple:
    what = {3: "three sizes X Y Z", 2: "two coordinates X Y"}.get(size, f"{size} numbers")
    message = (f"must be {what}, each from {meta['min']:g} to {meta['max']:g} {meta['unit']} "
               f"(got {value!r})")
    if isinstance(value, str):
        value = value.replace(",", " ").split()
    try:
        items = list(value)
    except TypeError:
        raise ParamError(name, message) from None
    if len(items) != size:
        raise ParamError(name, message)
    return tuple(float(coerce(name, v, meta)) for v in items)

def describe_range(meta: dict) -> str:
    if "choices" in meta:
        return f"must be one of {', '.join(meta['choices'])}"
    kind, lo, hi, unit = meta["kind"], meta["min"], meta["max"], meta["unit"]
    what = "an integer" if kind is int else "a number"
    suffix = f" {unit}" if unit and unit not in ("×", "fraction") else ""
    if unit == "rad":  # the range in both units, and how to write degrees
        return (f"must be an angle from {lo:.5g} to {hi:.5g} rad ({math.degrees(lo):g}° to "
                f"{math.degrees(hi):g}°): a number in rad, or with a unit: 1.95deg, 1.95°, "
                f"0.034rad")
    also = ", or in % (30%)" if meta.get("shown_in") == "%" else ""
    return f"must be {what} from {lo:g} to {hi:g}{suffix}{also}"

def split_unit(text: str) -> tuple[str, float | None]:
    """'-0.961deg' -> ('-0.961', π/180); '-0.01678rad' -> ('-0.01678', 1.0); '0.5' -> ('0.5',
    None): the number's text and the factor to radians its unit names (None: no unit)."""
    text = text.strip()
    low = text.lower()
    for unit, factor in ANGLE_UNITS.items():
        if low.endswith(unit):
            return text[:len(text) - len(unit)].strip(), factor
    return text, None

def angle_value(name: str, value: Any, meta: dict):
    """An angle as typed: a number (rad), or text with a unit ('1.95deg', '1.95°', '0.034rad')
    -> radians; anything else is returned as it is, for coerce to refuse."""
    if not isinstance(value, str):
        return value
    number, factor = split_unit(value)
    if factor is None:
        return value
    try:
        return float(number) * factor
    except ValueError:
        raise ParamError(name, f"{describe_range(meta)} (got {value!r})") from None
