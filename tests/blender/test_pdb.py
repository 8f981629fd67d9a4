"""The coarse-grained PDB: layout read back with gemmi, frames read from the bake, big models."""
import gemmi
import numpy as np
import pytest

from fibrilfit.model import params as P
from fibrilfit import pipeline
from fibrilfit.analysis.verdict import chain_positions as current_positions
from fibrilfit.model.start_layout import rest_positions
from fibrilfit.exports import pdb


def read(text: str, tmp_path) -> gemmi.Structure:
    path = tmp_path / "m.pdb"
    path.write_text(text)
    return gemmi.read_structure(str(path))


def atoms(model) -> list:
    return [(ch.name, res, a) for ch in model for res in ch for a in res]


def coords(model, shape) -> np.ndarray:
    return np.array([[a.pos.x, a.pos.y, a.pos.z] for _, _, a in atoms(model)]).reshape(shape)


def test_layout_names_chains_radii_and_bonds(tmp_path):
    p = P.make_params(layers=3, linker=3, globule_diameter=24)
    pos = rest_positions(p)
    st = read(pdb.pdb_text(p, [(1, pos)], ["seed = 5", "verdict = successful"]), tmp_path)
    assert len(st) == 1 and st[0].count_atom_sites() == 12
    assert [ch.name for ch in st[0]] == ["A", "B", "C"]
    for ch in st[0]:
        assert [r.name for r in ch] == ["ANC", "LNK", "LNK", "GLB"]
        assert [r.seqid.num for r in ch] == [1, 2, 3, 4]
        assert [r[0].b_iso for r in ch] == [1.75, 1.75, 1.75, 12.0]
        assert all(r[0].name == "CA" and r[0].element.name == "C" for r in ch)
    assert np.abs(coords(st[0], pos.shape) - pos).max() < 5e-4
    # CONECT joins consecutive spheres of one chain, never across chains (TER takes serial 5).
    assert dict(st.conect_map) == {1: [2], 2: [1, 3], 3: [2, 4], 4: [3], 6: [7], 7: [6, 8],
                                   8: [7, 9], 9: [8], 11: [12], 12: [11, 13], 13: [12, 14],
                                   14: [13]}
    remarks = "\n".join(st.raw_remarks)
    assert "seed = 5" in remarks and "verdict = successful" in remarks
    text = pdb.pdb_text(p, [(1, pos)])
    assert all(len(line) <= 80 for line in text.splitlines())


def test_result_remarks_carry_parameters_seed_and_verdict():
    r = {"fibrilfit_version": "0.1.0", "blender_version": "5.0.1",
         "params": P.make_params(layers=2).to_dict(), "seed": 4, "gravity": [0.1, -0.2, 0.3],
         "verdict": "intersection", "accommodated": False, "max_bond_stretch": 0.5,
         "clashing_pairs": [[0, 1, 2.5]]}
    text = "\n".join(pdb.result_remarks(r))
    for needle in ("Blender 5.0.1", "param layers = 2", "param slab = 40 22 4.8", "seed = 4",
                   "verdict = intersection", "clashing layer pairs: 0-1"):
        assert needle in text


def test_chain_labels_then_segments_past_62_layers(tmp_path):
    assert pdb.chain_label(0, 20) == ("A", "")
    assert [pdb.chain_label(k, 62)[0] for k in (25, 26, 51, 52, 61)] == ["Z", "a", "z", "0", "9"]
    assert pdb.chain_label(61, 130) == ("9", "0") and pdb.chain_label(62, 130) == ("A", "1")
    p = P.make_params(layers=130, linker=1)
    st = read(pdb.pdb_text(p, [(1, rest_positions(p))]), tmp_path)
    model = st[0]
    model.split_chains_by_segments(gemmi.HowToNameCopiedChain.AddNumber)
    assert len(model) == 130  # one chain per layer once segments split them
    for ch in model:
        layer = 62 * int(ch[0].segment) + pdb.CHAIN_IDS.index(ch.name[0])
        assert [r.name for r in ch] == ["ANC", "GLB"]
        assert abs(ch[0][0].pos.z - layer * p.rise) < 1e-3


def test_serials_past_99999_use_hybrid36(tmp_path):
    assert [pdb.hybrid36(n) for n in (1, 99999, 100000, 100001)] == [
        "    1", "99999", "A0000", "A0001"]
    assert pdb.hybrid36(9999, 4) == "9999" and pdb.hybrid36(10000, 4) == "A000"
    p = P.make_params(layers=500, linker=200, force=True)  # 100 500 atoms, never built
    st = read(pdb.pdb_text(p, [(1, rest_positions(p))]), tmp_path)
    assert st[0].count_atom_sites() == 100_500
    serials = sorted(a.serial for _, _, a in atoms(st[0]))
    assert serials[-1] == 100_500 + 499  # one TER serial after each of the 499 earlier chains
    assert len(set(serials)) == 100_500


def test_coordinates_beyond_pdb_columns_are_refused():
    p = P.make_params(layers=2, linker=1)
    pos = rest_positions(p)
    pos[1, 1, 0] = -1000.5
    with pytest.raises(pdb.PdbError, match="PDB columns"):
        pdb.pdb_text(p, [(1, pos)])


def test_keyframes_follow_the_tutorial_and_end_on_the_last_frame():
    assert pdb.keyframes(250) == [1, 51, 101, 151, 201, 250]
    assert pdb.keyframes(251) == [1, 51, 101, 151, 201, 251]
    assert pdb.keyframes(60) == [1, 51, 60] and pdb.keyframes(1) == [1]


def test_pdb_frames_are_the_baked_positions_and_the_bake_survives(scene, tmp_path):
    seen = {}
    p = P.make_params(layers=5, linker=3, seed=1, frames=110, settle=False)  # all 110 frames
    r = pipeline.run_model(p, scene,
                           on_frame=lambda f, pos: seen.__setitem__(f, pos.copy()) and False)
    model = pipeline.current_model(scene)
    final = current_positions(model)
    info = pdb.write_pdb(tmp_path / "all.pdb", model, scene, frames=pdb.keyframes(110), result=r)
    assert info["frames"] == [1, 51, 101, 110] and info["atoms_per_model"] == 20
    st = gemmi.read_structure(str(tmp_path / "all.pdb"))
    assert len(st) == 4
    for model_pdb, frame in zip(st, info["frames"]):
        assert model_pdb.count_atom_sites() == 20
        assert np.abs(coords(model_pdb, final.shape) - seen[frame]).max() < 1e-3, frame
    # All chain positions of the last model are the run's final ones, to 0.01 Å.
    last = coords(st[-1], final.shape)
    assert np.abs(last - final).max() < 0.01
    assert np.abs(last[:, -1] - np.array(r["globule_centres"])).max() < 0.01
    # Reading earlier frames left the scene on its last frame, with the bake intact.
    assert scene.frame_current == 110
    scene.frame_set(1)
    scene.frame_set(110)
    assert np.abs(current_positions(model) - final).max() < 1e-6


def test_two_protofilaments_give_one_chain_per_molecule(tmp_path, scene):
    """K = 2: chain n is layer n // 2, protofilament n % 2, as deposited fibrils name molecules;
    gemmi reads it back; the REMARKs carry the outline and say how chains map."""
    outline = [[-25, -11], [25, -11], [25, 11], [-25, 11]]
    p = P.make_params(layers=3, linker=3, protofilaments=2, pf_rotation=3.1294, pf_rise=2.34,
                      anchor=(26.75, 0), core_outline=outline, frames=3)
    result = pipeline.run_model(p, scene)
    path = tmp_path / "k2.pdb"
    from fibrilfit.exports import writers
    info = writers.write_pdb(scene, result, path)
    assert info["atoms_per_model"] == 6 * 4
    st = gemmi.read_structure(str(path))
    assert [ch.name for ch in st[0]] == ["A", "B", "C", "D", "E", "F"]
    pos = current_positions(pipeline.current_model(scene))
    assert np.abs(coords(st[0], pos.shape) - pos).max() < 5e-4
    remarks = "\n".join(st.raw_remarks)
    assert "layer n // K, protofilament n % K" in remarks and "param protofilaments = 2" in remarks
    assert "param core_outline = -25,-11 25,-11" in remarks.replace("\nREMARK 250 ", " ")
    assert "FIBRILFIT COARSE-GRAINED FIBRIL, 3 LAYERS X 2 PROTOFILAMENTS" in path.read_text()
