"""Materials, camera and light, so the model reads in a render or an opened .blend.

Colour lives on the objects (`ob.color`, set per role by builders/layers.py): each material reads
it through an Object Info node, so recolouring one clashing globule red touches nothing else.
Everything made here is tagged like the builders' datablocks, so clear_model removes it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import bpy
import numpy as np
from mathutils import Matrix, Vector

from ..builders.colours import COLORS, colour_globules
from ..builders.periodic import MOVING, STATIC, image_collection
from ..builders.physics import keep_bake
from ..builders.scene import TAG, is_ours, new_collection, tag

BACKGROUND = (0.3, 0.32, 0.36)     # linear; a mid grey that light globules stand out on
VIEW_ROLE = "view"                # collection holding the camera and light
LENS_MM, SENSOR_MM = 50.0, 36.0
ELEVATION = math.radians(20.0)    # the camera looks a little down on the model
TURN = math.radians(15.0)         # from side-on towards the globules, for depth
AMBIENT = 0.6                     # world light on the model; the backdrop itself shows BACKGROUND
MARGIN = 1.08                     # the model fills at most 1/MARGIN of the frame


@dataclass
class Dressing:
    camera: bpy.types.Object
    light: bpy.types.Object
    materials: dict


def dress(scene: bpy.types.Scene, model, clashing=None, *, aspect: float = 16 / 9,
          grazing=()) -> Dressing:
    """Give `model` materials, a framing camera and a light (reused if dressed before).

    `clashing`: layers to colour red (None leaves the colours as they are); `grazing`: layers
    whose globules only graze, pale red. The camera is
    framed on the model as it stands now (call at the last frame). scene.camera and
    scene.world are set only if empty or already FibrilFit's.
    """
    keep_bake(scene)
    if clashing is not None:
        colour_globules(model, clashing, scene, grazing)
    materials = ensure_materials(model)
    view = _view_collection(model)
    camera = _owned_object(view, "camera", lambda: bpy.data.cameras.new("FibrilFit camera"))
    light = _owned_object(view, "light", lambda: bpy.data.lights.new("FibrilFit light", "SUN"))
    frame_camera(camera, model_points(model), aspect, view_azimuth(model))
    aim_light(light, camera)
    if scene.camera is None or is_ours(scene.camera):
        scene.camera = camera
    if scene.world is None:
        scene.world = _new_world()
    elif is_ours(scene.world):
        _fill_world(scene.world)
    return Dressing(camera, light, materials)


# ---- materials ------------------------------------------------------------------------------

def ensure_materials(model) -> dict:
    """One material per shared mesh (slab, bead = anchor and residues, globule), each taking
    its colour from the object. Returns {part: material}."""
    first = model.chain[0] if model.chain else []  # a model built part of the way: its parts
    meshes = {"slab": model.slabs[0].data if model.slabs else None,
              "bead": first[0].data if first else None,
              "globule": first[-1].data if first and first[-1].get(TAG) == "globule" else None}
    meshes = {part: mesh for part, mesh in meshes.items() if mesh is not None}
    viewport = {"slab": COLORS["slab"], "bead": COLORS["residue"], "globule": COLORS["globule"]}
    out = {}
    for part, mesh in meshes.items():
        mat = next((m for m in mesh.materials if m is not None and is_ours(m)), None)
        if mat is None:
            mat = _object_colour_material(f"FibrilFit {part}")
            mesh.materials.clear()
            mesh.materials.append(mat)
        mat.diffuse_color = viewport[part]  # solid viewport in Material mode
        out[part] = mat
    # several real-shaped domains: each domain's own mesh takes the globules' material too
    if "globule" in out:
        for ob in first:
            if ob.get(TAG) == "globule" and out["globule"] not in ob.data.materials[:]:
                ob.data.materials.clear()
                ob.data.materials.append(out["globule"])
    return out


COLOUR_KEY = "fibrilfit_colour"  # on an object-linked colour material: its colour, "#rrggbb"


def show_colours(model) -> int:
    """The model's colours in Solid mode, with the user's shading left alone: Solid's default
    Color: Material shows a material's diffuse colour, so each object whose colour (ob.color:
    its role, its protofilament's tint, a clash's red, a graze's orange) differs from its mesh's
    material gets a material of that colour of the model's own, linked to the object; renders
    read ob.color through Object Info either way. Returns how many objects have their own.

    Edits simulated objects: after a bake, keep the bake first (colour_globules does)."""
    ensure_materials(model)
    palette = {m.get(COLOUR_KEY): m for m in bpy.data.materials
               if is_ours(m) and m.get(COLOUR_KEY)}
    own = 0

    def material_of(colour):
        key = "#" + "".join(f"{round(min(max(c, 0.0), 1.0) * 255):02x}" for c in colour)
        if key not in palette:
            palette[key] = _object_colour_material(f"FibrilFit {key}")
            palette[key][COLOUR_KEY] = key
            palette[key].diffuse_color = colour
        return palette[key]

    root = model.root
    for ob in {ob for c in (root, *root.children_recursive) for ob in c.objects}:
        if ob.type != "MESH" or not is_ours(ob):
            continue
        colour = tuple(ob.color)
        if not ob.material_slots:  # a mesh of its own (a core piece, an image's): its colour
            ob.data.materials.append(material_of(colour))
        slot = ob.material_slots[0]
        base = ob.data.materials[0]
        if base is not None and np.allclose(base.diffuse_color, colour, atol=1e-3):
            if slot.link != "DATA":
                slot.link = "DATA"
            continue
        mat = material_of(colour)
        if slot.link != "OBJECT":
            slot.link = "OBJECT"
        if slot.material != mat:
            slot.material = mat
        own += 1
    return own


def _object_colour_material(name: str) -> bpy.types.Material:
    mat = tag(bpy.data.materials.new(name), "material")
    if bpy.app.version < (5, 0, 0):  # from 5.0 every material has nodes (use_nodes deprecated)
        mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = next(n for n in nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    info = nodes.new("ShaderNodeObjectInfo")
    info.location = (bsdf.location.x - 250, bsdf.location.y)
    links.new(info.outputs["Color"], bsdf.inputs["Base Color"])
    bsdf.inputs["Roughness"].default_value = 0.45
    mat.roughness = 0.45
    return mat


def _new_world() -> bpy.types.World:
    world = tag(bpy.data.worlds.new("FibrilFit world"), "world")
    _fill_world(world)
    return world


def _fill_world(world: bpy.types.World) -> None:
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = True
    world.color = BACKGROUND  # Workbench's backdrop
    # Cycles: camera rays see the light backdrop; everything else gets a dimmer ambient light,
    # so the model is lit mostly by the sun and its shapes read.
    nodes, links = world.node_tree.nodes, world.node_tree.links
    for node in [n for n in nodes if n.bl_idname != "ShaderNodeOutputWorld"]:
        nodes.remove(node)
    out = next(n for n in nodes if n.bl_idname == "ShaderNodeOutputWorld")
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    ambient, backdrop = nodes.new("ShaderNodeBackground"), nodes.new("ShaderNodeBackground")
    for node, strength in ((ambient, AMBIENT), (backdrop, 1.0)):
        node.inputs["Color"].default_value = (*BACKGROUND, 1.0)
        node.inputs["Strength"].default_value = strength
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(ambient.outputs["Background"], mix.inputs[1])
    links.new(backdrop.outputs["Background"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])


# ---- camera and light -----------------------------------------------------------------------

def _view_collection(model) -> bpy.types.Collection:
    for coll in model.root.children:
        if coll.get("fibrilfit") == VIEW_ROLE:
            return coll
    return new_collection("FibrilFit view", VIEW_ROLE, model.root)


def _owned_object(coll, role, new_data):
    for ob in coll.objects:
        if ob.get("fibrilfit") == role:
            return ob
    data = tag(new_data(), role)
    ob = tag(bpy.data.objects.new(data.name, data), role)
    coll.objects.link(ob)
    return ob


def model_points(model) -> np.ndarray:
    """World-space corners of every object's bounding box, shape (n, 3): the cores, chains, a
    mixed fibril's bare tails and bare-anchor markers and, in a periodic cell, every image, so
    that the camera frames the cell and its images and every subunit, decorated or not."""
    objects = [*model.slabs, *(ob for members in model.chain for ob in members),
               *(ob for members in model.tails for ob in members), *model.bare_anchors]
    for role in (MOVING, STATIC):
        coll = image_collection(model, role)
        if coll is not None:
            objects += [ob for ob in coll.all_objects if ob.type == "MESH"]
    pts = []
    for ob in objects:
        corners = np.array(ob.bound_box, dtype=float)
        m = np.array(ob.matrix_world, dtype=float)
        pts.append(corners @ m[:3, :3].T + m[:3, 3])
    return np.concatenate(pts) if pts else np.zeros((1, 3))


def view_basis(forward, *, axis_across: bool) -> tuple[np.ndarray, np.ndarray]:
    """(right, up) for a camera looking along `forward`; the fibril axis Z points up, or to the
    right when `axis_across` (a tall fibril then fills a landscape frame)."""
    f = np.asarray(forward, dtype=float)
    right = np.cross(f, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    return (up, -right) if axis_across else (right, up)


def fit_view(points, target, forward, right, up, tan_x: float, tan_y: float
             ) -> tuple[float, float, float]:
    """The closest distance from `target` (along -forward) at which the points fit the frame
    once centred by lens shift; returns (distance, centre u, centre v), where u, v in [-1, 1]
    span the frame's width and height."""
    q = np.asarray(points, dtype=float) - target
    x, y, z = q @ right, q @ up, q @ forward
    size = float(np.ptp(q, axis=0).max()) or 1.0

    def spread(d):
        depth = d + z
        u, v = x / (depth * tan_x), y / (depth * tan_y)
        return u.min(), u.max(), v.min(), v.max()

    def fits(d):
        u0, u1, v0, v1 = spread(d)
        return (u1 - u0) / 2 * MARGIN <= 1.0 and (v1 - v0) / 2 * MARGIN <= 1.0

    # Centred on target with no shift, this distance fits (see the symmetric bound); search
    # down from it to the closest one that still fits with the best shift.
    hi = float((np.maximum(np.abs(x) * MARGIN / tan_x, np.abs(y) * MARGIN / tan_y) - z).max())
    lo = float(-z.min() + 0.05 * size)
    hi = max(hi, lo)
    for _ in range(50):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if fits(mid) else (mid, hi)
    u0, u1, v0, v1 = spread(hi)
    return hi, (u0 + u1) / 2, (v0 + v1) / 2


def view_azimuth(model) -> float:
    """Azimuth (rad) of the camera about the fibril axis: side-on to where the globules went,
    so the linkers between slabs and globules are in view rather than hidden behind globules."""
    centres = np.array([ob.matrix_world.translation for ob in model.globules], dtype=float)
    gx, gy = centres[:, :2].mean(axis=0) if len(centres) else (1.0, 0.0)
    towards = math.atan2(gy, gx) if math.hypot(gx, gy) > 1e-6 else 0.0
    if model.params.protofilaments > 1 and len(centres) > 1:
        # Globules all round the axis (protofilaments): their mean says little. Look across the
        # direction they spread most, so the protofilaments stand side by side, not one behind
        # the other.
        xy = centres[:, :2] - centres[:, :2].mean(axis=0)
        spread = np.linalg.eigh(xy.T @ xy)[1][:, -1]
        if math.hypot(gx, gy) < 0.25 * float(np.sqrt((xy ** 2).sum(axis=1).mean())):
            towards = math.atan2(spread[1], spread[0])
    return towards - math.pi / 2 + TURN


def frame_camera(camera: bpy.types.Object, points, aspect: float, azimuth: float) -> float:
    """Aim and place `camera` at `azimuth` so every point is in view at this aspect (w/h),
    centred by lens shift. Tries the fibril axis vertical and across, keeps the closer (larger)
    view. Returns the camera's distance from the model's centre.
    """
    points = np.asarray(points, dtype=float)
    lo, hi = points.min(axis=0), points.max(axis=0)
    target = (lo + hi) / 2
    forward = -np.array([math.cos(ELEVATION) * math.cos(azimuth),
                         math.cos(ELEVATION) * math.sin(azimuth), math.sin(ELEVATION)])
    tan_x = SENSOR_MM / 2 / LENS_MM
    tan_y = tan_x / aspect
    best = None
    for across in (False, True):
        right, up = view_basis(forward, axis_across=across)
        fit = fit_view(points, target, forward, right, up, tan_x, tan_y)
        if best is None or fit[0] < best[0][0] - 1e-9:
            best = (fit, right, up)
    (distance, cu, cv), right, up = best
    cam = camera.data
    cam.type = "PERSP"
    cam.lens, cam.sensor_width, cam.sensor_fit = LENS_MM, SENSOR_MM, "HORIZONTAL"
    # Blender's shift is in units of the frame's width (the fitted side) both ways.
    cam.shift_x, cam.shift_y = cu / 2, cv / (2 * aspect)
    depth = (points - target) @ forward + distance
    cam.clip_start = max(1e-3, float(depth.min()) * 0.5)
    cam.clip_end = float(depth.max()) * 1.5 + 1.0
    basis = Matrix((tuple(right), tuple(up), tuple(-forward))).transposed()  # camera X, Y, Z
    camera.matrix_world = Matrix.Translation(Vector(target - distance * forward)) @ basis.to_4x4()
    return distance


def aim_light(light: bpy.types.Object, camera: bpy.types.Object) -> None:
    """A sun from above, behind and left of the camera, so the spheres show their shape."""
    m = np.array(camera.matrix_world, dtype=float)
    right, up, back = m[:3, 0], m[:3, 1], m[:3, 2]
    travel = -back * 1.0 - np.array((0.0, 0.0, 0.9)) + right * 0.5
    light.matrix_world = (Matrix.Translation(camera.matrix_world.translation)
                          @ Vector(travel).to_track_quat("-Z", "Y").to_matrix().to_4x4())
    sun = light.data
    sun.energy = 2.0
    sun.angle = math.radians(8.0)
    sun.color = (1.0, 0.98, 0.95)
