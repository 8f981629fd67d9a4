"""Which code made a result: the FibrilFit version and the model version.

A resumed sweep or minimal-linker walk reuses a record only if both match this code
(batch/outdir.py); records from other code are set aside and their points run again, so results of
an older model never mix silently with new ones (docs/guide/sweeps.md#code-key).

MODEL_VERSION is explicit, bumped by hand when a change alters results. Why not key on a hash of
the source itself: every edit anywhere in the model (a renamed local, a refactor that keeps every
number) would throw away hours of cached runs. Why not the constant alone: it is easy to forget.
So the constant is guarded: MODEL_SOURCES_SHA256 is the hash of the model-defining code
(MODEL_SOURCES, comments, docstrings and layout ignored) as it was when MODEL_VERSION was last
checked, and tests/unit/test_model_version.py fails when the code's hash differs from it. The one
who changes the model then either bumps MODEL_VERSION (results change) or only updates the hash
(they do not), and says which in the commit.
"""
from __future__ import annotations

import ast
import hashlib
import pathlib
import tomllib

MODEL_VERSION = 8  # 2: inflate deterministic and near-miss cycles (#25), domain shapes (#24);
# 3: spheres under the tutorial protocol start spread (#24); 4: a real shape's joint bond is
# measured at its terminal CA (docs/model/domain-shapes.md#joint-stretch); 5: a buried anchor's
# exit spends linker residues (docs/model/buried-terminus.md#model), and `--periodic auto` under
# inflate takes a cell of whole lattice periods with a lattice start (docs/model/periodic-cell.md#auto-cell);
# 6: under inflate a clear miss ends the run at its judgement (docs/model/search.md#clear-miss)
# 7: a bare tail longer than the free linker no longer gets a stray unbonded bead at the
# globule's place (bare_tail 0 and shorter tails unchanged), and bare tails build in a periodic
# cell (docs/model/occupancy.md#bare-tails)
# 8: a buried anchor's exit by the rule: side chains cut to Cβ and OXT removed, to the Cβ
# atoms' outline, the shortest of three layers (docs/model/buried-terminus.md#rule)
# sources_hash() when MODEL_VERSION was last checked (see the module's docstring)
MODEL_SOURCES_SHA256 = "ab7b7d559e12b07e6ccfa83c0227b0f22e8e3c0e2fe982af00037f354ede0892"

PACKAGE = pathlib.Path(__file__).resolve().parents[1]
# What decides a result: parameters and structures read, geometry, the bodies and their physics,
# the judgement, and the run that ties them (not the writers, the batch drivers or the UI)
MODEL_SOURCES = ("model", "geom", "structure", "builders", "analysis", "pipeline.py")


def fibrilfit_version() -> str:
    """The version in the package's blender_manifest.toml."""
    manifest = PACKAGE / "blender_manifest.toml"
    return tomllib.loads(manifest.read_text(encoding="utf-8"))["version"]


def code_key() -> dict:
    """What every result records of the code that made it; a resume matches on it."""
    return {"fibrilfit_version": fibrilfit_version(), "model_version": MODEL_VERSION}


def same_code(record: dict, key: dict | None = None) -> bool:
    """Whether `record` (a results.jsonl line) was made by the code `key` (default: this code)."""
    key = key or code_key()
    return all(record.get(k) == v for k, v in key.items())


def source_files() -> list[pathlib.Path]:
    """The files of MODEL_SOURCES, this one left out (it holds the hash)."""
    files = []
    for name in MODEL_SOURCES:
        path = PACKAGE / name
        files += sorted(path.rglob("*.py")) if path.is_dir() else [path]
    return [f for f in files if f != pathlib.Path(__file__).resolve()]


def _strip_docstrings(tree: ast.AST) -> None:
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]


def _dump(value) -> str:
    """ast.dump without line numbers and without empty fields, so Python 3.11 and 3.13 (whose
    ast.dump differ in showing empty fields, and whose nodes gained empty type_params) agree."""
    if isinstance(value, ast.AST):
        fields = [f"{name}={_dump(v)}" for name, v in ast.iter_fields(value)
                  if v is not None and v != []]
        return f"{type(value).__name__}({','.join(fields)})"
    if isinstance(value, list):
        return "[" + ",".join(_dump(v) for v in value) + "]"
    return repr(value)


def sources_hash() -> str:
    """sha256 of the model-defining code's syntax trees (comments, docstrings and layout do not
    count), file by file in a fixed order."""
    digest = hashlib.sha256()
    for path in source_files():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        _strip_docstrings(tree)
        digest.update(path.relative_to(PACKAGE).as_posix().encode() + b"\0")
        digest.update(_dump(tree).encode() + b"\0")
    return digest.hexdigest()
