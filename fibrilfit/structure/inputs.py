"""`--fibril FILE` / `--domain FILE` and their options, shared by `inspect`, `run` and `sweep`:
measure the files, and merge the measured values under the explicit options."""
from __future__ import annotations

import argparse
import sys

from ..model import params as P
from ..exits import UsageError


def add_structure_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("structure files (PDB/mmCIF, optionally .gz)")
    group.add_argument("--fibril", metavar="FILE", help="a fibril structure: fills rise, twist, "
                                                          "protofilaments, core outline, anchor")
    group.add_argument("--domain", metavar="FILE", help="a domain structure: fills "
                                                          "globule_diameter from its Rg")
    group.add_argument("--terminus", choices=("N", "C"), default="C",
                       help="the core terminus that carries the linker [default C]")
    group.add_argument("--anchor-residue", metavar="R", type=_residue_number,
                       help="anchor on this residue instead of the core's terminus")
    group.add_argument("--domain-chain", metavar="C", help="the domain's chain [default: first]")
    group.add_argument("--domain-residues", metavar="A-B",
                       help="the domain's residues [default: all]")


def _residue_number(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a residue number (got {text!r})") from None


def measure_structures(args):
    """(FibrilGeometry or None, DomainSize or None) from --fibril / --domain."""
    from .. import structure
    if args.anchor_residue is not None and not args.fibril:
        raise UsageError("--anchor-residue: needs --fibril")
    if (args.domain_chain or args.domain_residues) and not args.domain:
        raise UsageError("--domain-chain/--domain-residues: need --domain")
    fib = dom = None
    if args.fibril:
        fib = structure.measure_fibril(args.fibril, terminus=args.terminus,
                                       anchor_residue=args.anchor_residue)
    if args.domain:
        dom = structure.measure_domain(args.domain, chain=args.domain_chain,
                                       residues=args.domain_residues,
                                       follows=args.terminus == "C")
    return fib, dom


def params_and_structure(args, explicit: dict | None = None) -> tuple[dict, dict | None]:
    """The parameter values of `run`/`sweep`: measured from --fibril/--domain, then the explicit
    options over them. Returns (values, the result's `structure` block or None)."""
    explicit = explicit if explicit is not None else {}
    if not (args.fibril or args.domain):
        return explicit, None
    from . import from_files
    fib, dom = measure_structures(args)
    radius = explicit.get("residue_radius", P.DEFAULTS.residue_radius)
    try:
        radius = float(radius)
    except (TypeError, ValueError):
        radius = P.DEFAULTS.residue_radius  # make_params names the bad value below
    shape = str(explicit.get("domain_shape", P.DEFAULTS.domain_shape)).strip().lower()
    applied, block = from_files.split(fib, dom, explicit=set(explicit),
                                      known={f.name for f in P.fields()}, residue_radius=radius,
                                      shape=shape)
    if block["not_in_model"]:
        print(f"fibrilfit: warning: measured but not in this model: "
              f"{', '.join(block['not_in_model'])}", file=sys.stderr)
    return {**applied, **explicit}, block
