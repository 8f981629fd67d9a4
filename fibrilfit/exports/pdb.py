"""A coarse-grained PDB of the model for molecular viewers (PyMOL, ChimeraX, gemmi, Biopython).

One pseudo-atom (name CA, element C) per sphere: residue ANC (the anchor, resSeq 1), LNK (linker
residues, 2 .. linker) and GLB (the globule, linker + 1). The B-factor column holds the sphere's
radius in Å (PyMOL: `alter all, vdw=b`; ChimeraX: `size byattribute bfactor 0:0 1000:1000`).
One PDB chain per model chain, i.e. per molecule as in a deposited fibril: per layer, and per
protofilament within a layer (chain c = layer c // K, protofilament c % K; with one protofilament
a chain is a layer), chain 0 first: chain IDs A-Z, a-z, 0-9; past 62 chains the IDs repeat and
the segment ID (columns 73-76) tells the copies apart: chain = 62 * segment + index of the chain
ID, and residue numbers continue (segment 1 of a linker-3 model numbers its residues 5-8), so a
viewer that merges chains by ID still sees distinct residues (gemmi: split_chains_by_segments).
CONECT records join each chain in order; REMARK 250 lines carry the parameters, seed and verdict.

Several frames make a multi-model file (MODEL/ENDMDL), one model per frame, same atoms in each.
"""
from __future__ import annotations

import dataclasses

import string
import textwrap

import bpy
import numpy as np

from .. import files
from .mmcif import shown as _shown
from ..model import helix, hetero, occupancy
from ..model.chain import chain_members, chain_radii
from ..analysis.verdict import chain_positions
from ..builders.physics import keep_bake
from ..builders.scene import LAYER, PROTOFILAMENT

CHAIN_IDS = string.ascii_uppercase + string.ascii_lowercase + string.digits
KEYFRAME_STEP = 50   # the tutorial's bake_to_keyframes(frame_start=1, frame_end=251, step=50)
COORD_MIN, COORD_MAX = -999.999, 9999.999  # what PDB's 8.3f columns hold
REMARK = "REMARK 250"


class PdbError(ValueError):
    """The model cannot be written as a PDB (e.g. coordinates beyond the format's columns)."""


def chain_label(layer: int, layers: int) -> tuple[str, str]:
    """(chain ID, segment ID) of a layer. The segment ID is blank up to 62 layers."""
    chain = CHAIN_IDS[layer % len(CHAIN_IDS)]
    segment = str(layer // len(CHAIN_IDS)) if layers > len(CHAIN_IDS) else ""
    if len(segment) > 4:
        raise PdbError(f"layer {layer} needs a segment ID longer than PDB's 4 columns")
    return chain, segment


def keyframes(last: int, step: int = KEYFRAME_STEP) -> list[int]:
    """The frames of `--pdb-frames all`: 1, 1 + step, ... as the tutorial keyframes them, and
    always the last baked frame (the one the verdict is about)."""
    frames = list(range(1, int(last) + 1, step))
    if not frames or frames[-1] != last:
        frames.append(int(last))
    return frames


def hybrid36(value: int, width: int = 5) -> str:
    """PDB serial (width 5) and residue (width 4) numbers: decimal while they fit, then
    hybrid-36 (A0000 ...), which gemmi, PyMOL and ChimeraX read."""
    if value < 10 ** width:
        return f"{value:>{width}d}"
    digits = string.digits + string.ascii_uppercase
    value -= 10 ** width
    value += 10 * 36 ** (width - 1)
    if value >= 36 ** width:
        raise PdbError(f"number too large for {width} hybrid-36 PDB columns")
    out = ""
    for _ in range(width):
        value, d = divmod(value, 36)
        out = digits[d] + out
    return out


def residue_names(p) -> list[str]:
    """ANC, LNK ..., GLB per chain member (several domains: GLB at each globule)."""
    globules = {d.member for d in p.domains}
    return ["ANC"] + ["GLB" if i in globules else "LNK" for i in range(1, chain_members(p))]


def pdb_text(p, models: list[tuple[int, np.ndarray]], remarks: list[str] = ()) -> str:
    """The PDB file for parameters `p` and [(frame, positions (chains, linker + 1, 3))]."""
    # "layers": PDB chains, one per chain of the model (a mixed fibril: its decorated ones)
    layers = len(models[0][1]) if models else p.chains
    members = chain_members(p)
    names = residue_names(p)
    radii = np.tile(chain_radii(p), (layers, 1))
    if occupancy.is_hetero(p) and layers == len(hetero.b_chains(p)):  # each chain's own globule
        radii[:, p.domains[0].member] = hetero.globule_radii_by_chain(p)
    labels = [chain_label(k, layers) for k in range(layers)]
    pfs = (f" X {p.protofilaments} PROTOFILAMENTS" if p.protofilaments > 1 else "")
    lines = [f"TITLE     FIBRILFIT COARSE-GRAINED FIBRIL, {p.layers} LAYERS{pfs}, LINKER {p.linker}"]
    lines += [f"{REMARK} {part}" for text in remarks
              for part in textwrap.wrap(text, 80 - len(REMARK) - 1, break_long_words=True)]
    lines.append(f"{REMARK} frames: {', '.join(str(f) for f, _ in models)}")

    serial_of = np.zeros((layers, members), dtype=np.int64)
    serial = 0
    for k in range(layers):  # serials are the same in every model: TER takes one after a chain
        for i in range(members):
            serial += 1
            serial_of[k, i] = serial
        serial += 1

    multi = len(models) > 1
    for n, (frame, pos) in enumerate(models, start=1):
        pos = np.asarray(pos, dtype=float)
        if pos.shape != (layers, members, 3):
            raise PdbError(f"positions have shape {pos.shape}, expected {(layers, members, 3)}")
        if pos.min() < COORD_MIN or pos.max() > COORD_MAX:
            raise PdbError(f"frame {frame} has coordinates from {pos.min():.1f} to "
                           f"{pos.max():.1f} Å; PDB columns hold {COORD_MIN} to {COORD_MAX}")
        if multi:
            lines.append(f"MODEL     {n:>4}")
        for k in range(layers):
            chain, segment = labels[k]
            first = (k // len(CHAIN_IDS)) * members  # residue numbers continue past 62 layers
            for i in range(members):
                x, y, z = pos[k, i]
                lines.append(
                    f"ATOM  {hybrid36(int(serial_of[k, i]))}  CA  {names[i]} {chain}"
                    f"{hybrid36(first + i + 1, 4)}    {x:8.3f}{y:8.3f}{z:8.3f}{1.0:6.2f}"
                    f"{radii[k, i]:6.2f}      {segment:<4} C  ")
            lines.append(f"TER   {hybrid36(int(serial_of[k, -1]) + 1)}      {names[-1]} "
                         f"{chain}{hybrid36(first + members, 4)}")
        if multi:
            lines.append("ENDMDL")
    for k in range(layers):
        for i in range(members):
            bonded = [serial_of[k, j] for j in (i - 1, i + 1) if 0 <= j < members]
            lines.append("CONECT" + "".join(hybrid36(int(s)) for s in (serial_of[k, i], *bonded)))
    lines.append("END")
    return "\n".join(lines) + "\n"


def result_remarks(result: dict | None) -> list[str]:
    """REMARK text: versions, every parameter, seed, gravity and the verdict."""
    if not result:
        return []
    out = [f"FibrilFit {result.get('fibrilfit_version', '?')} on Blender "
           f"{result.get('blender_version', '?')}",
           "one pseudo-atom per sphere: ANC anchor, LNK linker residue, GLB globule",
           "B-factor = sphere radius (A); one chain per layer, layer 0 = chain A"
           if result.get("params", {}).get("protofilaments", 1) == 1 else
           "B-factor = sphere radius (A); one chain per molecule: chain n (A = 0) is layer "
           "n // K, protofilament n % K"]
    for name, value in result.get("params", {}).items():
        out.append(f"param {name} = {_shown(value)}")
    out.append(f"seed = {result.get('seed')}")
    if "gravity" in result:
        out.append("gravity = " + " ".join(f"{g:.6f}" for g in result["gravity"]))
    if "verdict" in result:
        out.append(f"verdict = {result['verdict']}; accommodated = {result['accommodated']}; "
                   f"max_bond_stretch = {result['max_bond_stretch']:.4f}")
        pairs = [f"{i}-{j}" for i, j, *_ in result.get("clashing_pairs", [])]
        what = "layer" if result.get("params", {}).get("protofilaments", 1) == 1 else "chain"
        out.append(f"clashing {what} pairs: " + (" ".join(pairs) or "none"))
    return out


def positions_at(scene: bpy.types.Scene, model, frames) -> list[tuple[int, np.ndarray]]:
    """Chain positions at each frame, read from the baked cache; the scene returns to the
    frame it was on."""
    now = scene.frame_current
    if list(frames) == [now]:
        return [(now, chain_positions(model))]
    keep_bake(scene)
    out = []
    try:
        for f in frames:
            scene.frame_set(int(f))
            out.append((int(f), chain_positions(model)))
    finally:
        scene.frame_set(now)
    return out


def chains_with_images(p, positions: np.ndarray, images: int) -> np.ndarray:
    """The cell's chain positions followed by their exact images S^m, cell by cell."""
    return np.concatenate([positions] + [helix.apply_points(p, m, positions)
                                         for m in helix.image_cells(images)])


def write_pdb(path, model, scene: bpy.types.Scene | None = None, *, frames=None,
              result: dict | None = None, images: int = 0) -> dict:
    """Write the model as a PDB to `path` (atomically). `frames`: frame numbers, or None for
    the current frame. `result`: the pipeline result, for the REMARK header. `images`: for a
    periodic cell, the images in that many cells below and above, as extra chains."""
    scene = scene or bpy.context.scene
    frames = [scene.frame_current] if frames is None else [int(f) for f in frames]
    models = positions_at(scene, model, frames)
    p, remarks = model.params, result_remarks(result)
    if len(model.chain) < p.chains:  # a mixed fibril: which subunits the chains are
        remarks.append(f"mixed fibril: {len(model.chain)} of {p.chains} subunits carry the "
                       f"domain; chains in order are (layer, protofilament) "
                       + ", ".join(f"({m[0][LAYER]}, {m[0].get(PROTOFILAMENT, 0)})"
                                   for m in model.chain))
    if p.periodic and images:
        n = len(model.chain)
        models = [(f, chains_with_images(p, pos, images)) for f, pos in models]
        remarks.append(f"periodic cell: chains 0-{n - 1} are the cell; then its images, "
                       f"{n} chains per cell, in cells "
                       + ", ".join(f"{m:+d}" for m in helix.image_cells(images))
                       + " (S^m: turn m*M*twist about Z, raise m*M*rise)")
        # PDB chains, one per chain of the cell and its images: layers × protofilaments
        p = dataclasses.replace(p, layers=len(models[0][1]) // p.protofilaments)
    text = pdb_text(p, models, remarks)
    files.write_text(path, text)
    return {"path": str(path), "frames": frames,
            "atoms_per_model": len(models[0][1]) * chain_members(p),
            **({"image_cells": helix.image_cells(images)}
               if model.params.periodic and images else {})}
