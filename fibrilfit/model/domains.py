"""The domains of a chain, the one room that owns them: plain numpy, no bpy.

A chain is an anchor, a linker and one or more domains, from the core outward; with several, a
linker between consecutive ones (docs/guide/atoms-and-domains.md#several-domains). Each domain
is a `Domain`: its shape, its size, its body rows [x, y, z, r] in its body frame, the joint its
incoming linker holds, the exit its outgoing linker leaves from, and the residues to the next.
`Params.domains` builds them from the flat parameters (globule_diameter, domain_atoms,
domain_spheres, domain_joint, domain_diameters, further_atoms, further_spheres,
further_joints, domain_exits, domain_linker, domain_shape), which stay the one definition for
the CLI, the panel, case files and JSON; one domain is a list of one.

What differs between shapes is said once, in SHAPES (one `Shape` per word of
param_spec.DOMAIN_SHAPES): where its rows come from, how far its body reaches from its centre, the
collision body Bullet gives it, and which exact clash check judges it
(docs/model/domain-shapes.md#domain-shapes). Everything else asks a domain or its shape; only
the builders' mesh makers and the analysis' exact checks are looked up by the shape's name,
from the rooms that own them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .param_spec import ParamError

# A hull's points lie r/0.934 + 0.01 Å from their atom's centre (geom/shape.py, grow) and
# Bullet's surface 0.1 Å beyond them (HULL_MARGIN): 1/0.93 and 0.11 Å bound both
# (docs/model/domain-shapes.md#periodic).
HULL_REACH_FACTOR, HULL_REACH_SLACK = 1.0 / 0.93, 0.11
# Bullet's surface around a hull globule's mesh: resting contacts interpenetrate by ~0.05 Å
# (docs/model/domain-shapes.md#margin), so a margin of 0.1 Å keeps two resting meshes, and
# so the atoms, apart, and the BVH test on the mesh counts only a real overlap.
HULL_MARGIN = 0.1


@dataclass(frozen=True)
class Shape:
    """What one domain shape is. `rows`/`further`: the parameters holding the first domain's
    and the further domains' rows (None: the sphere, which has none); `grow`, `slack`: a
    bound of the body's reach from its rows (each row's radius times grow, plus slack);
    `collision`: Bullet's collision shape of its globule; `margin`: Bullet's collision margin
    (None: Bullet's default, unused); `compound`: the body is child spheres, one per row;
    `spread`: a full-size start must spread it (it can lock: docs/model/domain-shapes.md#spheres-start)."""

    name: str
    rows: str | None
    further: str | None
    grow: float
    slack: float
    collision: str
    margin: float | None
    compound: bool
    spread: bool

    @property
    def real(self) -> bool:
        """A real shape (taken from a structure, joined at its terminal CA): not the sphere."""
        return self.rows is not None

    def reach(self, rows) -> float:
        """The farthest this shape's body reaches from its centre, from its rows [x, y, z, r]:
        hull atoms grown as its points are (plus Bullet's margin), or covering spheres."""
        rows = np.asarray(rows, dtype=float).reshape(-1, 4)
        return float((np.linalg.norm(rows[:, :3], axis=1) + rows[:, 3] * self.grow).max()
                     + self.slack)


SHAPES = {
    "sphere": Shape("sphere", None, None, 1.0, 0.0, "SPHERE", None, False, False),
    "hull": Shape("hull", "domain_atoms", "further_atoms", HULL_REACH_FACTOR, HULL_REACH_SLACK,
                  "CONVEX_HULL", HULL_MARGIN, False, False),
    "spheres": Shape("spheres", "domain_spheres", "further_spheres", 1.0, 0.0, "COMPOUND", None,
                     True, True),
}


@dataclass(frozen=True, eq=False)
class Domain:
    """One domain of a chain (0 nearest the core). `member`: its index along the chain;
    `rows`: its body [x, y, z, r] in its body frame (None: the sphere); `joint`, `exit`: its
    incoming and outgoing linkers' joints (terminal CAs) in that frame (None: the sphere, or the
    last domain's exit); `linker`: residues to the next domain (None: the last)."""

    index: int
    shape: Shape
    diameter: float
    member: int
    rows: np.ndarray | None
    joint: np.ndarray | None
    exit: np.ndarray | None
    linker: int | None

    @property
    def radius(self) -> float:
        return self.diameter / 2.0

    @property
    def reach(self) -> float:
        """How far its body reaches from its centre (Å): the sphere's radius, or a bound of a
        real shape's (hull: its atoms grown as its points are; spheres: the farthest sphere)."""
        return self.radius if self.rows is None else self.shape.reach(self.rows)


def member_indices(p) -> list[int]:
    """Each domain's place along the chain (Domain.member), from the flat parameters: the first
    at free_linker (one domain: the chain's last member), each next one its linker's residues
    plus one further out. Read before the domains can be built (an unchecked Params)."""
    out = [p.free_linker]
    for gap in p.domain_linker or ():
        out.append(out[-1] + gap + 1)
    return out


def shape_of(p) -> Shape:
    """The chain's domain shape (every domain of a chain has the same)."""
    return SHAPES[p.domain_shape]


def several_shapes(p) -> bool:
    """Several domains per chain, each with its real shape (hull, spheres)."""
    return shape_of(p).real and bool(p.domain_diameters)


def domain_rows(p, k: int) -> np.ndarray:
    """Domain k's (0 nearest the core) shape rows [x, y, z, r] in its body frame: its hull atoms
    (hull) or covering spheres (spheres)."""
    shape = shape_of(p)
    if k == 0:
        return np.asarray(getattr(p, shape.rows), dtype=float).reshape(-1, 4)
    rows = np.asarray(getattr(p, shape.further), dtype=float).reshape(-1, 5)
    return rows[np.round(rows[:, 0]).astype(int) == k, 1:]


def domains(p) -> list[Domain]:
    """The chain's domains, from the core outward: one for each of globule_diameter and
    domain_diameters. A real shape's first domain has its rows and joint; its further domains
    (several real shapes) theirs, and every domain but the last its exit."""
    shape = shape_of(p)
    diameters = [p.globule_diameter, *(p.domain_diameters or ())]
    members = member_indices(p)
    gaps = list(p.domain_linker or ())
    real = shape.real and getattr(p, shape.rows) is not None and p.domain_joint is not None
    several = real and len(diameters) > 1
    joints = [p.domain_joint[0], *(p.further_joints or ())] if real else []
    exits = list(p.domain_exits or ()) if several else []
    out = []
    for k, (d, member) in enumerate(zip(diameters, members)):
        body = real and (k == 0 or several)
        out.append(Domain(
            index=k, shape=shape, diameter=float(d), member=member,
            rows=domain_rows(p, k) if body else None,
            joint=np.asarray(joints[k], dtype=float) if body and k < len(joints) else None,
            exit=np.asarray(exits[k], dtype=float) if k < len(exits) else None,
            linker=gaps[k] if k < len(gaps) else None))
    return out


# ---- the shapes' checks (make_params: param_checks.check_combination) ------------------------
def check_shapes(p) -> None:
    """A real shape needs its rows and joint; several real shapes every domain's, and an exit
    on each but the last; covering spheres positive radii."""
    need = p.shape.rows
    if need and (getattr(p, need) is None or p.domain_joint is None):
        raise ParamError("domain_shape", f"{p.shape.name} needs a domain structure (--domain "
                                         f"FILE) to take its shape and joint from")
    if p.several_shapes:
        _check_several_shapes(p)
    for name in ("domain_spheres", "further_spheres"):
        rows = getattr(p, name)
        if rows is not None and min(row[-1] for row in rows) <= 0:
            raise ParamError(name, "every sphere's radius must be positive")


def _check_several_shapes(p) -> None:
    """hull, spheres with several domains: every domain's own shape and joint, and an exit on
    every domain but the last (docs/guide/atoms-and-domains.md#shapes-of-several-domains)."""
    more = len(p.domain_diameters)
    rows = getattr(p, p.shape.further)
    have = set() if rows is None else {int(round(r[0])) for r in rows}
    if (have != set(range(1, more + 1)) or len(p.further_joints or ()) != more
            or len(p.domain_exits or ()) != more):
        raise ParamError("domain_shape", f"{p.shape.name} with {more + 1} domains per chain "
                                         f"needs every domain's structure (--domain FILE once "
                                         f"per domain) to take its shape, joint and exit from")
    if min(p.domain_linker) < 1:
        # the exit CA and the next domain's joint CA would be one bond apart, with both a few
        # Å inside their hulls: the two shapes start inside each other
        raise ParamError("domain_linker", f"must be at least 1 residue between real-shaped "
                                          f"domains ({p.shape.name}): the outgoing linker "
                                          f"leaves one domain's terminal CA and enters the "
                                          f"next one's through at least one bead "
                                          f"(got {', '.join(map(str, p.domain_linker))})")
