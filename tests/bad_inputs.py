"""One table of bad inputs, tested through the CLI, the Python API and the operators.

Each row: CLI arguments, the same input as API keyword arguments, and the parameter the one-line
error must name.
"""
import math

BAD_INPUTS = [
    # sizes: zero, negative, NaN, infinite
    (["--slab", "0", "22", "4.8"], {"slab": (0, 22, 4.8)}, "slab"),
    (["--slab", "40", "-22", "4.8"], {"slab": (40, -22, 4.8)}, "slab"),
    (["--slab", "40", "22", "nan"], {"slab": (40, 22, math.nan)}, "slab"),
    (["--globule-diameter", "0"], {"globule_diameter": 0}, "globule_diameter"),
    (["--globule-diameter", "-30"], {"globule_diameter": -30}, "globule_diameter"),
    (["--globule-diameter", "nan"], {"globule_diameter": math.nan}, "globule_diameter"),
    (["--globule-diameter", "inf"], {"globule_diameter": math.inf}, "globule_diameter"),
    (["--residue-radius", "-1.75"], {"residue_radius": -1.75}, "residue_radius"),
    (["--rise", "0"], {"rise": 0}, "rise"),
    (["--rise", "inf"], {"rise": math.inf}, "rise"),
    # counts of 0
    (["--linker", "0"], {"linker": 0}, "linker"),
    (["--layers", "0"], {"layers": 0}, "layers"),
    # non-numeric
    (["--layers", "twenty"], {"layers": "twenty"}, "layers"),
    (["--twist", "2turns"], {"twist": "2turns"}, "twist"),  # (2deg is an angle: issue #23)
    (["--twist", "-0.961"], {"twist": "-0.961"}, "twist"),  # degrees typed as radians
    (["--linker", "2.5"], {"linker": 2.5}, "linker"),
    # frames, gravity
    (["--frames", "0"], {"frames": 0}, "frames"),
    (["--gravity", "-0.5"], {"gravity": -0.5}, "gravity"),
    # too many layers without --force
    (["--layers", "20000"], {"layers": 20000}, "layers"),
]
