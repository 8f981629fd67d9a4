"""The panel's words for what the code and the command line name otherwise (issue #45 item 7):
a message shown in the sidebar (an operator's error or note, a line of the panel) names a value
by its field's label ("Core outline", "Protofilament rise"), not by its parameter name
(core_outline, pf_rise) or its command-line option (--fibril, --domain-chain). Plain Python:
tests/unit/test_panel_words.py reads it without bpy.

The labels are the ones the panel's fields carry: params' `label` (model/param_spec.py spec
label=), else the name in words; a plan option's `label` (plans.py option(label=)); the structure
options are the files and fields of the import dialogs."""
from __future__ import annotations

import dataclasses
import re

from ..model import params as P
from ..search.plans import SearchPlan
from ..structure.request import StructureRequest

# The structure options as the panel offers them (Import fibril… and Import domain…'s fields)
FILE_WORDS = {"--fibril": "Fibril file", "--domain": "Domain file",
              "--full-length": "Full-length model", "--domain-chain": "Domain chain",
              "--domain-residues": "Domain residues", "--anchor-residue": "Anchor residue",
              "--terminus": "Terminus", "--case": "Case file"}
_PARAMS = {f.name: f for f in P.fields()}
_PLAN_LABELS = {f.name: f.metadata["label"] for plan in (SearchPlan, StructureRequest)
                for f in dataclasses.fields(plan) if f.metadata.get("label")}
# an option (--name-like) or an internal name with an underscore (core_outline, pf_rise)
# (not inside a path or a file's name: /data/core_outline.json stays as it is)
_NAMES = re.compile(r"(?<![\w/.-])(?:--[a-z][a-z0-9-]*|[a-z][a-z0-9]*(?:_[a-z0-9]+)+)"
                    r"(?![\w/-]|\.\w)")


def field_label(name: str) -> str:
    """The panel's name of a model parameter or a plan option, without its unit."""
    if name in _PARAMS:
        return _PARAMS[name].metadata.get("label") or name.replace("_", " ").capitalize()
    return _PLAN_LABELS.get(name) or name.replace("_", " ").capitalize()


def known(name: str) -> bool:
    return name in _PARAMS or name in _PLAN_LABELS


def labels(names) -> str:
    """Names as the panel's labels, comma-separated."""
    return ", ".join(field_label(n) for n in names)


def _said(match) -> str:
    word = match.group(0)
    if word.startswith("--"):
        if word in FILE_WORDS:
            return FILE_WORDS[word]
        name = word[2:].replace("-", "_")
        return field_label(name) if known(name) else word
    return field_label(word) if known(word) else word


def in_panel_words(text: str, name: str | None = None) -> str:
    """`text` with its options and internal names as the panel says them; `name` (an error's
    parameter or field: ParamError.param, PlanError.field) said by its label where the text
    starts with it ("linker: must be ..." -> "Linker: must be ...")."""
    if name and known(name) and text.startswith(f"{name}:"):
        text = field_label(name) + text[len(name):]
    return _NAMES.sub(_said, text)


def error_words(exc: BaseException) -> str:
    """An expected error's one line in the panel's words (ParamError names .param, PlanError
    .field, StructureError .option)."""
    name = getattr(exc, "param", None) or getattr(exc, "field", None)
    return in_panel_words(str(exc), name)
