"""What a run writes and how its pictures look: the output plan and the render look, declared
once for `run`, `report`, the sidebar and the Python API (no bpy: the parser needs none).

    --json PATH  --blend PATH  --save-case FILE.toml  --envelope-plot PATH.png
    --pdb PATH [--pdb-frames last|all] [--pdb-images N]  --pdb-atoms PATH.cif [--pdb-assembly N]
    --render PATH.png [--render-size WxH] [--render-samples N] [--render-engine cycles|workbench]
    --movie PATH.mp4|PATH.gif [--movie-step K]
"""
from __future__ import annotations

import dataclasses
import re

from ..exits import UsageError
from ..plans import Plan, PlanError, option

MOVIE_FORMATS = (".mp4", ".gif")
ENGINES = ("cycles", "workbench")     # exports.render.ENGINES, without importing bpy
SIZE_RANGE, SAMPLES_RANGE = (16, 8192), (1, 4096)
DEFAULT_SIZE, DEFAULT_SAMPLES = "640x360", 8
PDB_STEP = 50                        # exports.pdb.KEYFRAME_STEP
MOVIE_STEP, MOVIE_STEP_RANGE = 5, (1, 10000)
ASSEMBLY_CELLS_MAX = 500             # --pdb-assembly: 1001 operators, a viewer's whole fibril
# Why only a periodic cell has a helical assembly (--pdb-assembly, exports.mmcif.helical_assembly)
NOT_SCREW_SYMMETRIC = ("a fibril with ends is not screw-symmetric once baked: each layer's "
                       "domains settle on their own, so no part of it repeats to the whole")
PICTURES = "pictures and structures"
LOOK = "the report's picture"


class OptionError(UsageError):
    """A bad output request found by a writer; the message starts with the option's name."""


def _size(text: str) -> str | None:
    m = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", text)
    lo, hi = SIZE_RANGE
    if not m or not all(lo <= int(v) <= hi for v in m.groups()):
        return f"must be WIDTHxHEIGHT, each from {lo} to {hi} pixels (got {text!r})"
    return None


@dataclasses.dataclass(frozen=True)
class RenderLook(Plan):
    """How a picture is rendered (`run --render`, the report's picture)."""

    render_size: str = option(DEFAULT_SIZE, "picture size in pixels", metavar="WxH",
                              check=_size, group=LOOK, label="Size")
    render_samples: int = option(DEFAULT_SAMPLES, "Cycles samples per pixel, denoised",
                                 lo=SAMPLES_RANGE[0], hi=SAMPLES_RANGE[1], metavar="N",
                                 group=LOOK, label="Samples")
    render_engine: str = option("cycles", "cycles (CPU, any machine) or workbench (faster; "
                                          "needs a software or hardware OpenGL context)",
                                choices=ENGINES, group=LOOK, label="Engine")

    @property
    def size(self) -> tuple[int, int]:
        w, h = re.split(r"\s*[xX×]\s*", self.render_size.strip())
        return int(w), int(h)

    def look(self) -> dict:
        """What the writers take: size, aspect, samples, engine."""
        width, height = self.size
        return {"size": (width, height), "aspect": width / height,
                "samples": self.render_samples, "engine": self.render_engine}


@dataclasses.dataclass(frozen=True)
class OutputPlan(Plan):
    """The files one run writes (each optional; `json` '-' is standard output)."""

    json: str | None = option(None, "write the result as JSON ('-': to standard output, "
                                    "everything else then to standard error)", kind="path",
                              metavar="PATH", group=PICTURES)
    blend: str | None = option(None, "save the baked model (cache included)", kind="path",
                               metavar="PATH", group=PICTURES)
    save_case: str | None = option(None, "write this run's case (every parameter, and the "
                                         "--case metadata)", kind="path", metavar="FILE.toml",
                                   group=PICTURES)
    envelope_plot: str | None = option(None, "draw the radial density of the domain centres "
                                             "(needs matplotlib)", kind="path",
                                       metavar="PATH.png", group=PICTURES)
    pdb: str | None = option(None, "write a coarse-grained PDB: one pseudo-atom per sphere, "
                                   "one chain per layer, radius in the B-factor", kind="path",
                             metavar="PATH", group=PICTURES)
    pdb_frames: str = option("last", f"'last': the final frame; 'all': a multi-model PDB with "
                                     f"frames 1, {1 + PDB_STEP}, {1 + 2 * PDB_STEP}, ... and the "
                                     f"last baked frame", choices=("last", "all"),
                             group=PICTURES)
    pdb_images: int = option(0, "with --periodic: add the cell's images in the N cells below "
                                "and above as extra chains, after the cell's own (0: the cell)",
                             lo=0, hi=10, unit="cells", metavar="N", group=PICTURES)
    pdb_atoms: str | None = option(None, "write the decorated fibril in atoms as mmCIF: the "
                                         "core's chains as deposited on the model's layers, "
                                         "each domain placed by its globule's final transform, "
                                         "linker beads as CA-only residues (needs --fibril "
                                         "and/or --domain)", kind="path", metavar="PATH.cif",
                                   group=PICTURES)
    pdb_assembly: int = option(0, "with --periodic and --pdb-atoms: add to the file a helical "
                                  "assembly for viewers to expand, the cell and its images in "
                                  "the N cells below and above (a flat pdbx_struct_oper_list, "
                                  "one screw operator per cell; 0: none)",
                               lo=0, hi=ASSEMBLY_CELLS_MAX, unit="cells", metavar="N",
                               group=PICTURES)
    render: str | None = option(None, "render the final frame to a PNG (clashing globules red)",
                                kind="path", metavar="PATH.png", group=PICTURES)
    movie: str | None = option(None, "render the bake as a movie (Workbench, --render-size; "
                                     "clashing globules red on the last frame, held for a "
                                     "second), with a progress bar on stderr", kind="path",
                               metavar="PATH.mp4|PATH.gif", group=PICTURES)
    movie_step: int = option(MOVIE_STEP, "put every K-th baked frame in the movie, and the last",
                             lo=MOVIE_STEP_RANGE[0], hi=MOVIE_STEP_RANGE[1], metavar="K",
                             group=PICTURES)

    def check(self) -> None:
        if self.pdb_images and not self.pdb:
            raise PlanError("pdb_images", "only with --pdb")
        if self.pdb_assembly and not self.pdb_atoms:
            raise PlanError("pdb_assembly", "only with --pdb-atoms")

    def paths(self) -> dict:
        """Output key -> path, for every file asked for."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                if f.metadata["kind"] == "path" and getattr(self, f.name)}

    def cells_for(self, p) -> dict:
        """pdb_images and pdb_assembly, checked against the model: only with --periodic."""
        why = {"pdb_images": "a fibril with ends has no images",
               "pdb_assembly": f"{NOT_SCREW_SYMMETRIC}; --pdb-atoms alone writes it whole"}
        for name, reason in why.items():
            if getattr(self, name) and not p.periodic:
                raise PlanError(name, f"only with --periodic ({reason})")
        return {name: getattr(self, name) for name in why}


def pdb_fits(p) -> None:
    """Refuse, before any work, a fibril taller than PDB's coordinate columns (9999.999 Å)."""
    top = ((p.layers - 1) * p.rise + max(0.0, float(p.pf_offsets()[1].max()))
           + p.globule_diameter + p.residue_radius)
    if p.layers > 1 and top > 9999.999:
        most = int((9999.999 - p.globule_diameter - p.residue_radius) // p.rise) + 1
        raise OptionError(f"--pdb: a {p.layers}-layer fibril is {top:.0f} Å tall; PDB "
                          f"coordinates stop at 9999.999 Å, so at most {most} layers")
