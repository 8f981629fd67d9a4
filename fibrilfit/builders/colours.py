"""The colours of a model's parts: per protofilament, and clashing or grazing globules red or
orange after a check (ob.color, read by the viewport and by materials)."""
from __future__ import annotations

import bpy
import numpy as np

from .physics import keep_bake
from .scene import PROTOFILAMENT, TAG

# an undecorated subunit (a mixed fibril): its bare tail or, without one, its anchor's marker;
# grey-blue, apart from the decorated chains' dark anchors and yellow linkers, so the picture
# shows which subunits carry the domain
BARE = (0.42, 0.45, 0.55, 1.0)
COLORS = {  # viewport/object colours; analysis recolours clashing globules
    "slab": (0.55, 0.62, 0.75, 1.0),
    "anchor": (0.25, 0.25, 0.3, 1.0),
    "residue": (0.95, 0.75, 0.2, 1.0),
    "globule": (0.7, 0.72, 0.7, 1.0),
    "tail": BARE,
    "bare_anchor": BARE,
}
CLASH_COLOR = (0.9, 0.08, 0.05, 1.0)
# A grazing pair (only the BVH names it, within the mesh's resolution:
# docs/model/verdict.md#two-checks) is not a deep clash: orange, so the picture does not overstate
# it and the two read apart.
GRAZE_COLOR = (1.0, 0.5, 0.0, 1.0)
# Protofilaments apart: globules and linker beads of protofilament j take tint j (0: COLORS).
PF_COLORS = {
    "globule": ((0.7, 0.72, 0.7, 1.0), (0.45, 0.62, 0.85, 1.0), (0.5, 0.78, 0.5, 1.0),
                (0.8, 0.6, 0.85, 1.0), (0.85, 0.75, 0.5, 1.0), (0.5, 0.8, 0.8, 1.0)),
    "residue": ((0.95, 0.75, 0.2, 1.0), (0.95, 0.5, 0.15, 1.0), (0.75, 0.9, 0.2, 1.0),
                (0.95, 0.6, 0.6, 1.0), (0.8, 0.8, 0.5, 1.0), (0.3, 0.85, 0.7, 1.0)),
}


def part_colour(role: str, pf: int = 0) -> tuple:
    """The colour of a part of protofilament `pf` (the same for every pf but globules, beads)."""
    tints = PF_COLORS.get(role)
    return COLORS[role] if tints is None else tints[pf % len(tints)]


def colour_globules(model, clashing_layers, scene=None, grazing=()) -> list[int]:
    """Globules of the chains `clashing_layers` red (chain = layer with one protofilament), those
    of `grazing` (chains whose every clash only grazes: analysis.clash_kinds) orange, the
    others their protofilament's colour, through ob.color. Returns the red.

    ob.color is what the viewport shows with Color: Object, and what materials read through
    an Object Info node, so one call recolours both after each check. Colouring edits simulated
    objects, so the bake is kept first (physics.keep_bake).
    """
    keep_bake(scene or bpy.context.scene)
    red = {int(k) for k in clashing_layers}
    pale = {int(k) for k in grazing} - red
    places = [d.member for d in model.params.domains]
    for k, members in enumerate(model.chain):
        for ob in (members[i] for i in places if i < len(members)):
            if ob.get(TAG) != "globule":
                continue
            colour = (CLASH_COLOR if k in red else GRAZE_COLOR if k in pale else
                      part_colour("globule", ob.get(PROTOFILAMENT, 0)))
            if not np.allclose(ob.color, colour, atol=1e-6):  # no needless update
                ob.color = colour
    return sorted(red)
