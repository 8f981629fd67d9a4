"""Every output of a run, in one table (OUTPUTS) that write_all walks after the run.

A failure of a picture or structure writer is reported and never costs the run's other outputs.
The result JSON is written once after the quick writers and rewritten once after each slow one
(render, movie), so whatever stops a slow writer leaves a JSON that says what was written.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import bpy

from ..analysis import clash_kinds
from ..builders import find_model, keep_bake
from ..model import cases
from .. import files
from . import dressing, envelope_plot, mmcif, movie, pdb, render
from .plans import MOVIE_FORMATS


def prepare(scene: bpy.types.Scene, result: dict, *, aspect: float = 16 / 9) -> None:
    """Colour clashing globules and add materials, camera and light (for --blend and
    --render)."""
    model = find_model(scene)
    if model is not None:
        deep, grazing = clash_kinds(result)
        dressing.dress(scene, model, deep, aspect=aspect, grazing=grazing)


def write_pdb(scene: bpy.types.Scene, result: dict, path, frames: str = "last",
              images: int = 0) -> dict:
    """--pdb: the last baked frame, or with frames='all' the tutorial's keyframes too."""
    model = find_model(scene)
    if model is None:
        raise pdb.PdbError(f"scene '{scene.name}' holds no FibrilFit model")
    last = int(result.get("frames_simulated") or scene.frame_current)
    wanted = pdb.keyframes(last) if frames == "all" else [last]
    return pdb.write_pdb(path, model, scene, frames=wanted, result=result, images=images)


def write_atoms(scene: bpy.types.Scene, result: dict, path, sources, assembly: int = 0) -> dict:
    """--pdb-atoms: the decorated fibril in atoms at the last baked frame (exports/mmcif.py);
    with `assembly` N (--pdb-assembly, a periodic cell) the cell and a helical assembly of it
    and its images in N cells below and above."""
    from ..analysis.verdict import chain_positions, world_matrices
    model = find_model(scene)
    if model is None:
        raise mmcif.AtomsError(f"scene '{scene.name}' holds no FibrilFit model")
    if sources is None:
        raise mmcif.AtomsError("no structure to place (give --fibril and/or --domain)")
    last = int(result.get("frames_simulated") or scene.frame_current)
    now = scene.frame_current
    if now != last:
        keep_bake(scene)
        scene.frame_set(last)
    try:
        members = [d.member for d in model.params.domains]
        positions = chain_positions(model)
        globules = [members_[i] for members_ in model.chain for i in members]
        mats = world_matrices(globules, model.root.children).reshape(
            len(model.chain), len(members), 4, 4)
    finally:
        if now != last:
            scene.frame_set(now)
    atoms = mmcif.decorated_atoms(model.params, positions, mats, sources, members)
    helical = mmcif.helical_assembly(model.params, assembly) if assembly else None
    info = mmcif.write(path, atoms, mmcif.header(result), helical)
    info["frame"] = last
    return info


def write_render(scene: bpy.types.Scene, result: dict, path, options: dict) -> dict:
    """--render: the final frame as a PNG, clashing globules red, grazing ones pale red, with
    a legend and a scale bar."""
    deep, grazing = clash_kinds(result)
    return render.render_png(scene, path, clashing=deep, grazing=grazing, result=result,
                             size=options["size"], samples=options["samples"],
                             engine=options["engine"])


def write_movie(scene: bpy.types.Scene, result: dict, path, **options) -> dict:
    """--movie: the bake, every k-th frame, clashing globules red at the end."""
    return movie.write_movie(scene, result, path, **options)


def export(result: dict, key: str, label: str, write, *args, **kwargs) -> str | None:
    """Run `write(*args)` and store what it returns (if anything) as result[key]. On any
    failure store {"error": message} instead and return "<label> failed: <message>"."""
    try:
        info = write(*args, **kwargs)
        if info is not None:
            result[key] = info
        return None
    except Exception as exc:  # noqa: BLE001 - reported; the run's other outputs still follow
        message = " ".join(str(exc).split()) or type(exc).__name__
        result[key] = {"error": message}
        return f"{label} failed: {message}"


def save_blend(path, scene: bpy.types.Scene | None = None) -> None:
    """--blend: the whole file with the bake kept, so it reopens ready to scrub."""
    keep_bake(scene or bpy.context.scene)  # a bake cancelled part-way is kept too
    with files.silenced_stdout():  # Blender's "Info: Saved copy as ..." (the printed result says it)
        files.atomic_write(path, lambda tmp: bpy.ops.wm.save_as_mainfile(
            filepath=str(tmp), copy=True, compress=True, check_existing=False))


@dataclass
class Job:
    """What the writers of one run need: the scene and result, the checked output paths by
    option (json, pdb, blend, ...), and the options of the pictures."""
    scene: bpy.types.Scene
    result: dict
    paths: dict
    look: dict = field(default_factory=dict)  # exports.plans.RenderLook.look
    pdb_frames: str = "last"
    pdb_images: int = 0
    pdb_assembly: int = 0                     # --pdb-assembly: cells below and above the cell
    movie_step: int = 1
    progress: bool = False
    case: dict | None = None                  # what --save-case writes
    atoms: object = None                      # structure.atoms.Sources, for --pdb-atoms


@dataclass(frozen=True)
class Output:
    """One output: the result key it stores under (and the option naming its file, --key), its
    label in a failure's message, the suffixes its file may end in (none: it writes no file of
    its own), when it is wanted, what writes it, whether it is slow (the JSON is rewritten after
    it) and whether a failure is only reported (guarded) or ends the command."""
    key: str
    label: str
    suffixes: tuple[str, ...]
    wanted: Callable[[Job], bool]
    write: Callable[[Job], dict | None]
    slow: bool = False
    guarded: bool = True


def _blend(job: Job) -> None:
    save_blend(job.paths["blend"])
    job.result["blend"] = str(job.paths["blend"])


def _asked(key: str) -> Callable[[Job], bool]:
    return lambda job: key in job.paths


OUTPUTS = (  # in the order they run: the slow ones last
    Output("dressing", "materials, camera and light", (),  # for --blend and --render; clashes red
           lambda j: bool(j.paths.keys() & {"blend", "render"}),
           lambda j: prepare(j.scene, j.result, aspect=j.look["aspect"])),
    Output("pdb", "--pdb", (".pdb",), _asked("pdb"), lambda j: write_pdb(
        j.scene, j.result, j.paths["pdb"], j.pdb_frames, j.pdb_images)),
    Output("pdb_atoms", "--pdb-atoms", mmcif.SUFFIXES, _asked("pdb_atoms"),
           lambda j: write_atoms(j.scene, j.result, j.paths["pdb_atoms"], j.atoms,
                                 j.pdb_assembly)),
    Output("blend", "--blend", (".blend",), _asked("blend"), _blend, guarded=False),
    Output("save_case", "--save-case", cases.SUFFIXES, _asked("save_case"),
           lambda j: cases.write(j.paths["save_case"], j.case) and None, guarded=False),
    Output("envelope_plot", "--envelope-plot", (".png",),
           lambda j: "envelope_plot" in j.paths and "envelope" in j.result,
           lambda j: envelope_plot.write(j.result, j.paths["envelope_plot"])),
    Output("render", "--render", (".png",), _asked("render"), lambda j: write_render(
        j.scene, j.result, j.paths["render"], j.look), slow=True),
    Output("movie", "--movie", MOVIE_FORMATS, _asked("movie"), lambda j: write_movie(
        j.scene, j.result, j.paths["movie"], step=j.movie_step, size=j.look["size"],
        progress=j.progress), slow=True),
)
BY_KEY = {out.key: out for out in OUTPUTS}
JSON_SUFFIXES = (".json",)  # --json: the result, which write_all writes itself
# The order the command line checks the output paths in, so that of two bad paths the one named
# is the one it always named (--json and --blend first, then the pictures and structures).
CHECK_ORDER = ("json", "blend", "pdb", "pdb_atoms", "render", "movie", "save_case", "envelope_plot")


def path_suffixes() -> dict[str, tuple[str, ...]]:
    """Every output option that names a file (key: suffixes), in CHECK_ORDER."""
    given = {"json": JSON_SUFFIXES, **{out.key: out.suffixes for out in OUTPUTS if out.suffixes}}
    return {key: given[key] for key in sorted(given, key=CHECK_ORDER.index)}


def write_all(job: Job, outputs=OUTPUTS) -> list[str]:
    """Write every wanted output of `outputs` in order, and the JSON (if asked for) once the
    quick ones are done and again after each slow one; return the failures' messages."""
    problems, json_written = [], False

    def write_json():  # `--json -` is written once, by the command, to standard output
        if "json" in job.paths and str(job.paths["json"]) != files.STDOUT:
            files.write_json(job.paths["json"], job.result)

    for out in outputs:
        if not out.wanted(job):
            continue
        if out.slow and not json_written:
            write_json()
            json_written = True
        if out.guarded:
            problems.append(export(job.result, out.key, out.label, out.write, job))
        else:
            out.write(job)
        if out.slow:
            write_json()
    if not json_written:
        write_json()
    return [p for p in problems if p]

