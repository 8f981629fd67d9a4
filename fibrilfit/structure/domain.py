"""Measure a globular domain: radius of gyration and the equivalent sphere's diameter."""
from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass, field

import numpy as np

from ..geom import shape as shapes
from . import fibril, reading
from .errors import StructureError

RG_TO_DIAMETER = 2.0 * math.sqrt(5.0 / 3.0)  # the uniform sphere with the same Rg
FIBRIL_STACK = 3  # chains stacked as layers that make a file a fibril, not a domain


@dataclass
class DomainSize:
    """What `inspect --domain` measures. to_dict() gives the JSON of the issue's key names."""

    file: str
    sha256: str
    chain: str
    residues: list  # [first, last] used
    atoms: int  # heavy atoms used
    rg: float  # Å, heavy atoms, unweighted
    globule_diameter: float  # Å, 2·√(5/3)·Rg
    max_dimension: float  # Å, largest heavy-atom distance (for comparison: an upper bound)
    notes: list = field(default_factory=list)
    # The real shape (docs/model/domain-shapes.md#domain-shapes): which residue carries the
    # joint, its CA's depth below the grown hull, the shape's sizes.
    shape: dict = field(default_factory=dict)
    # In the body frame (body_frame): hull atoms [x, y, z, r], covering spheres, the joint; not
    # in the JSON (the model's parameters carry them when a run uses them).
    geometry: dict = field(default_factory=dict, repr=False)

    def to_dict(self) -> dict:
        out = asdict(self)
        out.pop("geometry")
        return out


def parse_range(text) -> tuple:
    """'a-b' (negative numbers allowed, e.g. '-3-40') -> (a, b)."""
    if isinstance(text, (tuple, list)) and len(text) == 2:
        a, b = text
    else:
        m = re.fullmatch(r"\s*(-?\d+)\s*[-:]\s*(-?\d+)\s*", str(text))
        if not m:
            raise StructureError("--domain-residues", f"must be a residue range a-b, e.g. 1-72 "
                                                      f"(got {text!r})")
        a, b = m.groups()
    a, b = int(a), int(b)
    if a > b:
        raise StructureError("--domain-residues", f"must be a range a-b with a <= b (got {text!r})")
    return a, b


def select(loaded, *, chain: str | None = None, residues=None,
           option: str = "--domain") -> tuple:
    """(ChainAtoms, mask of its heavy atoms used, notes): the domain's chain (default the first
    protein chain) and residues (default all), as `measure` and the atom writer use them."""
    name = loaded.path.name
    stack = fibril.longest_stack(loaded)
    if stack >= FIBRIL_STACK:
        raise StructureError(option, f"{name} holds a stacked fibril ({stack} chains stacked "
                                     f"{fibril.STACK[0]}-{fibril.STACK[1]} Å apart, as a "
                                     f"fibril's layers), not a globular domain: give it as "
                                     f"--fibril, and the domain's own structure as --domain")
    names = [c.name for c in loaded.chains]
    if chain is None:
        c = loaded.chains[0]
    elif chain in names:
        c = loaded.chains[names.index(chain)]
    else:
        raise StructureError("--domain-chain", f"no protein chain {chain!r} in {name} "
                                               f"(chains: {', '.join(names)})")
    notes = list(loaded.notes)
    if chain is None and len(names) > 1:
        notes.append(f"{len(names)} protein chains ({', '.join(names)}): chain {c.name} used")
    keep = np.ones(len(c.heavy), bool)
    if residues is not None:
        a, b = parse_range(residues)
        keep = (c.heavy_residue >= a) & (c.heavy_residue <= b)
        if not keep.any():
            raise StructureError("--domain-residues", f"no residue {a}-{b} in chain {c.name} of "
                                                      f"{name} (residues {c.residues[0]}-"
                                                      f"{c.residues[-1]})")
    return c, keep, notes


def measure(path, *, chain: str | None = None, residues=None, option: str = "--domain",
            follows: bool = True, outgoing: bool = False) -> DomainSize:
    """Measure the domain of `path`. `follows`: the domain comes after the fibril core in
    sequence (the core's C-terminus carries the linker), so its first residue is the joint; else
    its last. `outgoing`: a further domain follows on the chain, so the outgoing linker's point
    (terminals) is reported too."""
    loaded = reading.load(path, option)
    return measure_loaded(loaded, chain=chain, residues=residues, option=option, follows=follows,
                          outgoing=outgoing)


def measure_loaded(loaded, *, chain: str | None = None, residues=None,
                   option: str = "--domain", follows: bool = True,
                   outgoing: bool = False) -> DomainSize:
    """`measure` of a file already read (reading.load)."""
    name = loaded.path.name
    c, keep, notes = select(loaded, chain=chain, residues=residues, option=option)
    xyz = c.heavy[keep]
    used = np.unique(c.heavy_residue[keep])
    rg = float(np.sqrt(((xyz - xyz.mean(axis=0)) ** 2).sum(axis=1).mean()))
    hull = xyz  # max dimension over all pairs, in blocks to bound memory
    dmax = 0.0
    for i in range(0, len(hull), 512):
        d = np.linalg.norm(hull[i:i + 512, None, :] - hull[None, :, :], axis=-1)
        dmax = max(dmax, float(d.max()))
    ca_keep = (c.residues >= used[0]) & (c.residues <= used[-1])
    summary, geometry = measure_shape(xyz, c.heavy_radius[keep], c.ca[ca_keep],
                                      c.residues[ca_keep], follows, outgoing)
    return DomainSize(name, loaded.sha256, c.name, [int(used[0]), int(used[-1])], int(len(xyz)),
                      round(rg, 3), round(RG_TO_DIAMETER * rg, 3), round(dmax, 2), notes,
                      summary, geometry)


def terminals(ca, residues, follows: bool = True) -> dict:
    """Where the linkers meet a domain (docs/model/domain-shapes.md#joint): the incoming linker
    (from the core, or from the domain before it) joins at the CA of the domain's first residue
    when the domain follows the core in sequence, of its last when it precedes; the outgoing
    linker (towards the next domain outward) leaves from the opposite terminal CA. `ca`: (n, 3)
    in residue order, `residues` their numbers. Returns {"entry": (CA, residue, terminus),
    "exit": (CA, residue, terminus)}, terminus "N" or "C"."""
    ca = np.asarray(ca, float).reshape(-1, 3)
    first, last = (ca[0], int(residues[0]), "N"), (ca[-1], int(residues[-1]), "C")
    return {"entry": first, "exit": last} if follows else {"entry": last, "exit": first}


def measure_shape(heavy, radii, ca, residues, follows: bool = True,
                  outgoing: bool = False) -> tuple[dict, dict]:
    """The domain's real shape in its body frame: (summary for inspect and the JSON, geometry
    for the model's parameters domain_atoms, domain_spheres, domain_joint). `outgoing`: a
    further domain follows on the chain; the summary also gives the outgoing linker's point
    (exit_*), as deep as the joint is reported."""
    centroid, local = body_frame(heavy)
    hull = shapes.hull_atoms(local, radii)
    spheres = shapes.covering_spheres(local, radii)
    ends = terminals(ca, residues, follows)
    joint = ends["entry"][0] - centroid
    reach = float((np.linalg.norm(hull[:, :3], axis=1) + hull[:, 3]
                   + shapes.grow(hull[:, 3])).max())
    summary = {"joint_residue": ends["entry"][1], "joint_terminus": ends["entry"][2],
               "joint_depth": round(shapes.depth_below(local, radii, joint), 2),
               "joint_distance": round(float(np.linalg.norm(joint)), 2),
               "hull_atoms": int(len(hull)), "bounding_radius": round(reach, 2),
               "spheres": int(len(spheres)),
               "joint_depth_spheres": round(shapes.union_exit(spheres, joint)[1], 2),
               "spheres_radius": [round(float(r), 2) for r in spheres[:, 3]]}
    if outgoing:
        out = ends["exit"][0] - centroid
        summary.update(exit_residue=ends["exit"][1], exit_terminus=ends["exit"][2],
                       exit_depth=round(shapes.depth_below(local, radii, out), 2),
                       exit_depth_spheres=round(shapes.union_exit(spheres, out)[1], 2),
                       exit_distance=round(float(np.linalg.norm(out)), 2),
                       joint_exit_distance=round(float(np.linalg.norm(out - joint)), 2))
    geometry = {"domain_atoms": np.round(hull, 3).tolist(),
                "domain_spheres": np.round(spheres, 3).tolist(),
                "domain_joint": np.round(joint, 3).tolist()}
    if outgoing:  # the outgoing linker's joint (mapping.model_values: domain_exits)
        geometry["exit"] = np.round(ends["exit"][0] - centroid, 3).tolist()
    return summary, geometry


def body_frame(atoms) -> tuple:
    """The domain's rigid-body frame: (centroid (3,), local_xyz (m, 3)).

    The globule object's local frame is the domain file's coordinates minus the heavy-atom
    centroid, with no rotation; its shape meshes (hull, spheres) are built in it, and an atom at
    `local` in it lies at `matrix_world @ local` once the body has moved. `atoms`: (m, 3) heavy
    atoms in the file's frame (Å)."""
    xyz = np.asarray(atoms, dtype=float).reshape(-1, 3)
    if not len(xyz):
        raise ValueError("body_frame: no atoms")
    centroid = xyz.mean(axis=0)
    return centroid, xyz - centroid
