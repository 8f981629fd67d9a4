"""The model a command runs: its values as given, the structure files measured under them, the
checked Params, and where each value came from (the result's `sources`)."""
from __future__ import annotations

import dataclasses

from ..exits import UsageError
from ..model import params as P
from ..model.param_checks import refuse_beside_periodic
from ..structure import from_files, termini


@dataclasses.dataclass
class ResolvedModel:
    """`p` (checked), `values` (as given and measured; strings allowed), the result's
    `structure` block (None without files) and the files' measurements (from_files.Measured,
    or None)."""

    p: P.Params
    values: dict
    block: dict | None
    measured: object


def measured_values(structure, explicit: dict) -> tuple[dict, dict | None, object]:
    """The values measured from the request's files with `explicit` over them, the structure
    block and the measurements; `explicit` alone when no file is named."""
    if not structure.any:
        return dict(explicit), None, None
    m = from_files.measure_files(structure)
    values, block = from_files.merged(m.fibril, m.domains, m.segmentation, explicit)
    return values, block, m


def resolve(plan, defaults: dict | None = None) -> ResolvedModel:
    """The plan's model checked: its values, the files measured under them, a command's own
    `defaults` under both (the report's protocol), made into Params under plan.force."""
    given = plan.given()
    refuse_beside_periodic(given)
    values, block, measured = measured_values(plan.structure, given)
    values = {**(defaults or {}), **values}
    values, block = termini.as_they_are(values, measured, given, block)
    p = termini.make_params(values, measured, given, force=plan.force)
    return ResolvedModel(p, values, block, measured)


def param_sources(given, p: P.Params, structure_block=None, *, case=None, restarts=None,
                  command: str | None = None, defaults=()) -> dict:
    """Parameter name -> where its value came from: "option" (given), "case", the file it was
    measured from with what in it ("2n0a.pdb.gz: modelled tail 98-140"), "default", or
    "<command> default" for a command's own default (`defaults`: their names)."""
    from_case = set(case.params) - set(case.overridden) if case is not None else set()
    given = set(given)
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
        elif name in defaults and command:
            where = f"{command} default"
        else:
            where = "default"
        out[name] = where
    if p.periodic:
        out["layers"] = f"{out['periodic']} (the periodic cell's layers)"
    if restarts is not None:
        out["seed"] = f"the best of --restarts {restarts} from seed {out['seed']}"
    return out


def atom_sources(structure, measured):
    """What --pdb-atoms places (structure.atoms.Sources), from the request's files as measured
    (`measured`: from_files.Measured, or None to measure them). Refused without a structure."""
    if not structure.any:
        raise UsageError("--pdb-atoms: needs a structure to place: give --fibril FILE and/or "
                         "--domain FILE")
    from ..structure import atoms
    fib = (measured.fibril if measured is not None else from_files.measure_all(structure)[0])
    specs, seg = from_files.domain_specs(structure, fib)
    option = "--full-length" if seg is not None else "--domain"
    domains = [atoms.domain_atoms(f, chain=c, residues=r, option=option) for f, c, r in specs]
    return (atoms.sources(structure.fibril, fib, domains) if structure.fibril
            else atoms.sources(domains=domains))
