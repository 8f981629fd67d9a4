"""The parameters' field specs (how each is described, bounded and offered) and the constants
they name; ParamError. Plain Python: the bottom of the parameters' rooms (params.py builds the
Params class from these; param_values.py reads values; param_checks.py checks combinations).
"""
from __future__ import annotations

import math
from dataclasses import field

# Above this many objects a build is refused unless forced: past it a bake takes hours and
# the scene needs gigabytes.
MAX_OBJECTS_UNFORCED = 60_000
# Resident memory per object once built, evaluated and simulated for a frame: measured 31.6 KiB
# (bpy 5.0.1, 200 -> 2000 layers; only 3.8 KiB right after the build, before the depsgraph
# copies every object). `make bench`;
# docs/benchmarks.md#peak-memory-2000-layers-1139-mib-317-kib-per-object
MEMORY_PER_OBJECT_KIB = 32
GLOBULE_SEGMENTS, GLOBULE_RINGS = 32, 16
RESIDUE_SEGMENTS, RESIDUE_RINGS = 8, 4


class ParamError(ValueError):
    """A parameter value outside what the model accepts. `param` names the parameter."""

    def __init__(self, param: str, message: str):
        super().__init__(f"{param}: {message}")
        self.param = param


# Å: the range of a coordinate a parameter holds (the core's outline, the anchor, a shape's rows
# in its body frame), from the fibril axis or the body's centre
MAX_COORDINATE = 1000.0


def spec(default, lo, hi, unit, doc, *, kind=float, ui=True, cli=True, section="Simulation",
          derived=None, size=None, choices=None, item=None, label=None, shown_in=None,
          question=False):
    """`derived`: for a parameter whose default (None) is worked out from others, how (text).
    `size`: a fixed number of values (a vector); kind "points" is a list of [x, y].
    `choices`: kind str, one of these (CLI choices, the panel's enum).
    The sidebar: `label` its name where the field's name reads badly; `shown_in` a unit it is
    shown in instead of `unit` (a key of SHOWN_IN: "%" for a fraction the summary prints in per
    cent); `question` marks what the user asks about, shown at the top of the panel; `section`
    is also the build step that reads it (docs/guide/sidebar.md#the-panel)."""
    meta = {"min": lo, "max": hi, "unit": unit, "doc": doc, "kind": kind, "ui": ui, "cli": cli,
            "section": section, "derived": derived, "size": size, "label": label,
            "shown_in": shown_in, "question": question}
    if choices is not None:
        meta["choices"] = tuple(choices)
    if item is not None:  # kind "list": any number of values of this type, comma-separated
        meta["item"] = item
    return field(default=default, metadata=meta)


def rows_spec(doc, size, derived, section="Globule"):
    """A parameter of rows of `size` numbers in Å (a real shape's atoms, spheres or joints, an
    exit's path), measured from a structure file: not on the panel or the command line."""
    return spec(None, -MAX_COORDINATE, MAX_COORDINATE, "Å", doc, kind="rows", size=size,
                ui=False, cli=False, section=section, derived=derived)


# A unit a parameter is shown in on the panel: (from `unit`, factor). The stretch tolerance is a
# fraction in the definition and the CLI, a percentage in the summary and the verdict's line.
SHOWN_IN = {"%": ("fraction", 100.0)}

# Words that ask for a derived parameter's default (None), from the CLI, sweeps or JSON.
DERIVED_WORDS = ("auto", "default", "none", "box", "")
# Integer parameters that also take one word (the CLI, sweeps, JSON and case files): every
# layer scored (0), and a periodic cell as long as the geometry needs (helix.auto_cell_layers).
NUMBER_WORDS = {"score_layers": "all", "periodic": "auto"}
MAX_OUTLINE_POINTS = 10_000
PROTOCOLS = ("tutorial", "inflate")
# Angles (docs/guide/headless.md#angles): a bare number is radians; a value may name its unit.
ANGLE_UNITS = {"degrees": math.pi / 180, "degree": math.pi / 180, "deg": math.pi / 180,
               "°": math.pi / 180, "rad": 1.0}
# A twist beyond this per layer is refused without force: measured amyloid fibrils twist 0-8°
# per layer (the six fibrils of tests/data: 0.5-1.8°), so -0.961 is degrees typed as radians.
MAX_TWIST = 0.2
DOMAIN_SHAPES = ("sphere", "hull", "spheres")  # docs/model/domain-shapes.md#domain-shapes
MAX_SHAPE_ROWS = 5_000
# The parameters that carry the domains' real shapes, as rows of numbers
SHAPE_ROWS = ("domain_atoms", "domain_spheres", "domain_joint", "further_atoms",
              "further_spheres", "further_joints", "domain_exits")
# exit_residues of an anchor no clear path leaves within geom.exit_path.MAX_LENGTH: more than
# any linker (docs/model/buried-terminus.md#model)
SEALED = 1000
# Mixed fibrils (docs/model/occupancy.md#patterns): how the decorated subunits are chosen, and
# how a periodic pattern counts subunits (along each protofilament, or layer-major over all)
PATTERNS = ("random", "periodic", "layers")
PATTERN_COUNTS = ("protofilament", "fibril")
