"""How results are written: the printed result (run_text), the output
writers (writers), a rendered PNG, a movie, a coarse-grained PDB, and the dressing (materials,
camera, light) that a saved .blend and a render share."""
