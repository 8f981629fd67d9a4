"""`--pdb-atoms FILE.cif`: the decorated fibril in atoms, as mmCIF written through gemmi.

Per model chain c (layer c // K, protofilament c % K) one mmCIF chain holds the core's chain as
deposited, turned and raised onto the model's chain pose (helix.chain_transforms), followed by
the linker's beads as CA-only residues (residue UNK, numbered on from the anchor in the protein's
numbering; B-factor = bead radius); each domain of the chain is a chain of its own, its atoms
placed by its globule's world matrix after the bake (the body frame of
structure.domain.body_frame). Chain names: layer number, protofilament letter, and for a
domain its number in chain order ("0A", "0A1", "1B", "1B1", ...). The model's parameters, seed
and verdict are in the header (_struct.title, _struct.pdbx_model_details, and a
_fibrilfit_param loop). docs/guide/atoms-and-domains.md#pdb-atoms

With --pdb-assembly N (a periodic cell only) the atoms are the cell, which is exact as an
asymmetric unit (the infinite fibril is the cell repeated by the screw S), and assembly 1 of
_pdbx_struct_assembly / _pdbx_struct_assembly_gen / _pdbx_struct_oper_list expands it to the
cell and its images in N cells below and above: one operator S^m per copy, a flat list (viewers
that read only one factor of an operator product would drop copies).
docs/guide/atoms-and-domains.md#helical-assembly

Plain numpy and gemmi, no bpy: exports.writers reads the matrices and calls `write`.
"""
from __future__ import annotations

import string

import numpy as np

from .. import files
from ..model import helix, occupancy
from ..model.chain import chain_radii
from ..model.hetero import b_chains, globule_radii_by_chain
from .plans import NOT_SCREW_SYMMETRIC

ATOM_COLUMNS = ("group_PDB", "id", "type_symbol", "label_atom_id", "label_alt_id",
                "label_comp_id", "label_asym_id", "label_entity_id", "label_seq_id",
                "pdbx_PDB_ins_code", "Cartn_x", "Cartn_y", "Cartn_z", "occupancy",
                "B_iso_or_equiv", "auth_seq_id", "auth_comp_id", "auth_asym_id", "auth_atom_id",
                "pdbx_PDB_model_num")
PF_LETTERS = string.ascii_uppercase
SUFFIXES = (".cif", ".mmcif")
ASSEMBLY_ID = "1"
OPER_TAGS = ("id", "type", "name", "symmetry_operation", *(  # row i: matrix[i][1..3], vector[i]
    tag for i in (1, 2, 3) for tag in (*(f"matrix[{i}][{j}]" for j in (1, 2, 3)), f"vector[{i}]")))
BEAD_NAME = "UNK"  # a linker bead: a residue of unknown type, its CA only
GLOBULE_NAME = "GLB"  # a domain without a structure file: one pseudo-atom at the centre


class AtomsError(ValueError):
    """The decorated fibril cannot be written (e.g. nothing to place)."""


def rigid_part(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(R, t) of a 4 × 4 world matrix, R the nearest rotation (a globule grown by inflate has
    scale 1 when judged; float32 storage leaves ~1e-7 of shear, removed here)."""
    m = np.asarray(matrix, float)
    u, _, vt = np.linalg.svd(m[:3, :3])
    r = u @ vt
    if np.linalg.det(r) < 0:
        u[:, -1] *= -1
        r = u @ vt
    return r, m[:3, 3]


def chain_name(layer: int, pf: int, domain: int | None = None) -> str:
    name = f"{layer}{PF_LETTERS[pf % 26]}"
    return name if domain is None else f"{name}{domain + 1}"


class _Table:
    """Columns gathered piece by piece, joined once."""

    def __init__(self):
        self.parts = {k: [] for k in ("xyz", "name", "element", "resname", "resnum", "b",
                                      "chain", "entity", "hetero")}

    def add(self, xyz, name, element, resname, resnum, b, chain: str, entity: int,
            hetero: bool = False):
        n = len(xyz)
        if not n:
            return
        full = (lambda v: np.full(n, v, dtype=object) if np.ndim(v) == 0 else
                np.asarray(v, dtype=object))
        P = self.parts
        P["xyz"].append(np.asarray(xyz, float).reshape(n, 3))
        P["name"].append(full(name))
        P["element"].append(full(element))
        P["resname"].append(full(resname))
        P["resnum"].append(np.broadcast_to(np.asarray(resnum, np.int64), (n,)))
        P["b"].append(np.broadcast_to(np.asarray(b, float), (n,)))
        P["chain"].append(full(chain))
        P["entity"].append(np.full(n, entity, dtype=np.int64))
        P["hetero"].append(np.full(n, hetero))

    def joined(self) -> dict:
        return {k: np.concatenate(v) for k, v in self.parts.items()}


def decorated_atoms(p, positions: np.ndarray, domain_matrices: np.ndarray, sources,
                    domain_members=None) -> dict:
    """Every atom of the decorated fibril as arrays (xyz, name, element, resname, resnum, b,
    chain, entity). `positions`: chain members' world centres (chains, members, 3);
    `domain_matrices`: (chains, domains, 4, 4) world matrices of each chain's globules;
    `domain_members`: the member index of each globule along the chain (default: the last)."""
    positions = np.asarray(positions, float)
    mats = np.asarray(domain_matrices, float)
    chains, members = positions.shape[:2]
    if mats.ndim == 3:
        mats = mats[:, None]
    n_dom = mats.shape[1]
    domain_members = list(domain_members) if domain_members is not None else [members - 1]
    if len(domain_members) != n_dom:
        raise AtomsError(f"{n_dom} globules per chain but {len(domain_members)} domain places")
    angle, height = helix.chain_transforms(p)
    ids = occupancy.decorated_chains(p)  # the chains' subunits (a mixed fibril: decorated ones)
    layer, pf = (a[ids] for a in helix.chain_layers(p))
    angle, height = angle[ids], height[ids]
    radii = np.asarray(_member_radii(p, members))
    # a hetero-amyloid's chains: each its own sphere, A's or B's (B has no structure file)
    second = (b_chains(p) if occupancy.is_hetero(p) and chains == len(ids)
              else np.zeros(chains, dtype=bool))
    sphere_radius = globule_radii_by_chain(p) if second.any() else None
    table = _Table()
    core = sources.core
    entity_of_domain = [2 + d for d in range(n_dom)]
    for c in range(chains):
        cname = chain_name(int(layer[c]), int(pf[c]))
        if core:
            atoms = core[int(pf[c]) % len(core)]
            ca, sa = np.cos(angle[c]), np.sin(angle[c])
            x, y, z = atoms.xyz.T
            xyz = np.stack([ca * x - sa * y, sa * x + ca * y, z + height[c]], axis=1)
            table.add(xyz, atoms.name, atoms.element, atoms.resname, atoms.resnum, atoms.b,
                      cname, 1)
        else:  # no fibril file: the anchor bead stands for the anchor residue
            table.add(positions[c, :1], "CA", "C", BEAD_NAME, 1, radii[0], cname, 1)
        start, number = 1, None  # number: the residue the next beads continue from
        step = -1 if sources.side == "N" else 1
        for d, member in enumerate(domain_members):
            beads = np.arange(start, member)
            numbers = (sources.linker_numbers(len(beads), p.exit_spent) if number is None else
                       number + step * np.arange(1, len(beads) + 1))
            # the beads before domain 0 join the core's chain; later ones the previous domain's
            owner = (cname, 1) if d == 0 else (chain_name(int(layer[c]), int(pf[c]), d - 1),
                                               entity_of_domain[d - 1])
            table.add(positions[c, beads], "CA", "C", BEAD_NAME, numbers, radii[beads], *owner)
            dname = chain_name(int(layer[c]), int(pf[c]), d)
            if d < len(sources.domains) and not second[c]:
                atoms = sources.domains[d]
                r, t = rigid_part(mats[c, d])
                table.add(atoms.xyz @ r.T + t, atoms.name, atoms.element, atoms.resname,
                          atoms.resnum, atoms.b, dname, entity_of_domain[d])
                number = int(atoms.resnum.max() if step > 0 else atoms.resnum.min())
            else:  # a sphere without a structure file: its centre, B-factor = its radius
                table.add(mats[c, d, :3, 3][None], "CA", "C", GLOBULE_NAME, 1,
                          radii[member] if sphere_radius is None else sphere_radius[c],
                          dname, entity_of_domain[d], hetero=True)
                number = None
            start = member + 1
    if core:  # a mixed fibril's undecorated subunits: their core chains alone
        a, h = helix.chain_transforms(p)
        for c in np.setdiff1d(np.arange(p.chains), ids).tolist():
            k, j = c // p.protofilaments, c % p.protofilaments
            atoms = core[j % len(core)]
            ca, sa = np.cos(a[c]), np.sin(a[c])
            x, y, z = atoms.xyz.T
            xyz = np.stack([ca * x - sa * y, sa * x + ca * y, z + h[c]], axis=1)
            table.add(xyz, atoms.name, atoms.element, atoms.resname, atoms.resnum, atoms.b,
                      chain_name(k, j), 1)
    return table.joined()


def helical_assembly(p, cells: int) -> dict:
    """The periodic cell's helical assembly: the cell (m = 0, the identity) and its images in
    `cells` cells below and above (helix.image_cells order), one 4 × 4 matrix S^m each
    (helix.screw_matrix): a flat list, never a product."""
    if not p.periodic:
        raise AtomsError(f"a helical assembly needs a periodic cell (--periodic): "
                         f"{NOT_SCREW_SYMMETRIC}")
    turn, rise = helix.screw_turn(p, 1)
    ms = [0, *helix.image_cells(cells)]
    return {"cells": int(cells), "cell_layers": int(p.periodic), "m": ms,
            "matrices": [helix.screw_matrix(p, m) for m in ms],
            "screw_turn_deg": float(np.degrees(turn)), "screw_rise": float(rise)}


def assembly_text(assembly: dict) -> str:
    """What the assembly is, for _struct.pdbx_model_details."""
    n = assembly["cells"]
    return (f"the atoms are the periodic cell of {assembly['cell_layers']} layers (the "
            f"asymmetric unit: the infinite fibril is the cell repeated by the screw S, turn "
            f"{assembly['screw_turn_deg']:.6g} deg about Z and rise "
            f"{assembly['screw_rise']:.6g} A); assembly {ASSEMBLY_ID} is the cell and its images "
            f"S^m, m = -{n} .. {n} ({2 * n + 1} cells), one operator per cell, a flat list")


def header(result: dict | None) -> dict:
    """Title, details and parameters of the header from the run's result."""
    result = result or {}
    par = result.get("params", {})
    verdict = result.get("verdict")
    title = (f"FibrilFit decorated fibril: {par.get('layers', '?')} layers x "
             f"{par.get('protofilaments', 1)} protofilaments, linker {par.get('linker', '?')}"
             + (f", verdict {verdict}" if verdict else ""))
    files_used = []
    for key, block in (result.get("structure") or {}).items():
        if isinstance(block, dict) and "file" in block:
            files_used.append(f"{key} {block['file']} (sha256 {block['sha256']})")
    details = "; ".join([
        f"FibrilFit {result.get('fibrilfit_version', '?')} on Blender "
        f"{result.get('blender_version', '?')}", f"seed {result.get('seed')}",
        *files_used,
        "one chain per layer and protofilament (core as deposited, then the linker's beads as "
        "CA-only UNK residues, B-factor = bead radius), one chain per domain placed by its "
        "globule's rigid-body transform"])
    if verdict:
        details += (f"; verdict {verdict}, accommodated {result.get('accommodated')}, "
                    f"max_bond_stretch {result.get('max_bond_stretch')}")
    params = {k: shown(v) for k, v in par.items() if v is not None}
    block = result.get("structure") or {}
    named = [d["file"] for d in block.get("domains", [])] or (
        [block["domain"]["file"]] if "domain" in block else [])
    entities = {1: "fibril core and linker"}
    entities.update({2 + d: f"domain {d + 1}" + (f" ({named[d]})" if d < len(named) else "")
                     for d in range(1 + len(par.get("domain_diameters") or ()))})
    return {"title": title, "details": details, "params": params, "entities": entities}


def shown(value) -> str:
    """A parameter's value in a header: numbers by %g, lists space-separated, an outline's
    points as x,y pairs (the --pdb REMARKs too)."""
    if isinstance(value, (list, tuple)):
        return " ".join(",".join(f"{v:g}" for v in item) if isinstance(item, (list, tuple))
                        else f"{item:g}" for item in value)
    return str(value)


def _member_radii(p, members: int) -> list:
    radii = chain_radii(p)
    return radii if len(radii) == members else [p.residue_radius] * members


def _fmt(values, spec: str) -> list:
    return [spec % v for v in np.asarray(values).tolist()]


def document(atoms: dict, header: dict, assembly: dict | None = None):
    """A gemmi.cif.Document of the atoms. `header`: title, details, params {name: text};
    `assembly` (helical_assembly): the atoms are its asymmetric unit, expanded by its operators."""
    import gemmi
    doc = gemmi.cif.Document()
    block = doc.add_new_block("fibrilfit")
    q = gemmi.cif.quote
    block.set_pair("_entry.id", "fibrilfit")
    block.set_pair("_struct.entry_id", "fibrilfit")
    block.set_pair("_struct.title", q(header.get("title", "FibrilFit decorated fibril")))
    details = header.get("details", "")
    if assembly is not None:
        details = "; ".join(filter(None, [details, assembly_text(assembly)]))
    block.set_pair("_struct.pdbx_model_details", q(details))
    entities = sorted(set(atoms["entity"].tolist()))
    block.set_mmcif_category("_entity", {
        "id": [str(e) for e in entities], "type": ["polymer"] * len(entities),
        "pdbx_description": [q(header.get("entities", {}).get(e, f"entity {e}"))
                             for e in entities]}, raw=True)
    params = header.get("params", {})
    if params:
        block.set_mmcif_category("_fibrilfit_param", {
            "name": list(params), "value": [str(v) for v in params.values()]})
    n = len(atoms["xyz"])
    xyz = atoms["xyz"]
    resnum = _fmt(atoms["resnum"], "%d")
    name = atoms["name"].tolist()
    resname = atoms["resname"].tolist()
    chain = atoms["chain"].tolist()
    cols = {
        "group_PDB": np.where(atoms["hetero"], "HETATM", "ATOM").tolist(),
        "id": _fmt(np.arange(1, n + 1), "%d"),
        "type_symbol": atoms["element"].tolist(),
        "label_atom_id": name, "label_alt_id": ["."] * n, "label_comp_id": resname,
        "label_asym_id": chain, "label_entity_id": _fmt(atoms["entity"], "%d"),
        "label_seq_id": resnum, "pdbx_PDB_ins_code": ["?"] * n,
        "Cartn_x": _fmt(xyz[:, 0], "%.3f"), "Cartn_y": _fmt(xyz[:, 1], "%.3f"),
        "Cartn_z": _fmt(xyz[:, 2], "%.3f"), "occupancy": ["1.00"] * n,
        "B_iso_or_equiv": _fmt(atoms["b"], "%.2f"), "auth_seq_id": resnum,
        "auth_comp_id": resname, "auth_asym_id": chain, "auth_atom_id": name,
        "pdbx_PDB_model_num": ["1"] * n}
    block.set_mmcif_category("_atom_site", {k: cols[k] for k in ATOM_COLUMNS}, raw=True)
    if assembly is not None:
        _assembly_categories(block, atoms, assembly)
    return doc


def _chains_in_order(atoms: dict) -> list[str]:
    return list(dict.fromkeys(atoms["chain"].tolist()))


def _assembly_categories(block, atoms: dict, assembly: dict) -> None:
    """_struct_asym, and assembly ASSEMBLY_ID: every chain, under every operator (listed one by
    one: '1,2,3', never a product '(1-3)(4)'), each operator's 3 × 4 matrix."""
    chains = _chains_in_order(atoms)
    entity_of = dict(zip(atoms["chain"].tolist(), atoms["entity"].tolist()))
    block.set_mmcif_category("_struct_asym", {
        "id": chains, "entity_id": [str(entity_of[c]) for c in chains]})
    ops = [str(i + 1) for i in range(len(assembly["m"]))]
    count = len(chains) * len(ops)
    block.set_mmcif_category("_pdbx_struct_assembly", {
        "id": [ASSEMBLY_ID], "details": ["software_defined_assembly"],
        "method_details": ["FibrilFit periodic cell"],
        "oligomeric_details": [f"{count}-meric"], "oligomeric_count": [str(count)]})
    block.set_mmcif_category("_pdbx_struct_assembly_gen", {
        "assembly_id": [ASSEMBLY_ID], "oper_expression": [",".join(ops)],
        "asym_id_list": [",".join(chains)]})
    rows = {tag: [] for tag in OPER_TAGS}
    for op, m, matrix in zip(ops, assembly["m"], assembly["matrices"]):
        rows["id"].append(op)
        rows["type"].append("identity operation" if m == 0 else "helical symmetry operation")
        rows["name"].append(f"S^{m}")
        rows["symmetry_operation"].append(None)  # '?': not a crystal symmetry
        matrix = np.round(matrix, 10) + 0.0  # no '-0.0000000000'
        for i in range(3):
            for j in range(3):
                rows[f"matrix[{i + 1}][{j + 1}]"].append(f"{matrix[i, j]:.10f}")
            rows[f"vector[{i + 1}]"].append(f"{matrix[i, 3]:.6f}")
    block.set_mmcif_category("_pdbx_struct_oper_list", rows)


def write(path, atoms: dict, header: dict, assembly: dict | None = None) -> dict:
    """Write the atoms to `path` (atomically) as mmCIF; what was written, for the result.
    `assembly` (helical_assembly): the atoms are its asymmetric unit, and the file says how to
    expand them."""
    if not len(atoms["xyz"]):
        raise AtomsError("no atoms to write")
    doc = document(atoms, header, assembly)
    files.atomic_write(path, lambda tmp: doc.write_file(str(tmp)))
    info = {"path": str(path), "atoms": int(len(atoms["xyz"])),
            "chains": int(len(set(atoms["chain"].tolist())))}
    if assembly is not None:
        info["assembly"] = {"id": ASSEMBLY_ID, "operators": len(assembly["m"]),
                            "image_cells": assembly["m"][1:],
                            "screw_turn_deg": assembly["screw_turn_deg"],
                            "screw_rise": assembly["screw_rise"],
                            "chains": info["chains"] * len(assembly["m"]),
                            "atoms": info["atoms"] * len(assembly["m"])}
    return info
