"""The parameters a model's root collection stores (an ID property), and reading them back: a
model found in a scene, saved in a .blend or undone carries the Params it was built with."""
from __future__ import annotations

import bpy

from ..model import params as P


def stored_params(p: P.Params) -> dict:
    """p.to_dict() as an ID property: derived parameters (None) are left out, and
    make_params gives them back as their defaults."""
    return {k: v for k, v in p.to_dict().items() if v is not None}


# The validated Params each model root was given, by the root's session_uid, with what was
# stored: find_model trusts it while the root still holds those values, so a Params is not
# validated again each time a step looks the model up (5 ms for 6CU7's outline). Anything
# else (a file opened again, values changed by hand or by undo) is validated from the store.
_GIVEN: dict[int, tuple[dict, P.Params]] = {}


def store_params(root: bpy.types.Collection, p: P.Params) -> None:
    """Store p on the model's root (as stored_params) and remember it as given."""
    stored = stored_params(p)
    root["params"] = stored
    _GIVEN[root.session_uid] = (root["params"].to_dict(), p)
    while len(_GIVEN) > 16:  # a sweep worker builds thousands of models: keep the latest few
        del _GIVEN[next(iter(_GIVEN))]


def params_of(root: bpy.types.Collection) -> P.Params:
    """The Params a model root holds: the one it was given if its stored values are unchanged,
    else validated from the stored values."""
    stored = root["params"].to_dict()
    given = _GIVEN.get(root.session_uid)
    if given is not None and given[0] == stored:
        return given[1]
    return P.make_params(force=True, **stored)
