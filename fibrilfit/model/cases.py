"""Case files: a model, its seeds and where its numbers come from, in one TOML file.

    name = "hnRNPDL-2 on 7ZIR"            # metadata (METADATA below), all optional
    doi = "10.1038/s41467-023-35854-0"
    expected = "fits"
    estimates = ["slab", "globule_diameter"]
    seeds = [0, 1, 2]                     # the seeds a sweep (or `make validate`) runs
    [params]                              # any parameter of params.Params, by its name
    linker = 25
    globule_diameter = 36.0

The [params] table's schema is params.Params itself: a parameter added there is a case key too.
Unknown keys and bad values raise CaseError (a ParamError) naming the key, e.g. `params.linker`.
Plain Python (tomllib), importable without bpy.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import pathlib
import tomllib
from typing import Any

from .. import files
from . import params as P
from .param_spec import DERIVED_WORDS

SUFFIXES = (".toml",)
PARAMS = "params"
EXPECTED = ("fits", "does not fit", "unknown")
# Metadata: key -> (type, what it is). Types are checked; the texts document the format.
METADATA = {
    "name": (str, "a short name for the system"),
    "description": (str, "what is modelled"),
    "citation": (str, "the paper the numbers come from"),
    "doi": (str, "its DOI"),
    "pdb": (str, "the PDB entry of the fibril core"),
    "source": (str, "where the numbers were taken from, if not (only) the paper"),
    "observed": (str, "what the literature observed"),
    "expected": (str, f"the verdict the literature implies: {', '.join(EXPECTED)}"),
    "envelope_width": (float, "measured width of the decorated fibril, Å"),
    "envelope_width_source": (str, "where that width was measured"),
    "estimates": (list, "parameters whose values are estimates, not the paper's numbers"),
    "notes": (str, "anything else: how numbers were estimated, caveats"),
    "changed": (str, "what changed against the case's earlier version, and why (the "
                     "validation table says it)"),
}
SEEDS = "seeds"
# What a case says of its own model, stale once an option changes it (dropped from the case as run)
STALE = ("description", "observed", "expected")
STRUCTURE = "structure"
# [structure]: the options of --fibril/--domain (structure/from_files.py); files are relative to
# the case file. Measured values fill the parameters the case and the command line leave unset.
# "domain" (and its chain and residues) may be a list: several domains in chain order (#24).
STRUCTURE_KEYS = {"fibril": "file", "domain": "file", "full_length": "file",
                  "terminus": ("N", "C"), "anchor_residue": int, "domain_chain": str,
                  "domain_residues": str}
LISTED = ("domain", "domain_chain", "domain_residues")
ORDER = ("name", "description", "citation", "doi", "pdb", "source", "observed", "expected",
         "envelope_width", "envelope_width_source", "estimates", "notes", "changed", SEEDS)


class CaseError(P.ParamError):
    """A case file that cannot be used; `param` names the key (`params.linker`, `doi`, ...)."""


@dataclasses.dataclass
class Case:
    """A loaded case: metadata, the seeds, and the [params] given (validated one by one)."""

    meta: dict
    params: dict
    seeds: list | None = None
    path: pathlib.Path | None = None
    sha256: str | None = None
    overridden: list = dataclasses.field(default_factory=list)  # names the command line set
    structure: dict = dataclasses.field(default_factory=dict)  # [structure], files absolute

    def make_params(self, *, force: bool = False, **overrides) -> P.Params:
        """Every parameter: the case's, then `overrides` (the command line's) on top."""
        return P.make_params(force=force, **{**self.params, **overrides})

    def resolved(self, p: P.Params, overridden=(), structure: dict | None = None,
                 changed=()) -> dict:
        """The case as run with `p` (and `structure`, the structure options as run, if not the
        case's own): JSON-ready, embedded in every result (`case`). `changed`: what the command
        line set beside the case (overridden or added), which makes its own words stale."""
        out = {k: self.meta[k] for k in ORDER if k in self.meta}
        changed = sorted(set(changed) | set(overridden))
        if changed and any(k in out for k in STALE):  # its words describe its own model
            out = {k: v for k, v in out.items() if k not in STALE}
            out["description"] = (f"{self.meta.get('name') or self.path or 'a case'}, with "
                                  f"{', '.join(changed)} set on the command line")
        if self.seeds is not None:
            out[SEEDS] = list(self.seeds)
        out[PARAMS] = p.to_dict()
        structure = self.structure if structure is None else structure
        if structure:
            out[STRUCTURE] = {k: structure[k] for k in STRUCTURE_KEYS if k in structure}
        files = {name: file_record(name, v, self.path) for name, v in self.params.items()
                 if _names_file(name, v)}
        for k, v in (structure or {}).items():
            if STRUCTURE_KEYS[k] == "file":
                for n, one in enumerate(v if isinstance(v, list) else [v]):
                    files[k if n == 0 else f"{k}.{n + 1}"] = file_record(k, one, self.path)
        if files:
            out["files"] = files  # the files the case named, relative to it, with sha256
        if self.path is not None:
            out["file"] = str(self.path)
            out["sha256"] = self.sha256
        out["overridden"] = sorted(overridden)
        return out


def _names_file(name: str, value) -> bool:
    f = P.Params.__dataclass_fields__.get(name)
    return (f is not None and f.metadata["kind"] == "points" and isinstance(value, str)
            and pathlib.Path(value).is_absolute())


def _where(path) -> str:
    return f"{path}: " if path else ""


def _error(path, key: str, message: str) -> CaseError:
    err = CaseError(key, message)
    err.args = (f"{_where(path)}{key}: {message}",)
    return err


def _check_meta(path, key: str, value: Any):
    kind, what = METADATA[key]
    if kind is float:
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        if not ok or not math.isfinite(value) or value <= 0:
            raise _error(path, key, f"must be a positive number ({what}) (got {value!r})")
        return float(value)
    if kind is list:
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise _error(path, key, f"must be a list of names ({what}) (got {value!r})")
        known = {f.name for f in P.fields()}
        for name in value:
            if name not in known:
                raise _error(path, key, f"{name!r} is not a parameter; known: "
                                        f"{', '.join(sorted(known))}")
        return list(value)
    if not isinstance(value, str):
        raise _error(path, key, f"must be a string ({what}) (got {value!r})")
    if key == "expected" and value not in EXPECTED:
        raise _error(path, key, f"must be one of {', '.join(EXPECTED)} (got {value!r})")
    return value


def _check_seeds(path, value) -> list[int]:
    hi = P.field_spec("seed")["max"]
    if (not isinstance(value, list) or not value
            or not all(isinstance(s, int) and not isinstance(s, bool) and 0 <= s <= hi
                       for s in value)):
        raise _error(path, SEEDS, f"must be a non-empty list of integers from 0 to {hi} "
                                  f"(got {value!r})")
    return list(dict.fromkeys(value))


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _file(path, key: str, value: str) -> str:
    """A file named in a case: relative to the case file's folder; it must exist."""
    where = pathlib.Path(path).resolve().parent if path else pathlib.Path.cwd()
    target = (where / pathlib.Path(value).expanduser()).resolve()
    if not target.is_file():
        raise _error(path, key, f"no file '{value}' (looked for {target})")
    return str(target)


def file_record(name: str, target, case_path=None) -> dict:
    """{path relative to the case file (absolute without one), sha256} of a file a case uses."""
    target = pathlib.Path(target)
    rel = str(target)
    if case_path is not None:
        rel = os.path.relpath(target, pathlib.Path(case_path).resolve().parent)
    return {"path": rel, "sha256": hashlib.sha256(target.read_bytes()).hexdigest()}


def _is_array(f) -> bool:
    meta = f.metadata
    return isinstance(f.default, tuple) or bool(meta.get("size")) or meta["kind"] == "points"


def _check_param(path, name: str, value):
    """One [params] value: its TOML type must fit the parameter (params validates the rest).
    A parameter whose default is derived from others may also say so in words ("auto")."""
    f = P.Params.__dataclass_fields__[name]
    meta, key = f.metadata, f"{PARAMS}.{name}"
    if meta["kind"] == "points" and isinstance(value, str) and not (
            value.strip().lower() in DERIVED_WORDS or value.strip().startswith("[")):
        return _file(path, key, value)  # a file of points, relative to the case file
    if meta.get("derived") and isinstance(value, str):
        return value
    if P.is_angle(name) and isinstance(value, str):
        return value  # an angle with its unit, "-0.961deg" (param_values.angle_value reads it)
    if meta.get("shown_in") == "%" and isinstance(value, str) and value.strip().endswith("%"):
        return value  # a fraction in per cent, "25%" (param_values.coerce reads it)
    if meta["kind"] is bool:
        if not isinstance(value, bool):
            raise _error(path, key, f"must be true or false (got {value!r})")
    elif _is_array(f):
        if not isinstance(value, list):
            example = list(f.default) if isinstance(f.default, tuple) else "[...]"
            raise _error(path, key, f"must be an array like {example} (got {value!r})")
    elif meta["kind"] in (int, float):
        special = P.NUMBER_WORDS.get(name) == value  # "all", "auto"
        if not _is_number(value) and not special:
            raise _error(path, key, f"must be a number, not {type(value).__name__} "
                                    f"(got {value!r})")
    return value


def from_dict(data: dict, path=None, sha256: str | None = None) -> Case:
    """Validate a parsed case (a dict as tomllib gives it); raise CaseError naming the key."""
    known = set(METADATA) | {SEEDS, PARAMS, STRUCTURE}
    meta, params, seeds, structure = {}, {}, None, {}
    for key, value in data.items():
        if key not in known:
            raise _error(path, key, f"unknown key; known: {', '.join(sorted(known))}")
        if key == PARAMS:
            if not isinstance(value, dict):
                raise _error(path, key, "must be a table: [params]")
            names = [f.name for f in P.fields()]
            for name, v in value.items():
                if name not in names:
                    raise _error(path, f"{PARAMS}.{name}",
                                 f"unknown parameter; known: {', '.join(sorted(names))}")
                params[name] = _check_param(path, name, v)
        elif key == SEEDS:
            seeds = _check_seeds(path, value)
        elif key == STRUCTURE:
            structure = _check_structure(path, value)
        else:
            meta[key] = _check_meta(path, key, value)
    try:  # the case's own values together; the object limit waits for the run's --force
        P.make_params(force=True, **params)
    except P.ParamError as exc:
        raise _error(path, f"{PARAMS}.{exc.param}", str(exc).split(": ", 1)[1]) from None
    return Case(meta, params, seeds, pathlib.Path(path) if path else None, sha256,
                structure=structure)


def _check_structure(path, table) -> dict:
    if not isinstance(table, dict):
        raise _error(path, STRUCTURE, "must be a table: [structure]")
    out = {}
    for key, value in table.items():
        name = f"{STRUCTURE}.{key}"
        kind = STRUCTURE_KEYS.get(key)
        if kind is None:
            raise _error(path, name, f"unknown key; known: {', '.join(STRUCTURE_KEYS)}")
        if key in LISTED and isinstance(value, list) and value:
            out[key] = [_check_structure(path, {key: v})[key] for v in value]
            continue
        if kind == "file":
            if not isinstance(value, str):
                raise _error(path, name, f"must be a file name (got {value!r})")
            out[key] = _file(path, name, value)
        elif isinstance(kind, tuple):
            if value not in kind:
                raise _error(path, name, f"must be one of {', '.join(kind)} (got {value!r})")
            out[key] = value
        elif kind is int:
            if not isinstance(value, int) or isinstance(value, bool):
                raise _error(path, name, f"must be a residue number (got {value!r})")
            out[key] = value
        else:
            if not isinstance(value, str):
                raise _error(path, name, f"must be a string (got {value!r})")
            out[key] = value
    return out


def load(path) -> Case:
    """Read and validate a case file."""
    path = pathlib.Path(path).expanduser()
    if path.suffix.lower() not in SUFFIXES:
        raise CaseError("--case", f"must be a .toml file (got '{path}')")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise CaseError("--case", f"cannot read '{path}': {exc.strerror or exc}") from None
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise CaseError("--case", f"'{path}' is not valid TOML: {exc}") from None
    return from_dict(data, path, hashlib.sha256(raw).hexdigest())


# ---- writing ------------------------------------------------------------------------------
# A tiny writer, not tomli_w: what a case holds is flat (strings, numbers, booleans, arrays of
# them, one [params] table), the extension would otherwise have to bundle a wheel for the panel's
# Save case, and every text written is parsed back with tomllib and compared before it is kept.

def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"cannot write {v!r} to a case")
        return repr(v)
    if isinstance(v, str):
        # JSON's escapes are TOML's, but not its surrogate pairs: keep non-ASCII as it is, and
        # escape DEL, which JSON leaves raw and TOML forbids
        return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to a case")


def dumps(case: dict, where=None) -> str:
    """A case dict (as Case.resolved gives it) as TOML text, metadata first, then [params] and
    [structure], whose files are written relative to the folder `where` (the file's)."""
    lines = ["# FibrilFit case: headless.py run --case THIS.toml (see docs/guide/cases.md#case-files)"]
    for key in ORDER:
        if key in case:
            lines.append(f"{key} = {_value(case[key])}")
    lines += ["", f"[{PARAMS}]"]
    # None: a parameter derived from others (TOML has no null); leaving it out means the same
    params = {k: v for k, v in case.get(PARAMS, {}).items() if v is not None}
    for f in P.fields():
        if f.name in params:
            lines.append(f"{f.name} = {_value(params[f.name])}")
    structure = dict(case.get(STRUCTURE) or {})
    for key, kind in STRUCTURE_KEYS.items():
        if kind == "file" and key in structure:
            rel = (lambda t: os.path.relpath(pathlib.Path(t).resolve(), pathlib.Path(
                where).resolve()) if where is not None else str(t))
            value = structure[key]
            structure[key] = [rel(v) for v in value] if isinstance(value, list) else rel(value)
    if structure:
        lines += ["", f"[{STRUCTURE}]"]
        lines += [f"{k} = {_value(structure[k])}" for k in STRUCTURE_KEYS if k in structure]
    text = "\n".join(lines) + "\n"
    back = tomllib.loads(text)
    want = {k: case[k] for k in ORDER if k in case} | {PARAMS: params}
    if structure:
        want[STRUCTURE] = structure
    if json.dumps(back, sort_keys=True) != json.dumps(_plain(want), sort_keys=True):
        raise ValueError("the case did not read back as written")  # a bug, never expected
    return text


def write(path, case: dict) -> pathlib.Path:
    """Write `case` (Case.resolved) as a case file, whole or not at all."""
    path = pathlib.Path(path).expanduser()
    return files.write_text(path, dumps(case, path.parent))


def _plain(x):
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return x


def metadata_of(resolved: dict) -> dict:
    """The metadata and seeds of a resolved case (what the panel keeps beside its values)."""
    return {k: resolved[k] for k in ORDER if k in resolved}
