"""The same model stepped in raw Bullet (pybullet), outside Blender: the floor for a bake's cost.

    python bench/baselines/bullet_peer.py LAYERS LINKER SEED
Steps 250 frames x 10 substeps at time scale 2 (Blender's defaults for the tutorial's bake) and
prints: bake=<s> bodies=<n> constraints=<n> clash_pairs=<n>
"""
import math
import random
import sys
import time

import pybullet as p

args = [a for a in sys.argv[1:] if a != "--"]
layers = int(args[0]) if args else 20
linker = int(args[1]) if len(args) > 1 else 6
seed = int(args[2]) if len(args) > 2 else 0
R, r, rise, twist = 15.0, 1.75, 4.8, 0.034

p.connect(p.DIRECT)
random.seed(seed)
p.setGravity(*[random.uniform(-0.5, 0.5) for _ in range(3)])
box = p.createCollisionShape(p.GEOM_BOX, halfExtents=[20, 11, 2.4])
small = p.createCollisionShape(p.GEOM_SPHERE, radius=r)
big = p.createCollisionShape(p.GEOM_SPHERE, radius=R)
globules, constraints = [], 0
for k in range(layers):
    a = twist * k
    c, s = math.cos(a), math.sin(a)
    orn = p.getQuaternionFromEuler([0, 0, a])
    place = lambda x: [c * x, s * x, rise * k]
    p.createMultiBody(0, box, basePosition=[0, 0, rise * k], baseOrientation=orn)
    chain = [p.createMultiBody(0, small, basePosition=place(21.75))]
    for i in range(1, linker):
        chain.append(p.createMultiBody(1, small, basePosition=place(21.75 + 3.5 * i)))
    chain.append(p.createMultiBody(1, big, basePosition=place(21.75 + 3.5 * (linker - 1) + r + R)))
    globules.append(chain[-1])
    for a_id, b_id in zip(chain, chain[1:]):
        pa = p.getBasePositionAndOrientation(a_id)[0]
        pb = p.getBasePositionAndOrientation(b_id)[0]
        mid = [(u + v) / 2 for u, v in zip(pa, pb)]
        p.createConstraint(a_id, -1, b_id, -1, p.JOINT_POINT2POINT, [0, 0, 0],
                           [m - u for m, u in zip(mid, pa)], [m - v for m, v in zip(mid, pb)])
        p.setCollisionFilterPair(a_id, b_id, -1, -1, 0)
        constraints += 1
p.setPhysicsEngineParameter(fixedTimeStep=2.0 / 24 / 10, numSolverIterations=10)
t = time.perf_counter()
for _ in range(250 * 10):
    p.stepSimulation()
bake = time.perf_counter() - t
pos = [p.getBasePositionAndOrientation(g)[0] for g in globules]
clash = sum(1 for i in range(len(pos)) for j in range(i + 1, len(pos)) if math.dist(pos[i], pos[j]) < 2 * R - 1e-3)
print(f"bake={bake:.3f} bodies={p.getNumBodies()} constraints={constraints} clash_pairs={clash}")
