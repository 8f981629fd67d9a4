"""`--fibril FILE` / `--domain FILE` / `--full-length FILE` and their options, shared by
`inspect`, `run`, `report`, `minimal-linker` and `sweep`: declare them, measure the files (the
structure room does the measuring), and merge the measured values under the explicit options."""
from __future__ import annotations

import argparse

from ..exits import UsageError
from ..model import cases


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
    group.add_argument("--terminus", choices=("N", "C"), default="C",
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


def _listed(value) -> list:
    """An option that argparse appends to, or a case file gives as one value or a list."""
    if value is None:
        return []
    return [value] if isinstance(value, (str, int)) else list(value)


def domain_files(args) -> list:
    return [str(v) for v in _listed(getattr(args, "domain", None))]


def has_structure(args) -> bool:
    return bool(getattr(args, "fibril", None) or domain_files(args)
                or getattr(args, "full_length", None))


def domain_specs(args, fib=None) -> tuple[list, object]:
    """[(file, chain, residues)] of the domains in chain order from the core outward, and the
    full-length model's Segmentation (or None). --full-length gives the folded domains on the
    linker's side of the core."""
    files = domain_files(args)
    chains, ranges = _listed(args.domain_chain), _listed(args.domain_residues)
    full = getattr(args, "full_length", None)
    if full:
        if files:
            raise UsageError("--full-length: gives the domains itself; leave out --domain")
        if chains or ranges:
            raise UsageError("--domain-chain/--domain-residues: not with --full-length")
        from ..structure.full_length import segment
        seg = segment(full, fib.core_residues if fib is not None else None)
        side = "N" if fib is not None and fib.terminus == "N" else "C"
        return [(full, seg.chain, f"{d['first']}-{d['last']}")
                for d in seg.chain_order(side)], seg
    for name, given in (("--domain-chain", chains), ("--domain-residues", ranges)):
        if given and not files:
            raise UsageError(f"{name}: needs --domain")
        if len(given) > 1 and len(given) != len(files):
            raise UsageError(f"{name}: given {len(given)} times for {len(files)} --domain "
                             "files: give it once (for all) or once per --domain")
    pick = (lambda given, i: None if not given else given[i] if len(given) > 1 else given[0])
    return [(f, pick(chains, i), pick(ranges, i)) for i, f in enumerate(files)], None


def measure_all(args) -> tuple:
    """(FibrilGeometry or None, [DomainSize] in chain order, Segmentation or None)."""
    from .. import structure
    if args.anchor_residue is not None and not args.fibril:
        raise UsageError("--anchor-residue: needs --fibril")
    fib = None
    if args.fibril:
        fib = structure.measure_fibril(args.fibril, terminus=args.terminus,
                                       anchor_residue=args.anchor_residue)
    specs, seg = domain_specs(args, fib)
    if seg is not None and not specs and args.command != "inspect":
        from ..structure.full_length import no_domain
        raise UsageError(f"--full-length: {no_domain(seg.file)}")
    option = "--full-length" if seg is not None else "--domain"
    doms = [structure.measure_domain(f, chain=c, residues=r, option=option,
                                       follows=args.terminus == "C",
                                       outgoing=i < len(specs) - 1)
            for i, (f, c, r) in enumerate(specs)]
    return fib, doms, seg


def params_and_structure(args, explicit: dict | None = None) -> tuple[dict, dict | None]:
    """The parameter values of `run`/`sweep`: measured from --fibril/--domain, then the explicit
    options over them. Returns (values, the result's `structure` block or None)."""
    explicit = explicit if explicit is not None else {}
    if not has_structure(args):
        return explicit, None
    from ..structure import from_files
    fib, doms, seg = measure_all(args)
    args.measured = (fib, doms)  # for --pdb-atoms (atom_sources), measured once
    return from_files.merged(fib, doms, seg, explicit)


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
