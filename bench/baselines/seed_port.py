"""The seed tutorial's procedure, ported operator-for-operator to Blender 4.2+/5.0,
as the performance baseline (what a user of the tutorial runs today).

    python bench/baselines/seed_port.py LAYERS LINKER SEED      (with the bpy module)
Prints one line: build=<s> bake=<s> check=<s> verdict=<intersection|successful>
"""
import math
import random
import sys
import time

import bpy  # first: it makes bmesh and mathutils importable
import bmesh
from mathutils.bvhtree import BVHTree

args = [a for a in sys.argv[1:] if a != "--"]
layer = int(args[0]) if args else 20
len_of_linker = int(args[1]) if len(args) > 1 else 6
seed = int(args[2]) if len(args) > 2 else 0

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
t0 = time.perf_counter()

# 1. slab
bpy.ops.mesh.primitive_cube_add(size=2, location=(0.0, 0.0, 0.0))
bpy.ops.transform.resize(value=(20.0, 11.0, 2.4))
bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
bpy.ops.rigidbody.object_add(type="PASSIVE")
bpy.context.object.rigid_body.collision_shape = "BOX"
# 2. anchor
bpy.ops.mesh.primitive_uv_sphere_add(segments=4, ring_count=4, radius=1.75, location=(21.75, 0.0, 0.0))
bpy.ops.rigidbody.object_add(type="PASSIVE")
bpy.context.object.rigid_body.collision_shape = "SPHERE"
# 3. linker
loc_sphere_x = 21.75
rep = -1
for index in range(len_of_linker - 1):
    rep += 1
    loc_sphere_x += 3.5
    bpy.ops.mesh.primitive_uv_sphere_add(segments=4, ring_count=4, radius=1.75, location=(loc_sphere_x, 0.0, 0.0))
    bpy.ops.rigidbody.object_add(type="ACTIVE")
    bpy.context.object.rigid_body.collision_shape = "SPHERE"
    bpy.ops.object.constraint_add(type="LIMIT_DISTANCE")
    bpy.context.object.constraints["Limit Distance"].target = (
        bpy.data.objects["Sphere"] if rep == 0 else bpy.data.objects["Sphere." + str(rep).rjust(3, "0")])
# 4. globule
radius = 30 / 2
bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=radius, location=(loc_sphere_x + 1.75 + radius, 0.0, 0.0))
bpy.ops.rigidbody.object_add(type="ACTIVE")
bpy.context.object.rigid_body.collision_shape = "SPHERE"
globula = bpy.data.collections.new("globula")
scene.collection.children.link(globula)
globula.objects.link(bpy.context.object)
bpy.ops.object.constraint_add(type="LIMIT_DISTANCE")
rep += 1 if len_of_linker == 1 else 0
bpy.context.object.constraints["Limit Distance"].target = (
    bpy.data.objects["Sphere"] if rep <= 0 else bpy.data.objects["Sphere." + str(rep).rjust(3, "0")])
# 5. point constraints
loc_empty_x = 18.25
for i in range(len_of_linker):
    loc_empty_x += 3.5
    bpy.ops.object.empty_add(type="PLAIN_AXES", location=(loc_empty_x, 0.0, 0.0))
    bpy.ops.rigidbody.constraint_add(type="POINT")
    rbc = bpy.context.object.rigid_body_constraint
    rbc.object1 = bpy.data.objects["Sphere" if i == 0 else "Sphere." + str(i).rjust(3, "0")]
    rbc.object2 = bpy.data.objects["Sphere." + str(i + 1).rjust(3, "0")]
# 6. layers: duplicate, raise 4.8, rotate 0.034 rad about the fibril axis (cursor at origin)
scene.frame_current = 1
scene.tool_settings.transform_pivot_point = "CURSOR"
bpy.ops.object.select_all(action="SELECT")
for _ in range(layer - 1):
    bpy.ops.object.duplicate_move()
    bpy.ops.transform.translate(value=(0, 0, 4.8), constraint_axis=(False, False, True))
    bpy.ops.transform.rotate(value=0.034, orient_axis="Z", center_override=(0.0, 0.0, 0.0))
t1 = time.perf_counter()
# 7. bake with random gravity
random.seed(seed)
scene.gravity = (random.uniform(-0.5, 0.5), random.uniform(-0.5, 0.5), random.uniform(-0.5, 0.5))
scene.rigidbody_world.time_scale = 2.0
scene.rigidbody_world.point_cache.frame_end = 251
bpy.ops.ptcache.free_bake_all()
bpy.ops.ptcache.bake_all(bake=True)
t2 = time.perf_counter()
# 8. join globules at the last frame, BVH self-overlap
scene.frame_set(251)
dg = bpy.context.evaluated_depsgraph_get()
bm = bmesh.new()
for ob in globula.all_objects:
    me = ob.evaluated_get(dg).to_mesh()
    me.transform(ob.evaluated_get(dg).matrix_world)
    bm.from_mesh(me)
    ob.evaluated_get(dg).to_mesh_clear()
tree = BVHTree.FromBMesh(bm, epsilon=0.00001)
faces_error = {i for pair in tree.overlap(tree) for i in pair}
t3 = time.perf_counter()
print(f"build={t1-t0:.3f} bake={t2-t1:.3f} check={t3-t2:.3f} globules={len(globula.all_objects)} "
      f"objects={len(bpy.data.objects)} verdict={'intersection' if faces_error else 'successful'}")
