"""bullet_peer.py with plain rigid bodies: the tighter floor for the bake's cost.

    python bench/bullet_rigid_peer.py PATH/TO/bullet_peer.py LAYERS LINKER SEED

The shared bullet_peer.py builds Featherstone multibodies (`createMultiBody` without
useMaximalCoordinates), which cost more per step than the btRigidBody bodies and
btPoint2PointConstraints of Blender's btDiscreteDynamicsWorld. This runs the same script, same
model and steps, with every body made as a maximal-coordinates rigid body, without copying it.
"""
import functools
import runpy
import sys

import pybullet

pybullet.createMultiBody = functools.partial(pybullet.createMultiBody, useMaximalCoordinates=True)
peer, sys.argv = sys.argv[1], sys.argv[1:]
runpy.run_path(peer, run_name="__main__")
