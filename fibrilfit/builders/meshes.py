"""Mesh datablocks shared by every object of a kind: one box, one bead, one globule."""
from __future__ import annotations

import bmesh
import bpy
from mathutils import Matrix, Vector
from mathutils.geometry import tessellate_polygon

from ..geom import polygons

from .scene import tag


def box(name: str, size) -> bpy.types.Mesh:
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0, matrix=Matrix.Diagonal((*size, 1.0)))
    return _finish(bm, name)


def prism(name: str, outline, height: float) -> bpy.types.Mesh:
    """A closed polygon (n, 2), possibly concave, extruded `height` along Z about z = 0: two
    n-gon caps and n quads, normals outward (Bullet's MESH shape triangulates the caps)."""
    pts = [tuple(map(float, xy)) for xy in outline]
    area = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]))
    if area < 0:
        pts.reverse()  # counter-clockwise seen from +Z
    n, h = len(pts), height / 2.0
    verts = [(x, y, -h) for x, y in pts] + [(x, y, h) for x, y in pts]
    faces = [tuple(range(n - 1, -1, -1)), tuple(range(n, 2 * n))]
    faces += [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
    me = tag(bpy.data.meshes.new(name), "mesh")
    me.from_pydata(verts, [], faces)
    me.validate()
    me.update()
    return me


def convex_pieces(outline) -> list:
    """A polygon (n, 2), possibly concave, cut into convex polygons (polygons.convex_pieces
    over Blender's own triangulation)."""
    pts = [[Vector((float(x), float(y), 0.0)) for x, y in outline]]
    return polygons.convex_pieces(outline, tessellate_polygon(pts))


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


def convex_hull(name: str, points) -> bpy.types.Mesh:
    """The convex hull of points (n, 3) as a closed triangle mesh (bmesh.ops.convex_hull),
    coplanar triangles kept (the BVH and Bullet see the same faces)."""
    bm = bmesh.new()
    for xyz in points:
        bm.verts.new(tuple(map(float, xyz)))
    bm.verts.index_update()
    result = bmesh.ops.convex_hull(bm, input=bm.verts, use_existing_faces=False)
    inner = {v.index: v for v in result["geom_interior"] + result["geom_unused"]
             if isinstance(v, bmesh.types.BMVert) and not v.link_faces}
    bmesh.ops.delete(bm, geom=list(inner.values()), context="VERTS")
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    me = tag(bpy.data.meshes.new(name), "mesh")
    bm.to_mesh(me)
    bm.free()
    return me


def sphere_union(name: str, spheres, segments: int, rings: int) -> bpy.types.Mesh:
    """Overlapping spheres [x, y, z, r] as one mesh of closed shells (drawn and BVH-tested)."""
    bm = bmesh.new()
    for x, y, z, r in spheres:
        bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings, radius=float(r),
                                  matrix=Matrix.Translation((float(x), float(y), float(z))))
    return _finish(bm, name)
