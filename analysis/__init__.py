"""Read the baked model and judge it: BVH and analytic clash checks, linker stretch, verdict."""
from .clashes import bvh_clashes, sphere_clashes
from .stretch import bond_stretch
from .verdict import check_model, clashing_layers

__all__ = ["bvh_clashes", "sphere_clashes", "bond_stretch", "check_model", "clashing_layers"]
