"""Which values a command runs with, and where each came from: the options given, a case file
under them (--case), the structure files measured (structure_files.py), a command's own defaults.
"""
from __future__ import annotations

import dataclasses

from ..model import cases, params as P
from .parser import option
from .structure_files import params_and_structure


def _given(argv, name: str) -> bool:
    flag = option(name)
    return any(a == flag or a.startswith(flag + "=") for a in argv)


SEARCHED = {"minimal-linker": ("linker",)}  # what a command finds, so a case cannot set it


def apply_case(args, argv=()):
    """Load args.case and fill every option the command line left unset from it (model
    parameters, the [structure] options; for a sweep also its seeds). Returns the Case, or None
    without --case."""
    if not getattr(args, "case", None):
        return None
    case = cases.load(args.case)
    for key, value in case.structure.items():
        if not hasattr(args, key):
            raise cases.CaseError(f"{cases.STRUCTURE}.{key}",
                                  f"`{args.command}` takes no structure files")
        if _given(argv, key):
            case.overridden.append(key)
        else:
            setattr(args, key, value)
    sweep = hasattr(args, "seed_list")  # a command that runs a list of seeds
    seeds_given = sweep and any(getattr(args, o, None) is not None
                                for o in ("seeds", "seed_list", "seed"))
    overridden = []
    searched = SEARCHED.get(args.command, ())
    for name, value in case.params.items():
        if name in searched:  # the command's answer, e.g. minimal-linker's linker
            continue
        if getattr(args, name, None) is not None:
            overridden.append(name)
        elif not (name == "seed" and sweep and (seeds_given or case.seeds is not None)):
            setattr(args, name, value)
    if sweep and case.seeds is not None and not seeds_given:
        args.seed_list = ",".join(str(s) for s in case.seeds)
    case.overridden = sorted(case.overridden + overridden)
    return case


def params_from(args) -> dict:
    """The parameters given on the command line; an outline FILE is read into its points."""
    out = {f.name: getattr(args, f.name) for f in dataclasses.fields(P.Params)
           if getattr(args, f.name, None) is not None}
    if isinstance(out.get("core_outline"), str):  # a case file may give the points inline
        text = out["core_outline"]
        out["core_outline"] = (None if text.strip().lower() in P.DERIVED_WORDS
                               else P.read_outline(text))
    return out


def checked_params(args, defaults: dict | None = None) -> tuple:
    """(Params, values, structure block) of `run` and `report`: the options and the measured
    structures merged and validated (`defaults`: a command's own defaults under them)."""
    given = params_from(args)
    P.refuse_beside_periodic(given)
    values, structure_block = params_and_structure(args, given)
    values = {**(defaults or {}), **values}
    return P.make_params(force=args.force, **values), values, structure_block


def sources_of(args, p, structure_block: dict | None, defaults: dict) -> dict:
    """`param_sources`, with a command's own defaults named as such ('report default')."""
    out = param_sources(args, p, structure_block)
    for name in defaults:
        if out.get(name, "").startswith("default"):
            out[name] = f"{args.command} default"
    return out


def param_sources(args, p, structure_block=None, restarts=None) -> dict:
    """Parameter name -> where its value came from: "default", "option", "case", or the file
    it was measured from with what in it ("2n0a.pdb.gz: modelled tail 98-140")."""
    case = getattr(args, "loaded_case", None)
    from_case = set(case.params) - set(case.overridden) if case is not None else set()
    given = set(params_from(args))
    measured = (structure_block or {}).get("sources", {})
    applied = (structure_block or {}).get("applied", {})
    out = {}
    for f in P.fields():
        name = f.name
        if name in given:
            where = "case" if name in from_case else "option"
        elif name in applied:
            block = structure_block or {}
            files_ = [m["file"] for m in (block.get("fibril"), block.get("domain")) if m]
            where = measured.get(name, f"{files_[0] if files_ else 'a file'} (measured)")
        elif f.metadata["derived"] and getattr(p, name) is None:
            where = f"default: {f.metadata['derived']}"
        else:
            where = "default"
        out[name] = where
    if p.periodic:
        out["layers"] = f"{out['periodic']} (the periodic cell's layers)"
    if restarts is not None:
        out["seed"] = f"the best of --restarts {args.restarts} from seed {out['seed']}"
    return out
