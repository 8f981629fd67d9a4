"""Outputs people look at: a rendered PNG, a coarse-grained PDB, and the dressing (materials,
camera, light) that a saved .blend and a render share."""
