"""Read the baked model and judge it: BVH and analytic clash checks, linker stretch, verdict."""
from .clashes import bvh_clashes, grazing_depth
from .exact import sphere_clashes
from .stretch import StretchLog, bond_stretch
from .verdict import (check_model, clash_kinds, clashing_layers, scored_chains,
                      scored_range)

__all__ = ["bvh_clashes", "grazing_depth", "sphere_clashes", "StretchLog", "bond_stretch",
           "check_model", "clash_kinds", "clashing_layers", "scored_chains",
           "scored_range"]
