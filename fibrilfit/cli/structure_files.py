"""`--fibril FILE` / `--domain FILE` / `--full-length FILE` and their options, shared by
`inspect`, `run`, `report`, `minimal-linker` and `sweep`: declare them; measuring the files and
merging the measured values under the explicit options is structure/from_files.py's (the
sidebar's Load case measures a case's [structure] with the same functions)."""
from __future__ import annotations

import argparse

from ..exits import UsageError
from ..model import cases
from ..structure.from_files import (TERMINUS, domain_specs, has_structure, measure_all,
                                    measure_files)


def add_structure_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("structure files (PDB/mmCIF, optionally .gz)")
    group.add_argument("--fibril", metavar="FILE", help="a fibril structure: fills rise, twist, "
                                                          "protofilaments, core outline, anchor")
    group.add_argument("--domain", metavar="FILE", action="append",
                       help="a domain structure: fills globule_diameter from its Rg; repeat it "
                            "for several domains on one chain, in chain order from the core "
                            "outward")
    group.add_argument("--full-length", metavar="FILE",
                       help="a predicted model of the whole chain in the fibril's numbering "
                            "(pLDDT in the B-factor column): its folded domains and linkers "
                            "(instead of --domain)")
    group.add_argument("--terminus", choices=("N", "C"), default=TERMINUS,
                       help="the core terminus that carries the linker [default C]")
    group.add_argument("--anchor-residue", metavar="R", type=_residue_number,
                       help="anchor on this residue instead of the core's terminus")
    group.add_argument("--domain-chain", metavar="C", action="append",
                       help="the domain's chain [default: first]; once for every --domain, "
                            "or once for all")
    group.add_argument("--domain-residues", metavar="A-B", action="append",
                       help="the domain's residues [default: all]; once for every --domain, "
                            "or once for all")


def _residue_number(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a residue number (got {text!r})") from None


def params_and_structure(args, explicit: dict | None = None) -> tuple[dict, dict | None]:
    """The parameter values of `run`/`sweep`: measured from --fibril/--domain, then the explicit
    options over them. Returns (values, the result's `structure` block or None)."""
    explicit = explicit if explicit is not None else {}
    if not has_structure(args):
        return explicit, None
    from ..structure import from_files
    m = measure_files(args)
    args.measured = (m.fibril, m.domains)  # for --pdb-atoms (atom_sources), measured once
    return from_files.merged(m.fibril, m.domains, m.segmentation, explicit)


def structure_options(args) -> dict:
    """The --fibril/--domain options as they will run (for a case's [structure])."""
    if not has_structure(args):
        return {}
    out = {k: getattr(args, k) for k in cases.STRUCTURE_KEYS if getattr(args, k, None) is not None}
    for k, v in list(out.items()):  # an option given once (argparse appends) is one value
        if isinstance(v, list):
            out[k] = v[0] if len(v) == 1 else v
    if not args.fibril:
        out.pop("terminus", None)
    return out


def atom_sources(args):
    """What --pdb-atoms places (structure.atoms.Sources), from --fibril/--domain/--full-length
    as measured by params_and_structure. Refused without a structure to place."""
    if not has_structure(args):
        raise UsageError("--pdb-atoms: needs a structure to place: give --fibril FILE and/or "
                         "--domain FILE")
    from ..structure import atoms
    fib = (getattr(args, "measured", None) or measure_all(args))[0]
    specs, seg = domain_specs(args, fib)
    option = "--full-length" if seg is not None else "--domain"
    domains = [atoms.domain_atoms(f, chain=c, residues=r, option=option) for f, c, r in specs]
    return atoms.sources(args.fibril, fib, domains) if args.fibril else atoms.sources(
        domains=domains)
