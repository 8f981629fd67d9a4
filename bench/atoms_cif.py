"""`--pdb-atoms` on a finished model: 100 layers × 2 protofilaments of GFP (1GFL) on 6CU7, about
400,000 atoms. Times the writer alone (reading the globules' matrices, placing the atoms, the
mmCIF through gemmi), not the build. Medians of --repeat.

    .venv/bin/python bench/atoms_cif.py [--repeat 5] [--layers 100]

Target (issue #24): under 10 s. docs/benchmarks.md#decorated-fibril-in-atoms-pdb-atoms
"""
import argparse
import pathlib
import statistics
import tempfile
import time

import bpy

from fibrilfit import pipeline
from fibrilfit.api.model import atom_sources, measured_values
from fibrilfit.exports import mmcif, writers
from fibrilfit.model import params as P
from fibrilfit.structure.request import StructureRequest

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--layers", type=int, default=100)
    a = ap.parse_args()
    request = StructureRequest(fibril=str(DATA / "6cu7.pdb.gz"), domain=str(DATA / "1gfl.pdb.gz"),
                               domain_chain="A")
    values, block, measured = measured_values(request, {"layers": a.layers})
    p = P.make_params(force=True, **values)
    sources = atom_sources(request, measured)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    result = {**pipeline.describe(p), "structure": block}
    pipeline.build(p, scene, force=True)
    times, split = [], []
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp, "fibril.cif")
        for _ in range(a.repeat):
            t = time.perf_counter()
            info = writers.write_atoms(scene, result, path, sources)
            times.append(time.perf_counter() - t)
        size = path.stat().st_size
        model = writers.find_model(scene)
        from fibrilfit.analysis.verdict import chain_positions, world_matrices
        members = [d.member for d in p.domains]
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            pos = chain_positions(model)
            mats = world_matrices([c[i] for c in model.chain for i in members]).reshape(
                len(model.chain), len(members), 4, 4)
            t1 = time.perf_counter()
            atoms = mmcif.decorated_atoms(p, pos, mats, sources, members)
            t2 = time.perf_counter()
            mmcif.write(path, atoms, mmcif.header(result))
            t3 = time.perf_counter()
            split.append((t1 - t0, t2 - t1, t3 - t2))
    med = statistics.median
    print(f"{p.layers} layers x {p.protofilaments} protofilaments: {info['atoms']:,} atoms, "
          f"{info['chains']} chains, {size / 1e6:.1f} MB")
    print(f"write_atoms, whole: median {med(times):.2f} s [{min(times):.2f}, {max(times):.2f}]")
    print("  read matrices {:.3f} s, place atoms {:.3f} s, mmCIF {:.3f} s (medians)".format(
        *(med(s[i] for s in split) for i in range(3))))


if __name__ == "__main__":
    main()
