"""Mesh datablocks shared by every object of a kind: one box, one bead, one globule."""
from __future__ import annotations

import bmesh
import bpy
from mathutils import Matrix

from .scene import tag


def box(name: str, size) -> bpy.types.Mesh:
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0, matrix=Matrix.Diagonal((*size, 1.0)))
    return _finish(bm, name)


def uv_sphere(name: str, radius: float, segments: int, rings: int) -> bpy.types.Mesh:
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings, radius=radius)
    return _finish(bm, name)


def _finish(bm, name):
    me = tag(bpy.data.meshes.new(name), "mesh")
    bm.to_mesh(me)
    bm.free()
    me.shade_smooth()
    return me
