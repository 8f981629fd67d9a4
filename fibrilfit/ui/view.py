"""After a build or a run, the model framed in the window's 3D Views
(docs/guide/sidebar.md#after-a-run).

The model is about 100 Å tall (1 unit = 1 Å), so Blender's start-up view (about 18 units from
the origin) sits inside it: the user saw grey slabs until Home. Each 3D View's region_3d is set
through the data API (view_location at the centre of the model's bounds, view_distance so that
its bounding sphere fits the narrower side of the view); the view's rotation and shading stay
the user's, a camera view is left alone, and in the background (no windows) nothing happens.
"""
import math

import bpy
import numpy as np

from ..exports.dressing import model_points

SENSOR_MM = 36.0  # the 3D View's lens is given against Blender's default 36 mm sensor
MARGIN = 1.1      # a little room around the model's bounding sphere


def view_distance(radius: float, lens_mm: float, width: int, height: int) -> float:
    """The distance at which a sphere of `radius` fits a perspective view of this lens and
    region (its field of view spans the wider side; the narrower one is scaled by the aspect)."""
    half = math.atan(SENSOR_MM / (2.0 * lens_mm))
    if width < height:
        half = math.atan(math.tan(half) * width / height)
    return MARGIN * radius / math.sin(half)


def frame_model(context, model) -> int:
    """Frame `model` in every 3D View of every window. Returns the number of views framed."""
    return frame_points(context, model_points(model))


def frame_points(context, pts) -> int:
    """Frame the points `pts` (n, 3; world, Å) in every 3D View of every window: none in the
    background, without a window manager or 3D View, or with no point. Returns the number of
    views framed."""
    if bpy.app.background or getattr(context, "window_manager", None) is None or not len(pts):
        return 0
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre, radius = (lo + hi) / 2.0, max(float(np.linalg.norm(hi - lo)) / 2.0, 1.0)
    framed = 0
    for window in context.window_manager.windows:
        for area in window.screen.areas:
            if area.type != "VIEW_3D":
                continue
            space = area.spaces.active
            r3d = space.region_3d
            if r3d is None or r3d.view_perspective == "CAMERA":
                continue
            region = next((r for r in area.regions if r.type == "WINDOW"), None)
            if region is None or region.width < 2 or region.height < 2:
                continue
            distance = view_distance(radius, space.lens, region.width, region.height)
            r3d.view_location = centre.tolist()
            r3d.view_distance = distance
            if space.clip_end < distance + radius:  # else the far half would be clipped away
                space.clip_end = 2.0 * (distance + radius)
            area.tag_redraw()
            framed += 1
    return framed
