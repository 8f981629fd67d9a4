"""How results are written: atomic file writes (files), the text summary (summary), the output
writers (writers), a rendered PNG, a movie, a coarse-grained PDB, and the dressing (materials,
camera, light) that a saved .blend and a render share."""
