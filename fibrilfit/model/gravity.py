"""Which part of the random gravity a model feels: plain Python, no bpy.

A periodic cell judged with gravity on feels only its axial part
(docs/model/periodic-cell.md#gravity-in-a-cell); anything else feels the whole vector.
"""
from __future__ import annotations


def cell_gravity(p, gravity):
    """The part of a uniform gravity a periodic cell can feel while it is judged: its axial (Z)
    component.

    The screw turns an image's surroundings by m·M·twist, so a sideways gravity would act on
    the cell as on a fibril whose every M-th stretch of layers feels it turned: not a uniform
    field, and not an infinite fibril. Only the axial part is the same in every image. This
    matters where gravity is still on when the layout is judged (the tutorial protocol). Inflate
    anneals its gravity to zero before it judges: there gravity is only a way to search, any
    layout it reaches is judged as it is, so it keeps the whole vector
    (docs/model/periodic-cell.md#gravity-in-a-cell). Outside a cell `gravity` is returned
    unchanged.
    """
    if not axial_gravity(p):
        return tuple(float(g) for g in gravity)
    return (0.0, 0.0, float(gravity[2]))


def axial_gravity(p) -> bool:
    """Whether cell_gravity keeps only the axial part: a periodic cell judged with gravity on."""
    return bool(p.periodic) and p.protocol != "inflate"
