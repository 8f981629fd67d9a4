"""Domains as they are (issue #24) in a run: the linker from numbering, several domains."""
import json

import gemmi
import numpy as np
import pytest
from helpers import ROOT

DATA = ROOT / "tests" / "data"
FAST = ["--layers", "3", "--frames", "10"]


def renumbered(tmp_path, shift: int):
    st = gemmi.read_structure(str(DATA / "1ubq.pdb.gz"))
    for ch in st[0]:
        for res in ch:
            res.seqid.num += shift
    out = tmp_path / f"ubq{shift}.pdb"
    st.write_pdb(str(out))
    return out


def test_the_run_takes_the_linker_from_numbering_and_says_so(ff, scene, tmp_path):
    dom, out = renumbered(tmp_path, 127), tmp_path / "r.json"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        *FAST, "--stop-after", "build", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 31 and r["structure"]["applied"]["linker"] == 31
    assert r["structure"]["sources"]["linker"].startswith("numbering: 30 residues between")
    # an explicit --linker wins, and the source says so
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        *FAST, "--linker", "5", "--stop-after", "build", "--json",
                        str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 5 and "linker" in r["structure"]["overridden"]
    assert r["structure"]["sources"]["linker"].startswith("the --linker option")


def test_inspect_says_where_the_linker_comes_from(ff, tmp_path, capsys):
    dom, out = renumbered(tmp_path, 127), tmp_path / "i.json"
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        "--json", str(out)]) == 0
    assert "linker: numbering: 30 residues between LYS97" in capsys.readouterr().out
    data = json.loads(out.read_text())
    assert data["model_values"]["linker"] == 31 and "numbering" in data["sources"]["linker"]


def test_a_full_length_model_gives_the_domain_and_its_linker(ff, scene, tmp_path, capsys):
    from helpers import synthetic_full_length
    fl, js = synthetic_full_length(tmp_path), tmp_path / "i.json"
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length",
                        str(fl), "--json", str(js)]) == 0
    data = json.loads(js.read_text())
    assert [(d["first"], d["last"]) for d in data["domains"]] == [(128, 203)]
    assert data["linkers"] == [{"first": 98, "last": 127, "length": 30,
                                "between": ["core 38-97", "domain 128-203"]}]
    assert "linker 98-127: 30 residues" in capsys.readouterr().out
    out, cif = tmp_path / "r.json", tmp_path / "r.cif"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length", str(fl),
                        *FAST, "--stop-after", "build", "--json", str(out), "--pdb-atoms",
                        str(cif)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 31  # 30 residues between K97 and 128, plus the anchor
    assert r["params"]["globule_diameter"] == 30.276  # ubiquitin's own coordinates
    assert r["structure"]["full_length"]["domains"][0]["first"] == 128
    st = gemmi.read_structure(str(cif))
    dom = st[0]["0A1"]
    assert (dom[0].seqid.num, dom[len(dom) - 1].seqid.num) == (128, 203)
    core = st[0]["0A"]  # the beads continue the numbering up to the domain
    assert core[len(core) - 1].seqid.num == 127


def test_bad_full_length_models_are_refused_in_one_line(ff, scene, tmp_path, capsys):
    from helpers import synthetic_full_length
    for bad, words in ((synthetic_full_length(tmp_path, flat=True, name="flat.pdb"),
                        "no pLDDT"),
                       (synthetic_full_length(tmp_path, shift=500, name="far.pdb"),
                        "do not cover the fibril's core 38-97")):
        out = tmp_path / "r.json"
        assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length",
                            str(bad), *FAST, "--json", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("fibrilfit: error: --full-length: ")
        assert words in err[0] and not out.exists()


# A TDP-43-like chain: the core, 50 residues to RRM2, 23 to RRM1, 24 to the NTD (the issue's
# numbers; spheres of given diameters: the repository has no TDP-43 domain files), two
# molecules per layer as in 8QX9 (examples/numbers/tdp43_8qx9.toml's geometry).
TDP43 = dict(protofilaments=2, slab=(56.5, 22.0, 4.78), rise=4.78, twist=-0.0309, layers=4,
             linker=51, globule_diameter=31.0, domain_diameters="31,30", domain_linker="23,24",
             frames=40)


def test_a_tdp43_like_chain_of_three_domains_builds_bakes_and_is_judged(ff, scene):
    P = ff.model.params
    p = P.make_params(**TDP43)
    assert [d.member for d in p.domains] == [51, 75, 100]
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    assert len(model.chain) == 8 and all(len(c) == 101 for c in model.chain)
    assert len(model.globules) == 24
    scales = [round(ob.scale[0], 4) for ob in model.globules[:3]]
    assert scales == [1.0, 1.0, round(30 / 31, 4)]
    # measured on bpy 4.2, 5.0 and 5.2: no clash, but a bond stretched 6.88 %, past the 5 %
    # tolerance (40 frames of the tutorial protocol: not a fit)
    assert r["verdict"] == "successful" and r["clashing_pairs"] == []
    assert r["linker_intact"] is False and r["accommodated"] is False
    assert [e["n"] for e in r["domain_envelopes"]] == [8, 8, 8]
    assert r["envelope"]["n"] == 24
    assert len(r["globule_centres"]) == 24 and r["checks_agree"]
    # the worst of the whole chain's bonds (100 a chain): measured 0.068846 on all three bpy
    assert r["max_bond_stretch"] == pytest.approx(0.0688, abs=0.002)
    # no two domains overlap deeper than the sphere check's tolerance unless it says so
    centres = np.array(r["globule_centres"])
    radii = np.tile([d.radius for d in p.domains], p.chains)
    d = np.linalg.norm(centres[:, None] - centres[None], axis=-1)
    depth = radii[:, None] + radii[None] - d
    np.fill_diagonal(depth, -np.inf)
    deep = {(int(i), int(j)) for i, j in zip(*np.nonzero(np.triu(depth > r["sphere_check"][
        "tolerance"])))}
    assert deep == {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}


def test_the_json_names_which_domain_of_which_chain_clashes(ff, scene):
    p = ff.model.params.make_params(layers=4, linker=2, globule_diameter=40,
                                    domain_diameters="40,40", domain_linker="1,1", frames=20)
    r = ff.pipeline.run_model(p, scene)
    assert r["verdict"] == "intersection" and r["clashing_domains"]
    assert len(r["clashing_domains"]) == len(r["clashing_pairs"])
    for (a, b, depth), (i, j, d) in zip(r["clashing_domains"], r["clashing_pairs"]):
        assert (a["chain"], a["domain"], b["chain"], b["domain"]) == (i // 3, i % 3, j // 3,
                                                                    j % 3)
        assert a["layer"] == a["chain"] and a["protofilament"] == 0 and depth == d
    assert ff.analysis.clashing_layers(r) == sorted(
        {k // 3 for i, j, _ in r["clashing_pairs"] for k in (i, j)})
    # two protofilaments: the chain blocks count chains, not globules
    p = ff.model.params.make_params(layers=3, protofilaments=2, linker=2, globule_diameter=40,
                                    domain_diameters="40,40", domain_linker="1,1", frames=10)
    r = ff.pipeline.run_model(p, scene)
    assert r["verdict"] == "intersection" and len(r["chain_clashes"]) == 6
    for (a, b, _), (la, lb, _) in zip(r["clashing_domains"], r["clashing_chains"]):
        assert la == [a["layer"], a["protofilament"]] and lb == [b["layer"], b["protofilament"]]


def test_a_domain_linker_count_that_does_not_match_is_refused(ff, scene, tmp_path, capsys):
    out = tmp_path / "r.json"
    for extra in (["--domain-diameters", "30,20", "--domain-linker", "5"],
                  ["--domain", str(DATA / "1ubq.pdb.gz"), "--domain", str(DATA / "1gfl.pdb.gz")],
                  ["--domain-diameters", "30", "--domain-linker", "5,5"]):
        assert ff.cli.main(["run", *FAST, *extra, "--json", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and not out.exists()
        assert err[0].startswith(("fibrilfit: error: domain_linker: needs one value per gap",
                                  "fibrilfit: error: domain_diameters: several domains"))


def test_several_domain_files_fill_the_chain(ff, scene, tmp_path):
    """--domain twice: diameters from the files; the gap from their numbering when it runs
    outward (ubiquitin 128-203, then ubiquitin again as 230-305: 26 residues between)."""
    near, far, out = renumbered(tmp_path, 127), renumbered(tmp_path, 229), tmp_path / "r.json"
    cif = tmp_path / "r.cif"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(near),
                        "--domain", str(far), *FAST, "--json", str(out), "--pdb-atoms",
                        str(cif)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 31 and r["params"]["domain_linker"] == [26]
    assert r["params"]["domain_diameters"] == [r["params"]["globule_diameter"]] == [30.276]
    assert len(r["structure"]["domains"]) == 2
    st = gemmi.read_structure(str(cif))
    chains = {ch.name: ch for ch in st[0]}
    assert {"0A", "0A1", "0A2", "0B2"} <= set(chains) and len(chains) == 3 * 3 * 2
    gap = chains["0A1"]  # domain 1, then its 26 beads numbered on to 229
    assert [r.seqid.num for r in gap][-27:] == [203] + list(range(204, 230))
    assert chains["0A2"][0].seqid.num == 230



def test_the_two_domain_full_length_model_runs(ff, scene, tmp_path):
    """docs/guide/atoms-and-domains.md#full-length-models' `run` on tests/full_length_model.py's
    chain (fast: 3 layers, 10 frames): ubiquitin 118-193 after 20 residues from K97 (linker 21
    with the anchor), GFP 209-438 after 15 more, each at its deposited size; built, baked and
    judged."""
    from full_length_model import two_domain_model
    model, out = two_domain_model(tmp_path / "two.pdb"), tmp_path / "r.json"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length",
                        str(model), *FAST, "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 21 and r["params"]["domain_linker"] == [15]
    assert r["params"]["globule_diameter"] == pytest.approx(30.28, abs=0.02)  # the first
    assert r["params"]["domain_diameters"] == pytest.approx([43.94], abs=0.02)  # the next
    assert [(d["first"], d["last"]) for d in r["structure"]["full_length"]["domains"]] == \
        [(118, 193), (209, 438)]
    # 10 frames judge it (measured 2026-11-27): clash-free, a linker still stretched 8.5 %
    assert r["frames_simulated"] == 10 and r["accommodated"] is False
    assert r["verdict"] == "successful" and r["clashing_pairs"] == [] and not r["linker_intact"]
    assert r["max_bond_stretch"] == pytest.approx(0.0851, abs=0.002)

# ---- several domains under inflate and in a periodic cell -----------------------------------
INFLATE = dict(protocol="inflate", grow_frames=15, hold_frames=15, regrow_cycles=1,
               near_cycles=0)


def _spheres_of_the_cell(p, centres, cells):
    """Independently of the check: every pair of the infinite fibril's globules (cell globules
    with cell globules or with images m = 1..cells above) overlapping by more than `tol`, with
    each globule's own domain radius; returns {(i, j): depth} over indices of cell + images."""
    import importlib
    helix = importlib.import_module("fibrilfit.model.helix")
    n = len(centres)
    blocks = [centres] + [helix.apply_points(p, np.full(n, float(m)), centres)
                          for m in range(1, cells + 1)]
    pts = np.concatenate(blocks)
    radii = np.tile([d.radius for d in p.domains], len(pts) // len(p.domains))
    d = np.linalg.norm(pts[:, None] - pts[None], axis=-1)
    depth = radii[:, None] + radii[None] - d
    return {(int(i), int(j)): float(depth[i, j]) for i, j in zip(*np.nonzero(depth > 0))
            if i < j and i < n}


def test_a_tdp43_like_chain_grows_each_domain_to_its_own_size_under_inflate(ff, scene):
    """Inflate scales every globule by the schedule's fraction of its OWN full size (the
    further domains share domain 1's mesh at their size / domain 1's), starts small enough that
    no two globules of any size overlap, and is judged as a single domain is."""
    import importlib
    growth = importlib.import_module("fibrilfit.builders.growth")
    p = ff.model.params.make_params(**{**TDP43, **INFLATE})
    model = ff.builders.build_model(p, scene)
    hook = growth.Inflate(model, scene)
    full = {51: 1.0, 75: 1.0, 100: 30 / 31}
    hook._set_scale(0.5)
    for ob in model.globules:
        assert ob.scale[:] == pytest.approx([0.5 * full[ob["fibrilfit_index"]]] * 3, abs=1e-6)
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    assert [round(ob.scale[0], 4) for ob in model.globules[:3]] == [1.0, 1.0, round(30 / 31, 4)]
    # measured on bpy 4.2, 5.0 and 5.2: inflate fits it (no clash, worst stretch 0.0008 %)
    assert r["inflate"]["cycles"] and r["verdict"] == "successful" and r["accommodated"]
    assert 0.01 <= r["inflate"]["start_scale"] <= p.grow_start
    assert [e["n"] for e in r["domain_envelopes"]] == [8, 8, 8] and r["checks_agree"]
    # at the start scale no two globules (each its own size) overlapped in the start layout
    start = ff.model.start_layout.rest_positions(p)
    start = ff.model.start_layout.inflate_layout(p, start, p.seed)[0]
    centres = start[:, [d.member for d in p.domains]].reshape(-1, 3)
    s = r["inflate"]["start_scale"]
    radii = np.tile([d.radius for d in p.domains], len(centres) // 3)
    gap = np.linalg.norm(centres[:, None] - centres[None], axis=-1) - s * (radii[:, None]
                                                                          + radii[None])
    np.fill_diagonal(gap, np.inf)
    assert gap.min() > 0
    # the verdict's sphere check is every pair of each domain's own radius
    mine = {k for k, d in _spheres_of_the_cell(p, np.array(r["globule_centres"]), 0).items()
            if d > r["sphere_check"]["tolerance"]}
    assert mine == {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}


def test_the_fallback_judge_counts_each_domain_with_its_own_radius(ff):
    import importlib
    growth = importlib.import_module("fibrilfit.builders.growth")
    p = ff.model.params.make_params(layers=3, linker=2, globule_diameter=20,
                                    domain_diameters="10", domain_linker="1")
    pos = ff.model.start_layout.rest_positions(p)  # 3 chains x [anchor, bead, g0, bead, g1]
    pos[:, 2] = [[0, 0, 0], [0, 0, 50], [0, 0, 200]]  # the big domains apart (z 0, 50, 200)
    pos[:, 4] = [[0, 0, 400], [0, 0, 500], [14, 0, 50]]  # small ones apart, but one 14 Å from
    # a big one: radii 10 + 5 = 15
    out = growth.sphere_judge(p, pos, slice(0, 3))
    assert out["clashing_pairs"] == 1 and out["max_overlap"] == pytest.approx(1.0)
    pos[2, 4] = [15.5, 0, 50]  # 15.5 Å: apart for 10 + 5, a clash for 10 + 10
    assert growth.sphere_judge(p, pos, slice(0, 3))["clashing_pairs"] == 0


# A short cell of the TDP-43-like chain (shorter linkers than the protein's, so that the images
# a chain of 100 residues can reach, ~55,000 at linkers 51/23/24, stay few for a fast test).
TDP43_CELL = {**TDP43, "layers": None, "periodic": "auto", "linker": 8, "domain_linker": "4,4",
              "frames": 20}


def _images_follow_with_their_scale(ff, model):
    """Every image carries its original's scale, and so its size (several domains share one
    mesh at their own scale). Where an image stands is not tested here: images follow their
    originals a frame behind (the bake's `image_lag`), and the check recomputes them from the
    originals. Returns the members imaged."""
    import importlib
    periodic = importlib.import_module("fibrilfit.builders.periodic")
    seen = set()
    for ob in periodic.image_collection(model).objects:
        c, i, m = ob[periodic.CHAIN], ob["fibrilfit_index"], ob[periodic.CELL]
        src = model.chain[c][i]
        assert ob.scale[:] == pytest.approx(src.scale[:], abs=1e-6), (c, i, m)
        assert np.array(ob.matrix_world.to_scale()) == pytest.approx(src.scale[:], abs=1e-5)
        seen.add(i)
    return seen


def test_a_tdp43_like_chain_in_a_periodic_cell_images_every_member(ff, scene):
    p = ff.model.params.make_params(**{k: v for k, v in TDP43_CELL.items() if v is not None})
    assert p.periodic == 13 and [d.member for d in p.domains] == [8, 13, 18]  # ceil(2 · 31 / 4.78)
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    # images of every member kind: beads, each domain, each at its original's scale
    seen = _images_follow_with_their_scale(ff, model)
    assert {8, 13, 18} <= seen and set(range(1, 19)) - {8, 13, 18} <= seen
    # linker 8 and 4, 4 on a 13-layer cell jam (measured on bpy 4.2, 5.0 and 5.2: 487 faces,
    # 41 pairs, 16 by the spheres; worst stretch 297 %)
    assert r["periodic"]["images"]["moving"] > 0 and r["verdict"] == "intersection"
    assert r["sphere_check"]["clashing_pairs"] and r["accommodated"] is False
    assert [e["n"] for e in r["domain_envelopes"]] == [26, 26, 26] and r["checks_agree"]
    mine = {k for k, d in _spheres_of_the_cell(p, np.array(r["globule_centres"]),
                                               r["periodic"]["check_cells"]).items()
            if d > r["sphere_check"]["tolerance"]}
    assert mine == {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}


@pytest.mark.parametrize("protocol", ["tutorial", "inflate"])
def test_contacts_with_images_of_further_domains_are_counted_and_named(ff, scene, protocol):
    """Crowded short chains (20, 12 and 20 Å domains 1 residue apart) in a cell: the check
    counts pairs with the images above the cell, each of its own size, and names an image's
    layer in the infinite fibril (its layer + m · M)."""
    extra = INFLATE if protocol == "inflate" else {"frames": 10}
    p = ff.model.params.make_params(linker=2, globule_diameter=20, domain_diameters="12,20",
                                    domain_linker="1,1", periodic="auto", **extra)
    r = ff.pipeline.run_model(p, scene)
    model = ff.pipeline.current_model(scene)
    _images_follow_with_their_scale(ff, model)
    n = len(r["globule_centres"])
    assert n == 3 * p.chains and r["verdict"] == "intersection" and r["checks_agree"]
    across = [(i, j) for i, j, _ in r["clashing_pairs"] if j >= n]
    mine = _spheres_of_the_cell(p, np.array(r["globule_centres"]), r["periodic"]["check_cells"])
    deep = {k for k, d in mine.items() if d > r["sphere_check"]["tolerance"]}
    assert deep == {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}
    assert any(j >= n for i, j in deep) and across  # the cell's ends do meet
    for (a, b, _), (i, j, _) in zip(r["clashing_domains"], r["clashing_pairs"]):
        for name, g in ((a, i), (b, j)):
            assert name["chain"] == g % n // 3 and name["domain"] == g % 3
            assert name["layer"] == g % n // 3 + g // n * p.layers


def test_inspect_gives_both_linker_points_of_a_domain_with_a_next_one(ff, tmp_path, capsys):
    """Two domains on a chain (ubiquitin 128-203, then 230-305): domain 1's incoming linker
    joins at its first residue's CA, the outgoing one leaves from its last (the domain follows
    the core); inspect reports both points' depths and where they are, checked here against
    the file read directly. The outermost domain has no outgoing point."""
    near, far, js = renumbered(tmp_path, 127), renumbered(tmp_path, 229), tmp_path / "i.json"
    assert ff.cli.main(["inspect", "--domain", str(near), "--domain", str(far), "--json",
                        str(js)]) == 0
    text = capsys.readouterr().out
    first, second = json.loads(js.read_text())["domains_measured"]
    s = first["shape"]
    assert (s["joint_residue"], s["joint_terminus"], s["exit_residue"], s["exit_terminus"]) == (
        128, "N", 203, "C")
    assert "exit_residue" not in second["shape"] and second["shape"]["joint_residue"] == 230
    st = gemmi.read_structure(str(near))
    st.remove_hydrogens()
    chain = st[0][0]
    protein = [r for r in chain if gemmi.find_tabulated_residue(r.name).is_amino_acid()]
    heavy = np.array([a.pos.tolist() for r in protein for a in r])
    ca = {r.seqid.num: np.array(r["CA"][0].pos.tolist()) for r in protein}
    centroid = heavy.mean(axis=0)
    assert s["joint_distance"] == pytest.approx(np.linalg.norm(ca[128] - centroid), abs=0.01)
    assert s["exit_distance"] == pytest.approx(np.linalg.norm(ca[203] - centroid), abs=0.01)
    assert s["joint_exit_distance"] == pytest.approx(np.linalg.norm(ca[203] - ca[128]), abs=0.01)
    # a CA lies at least its own van der Waals radius (1.7 Å) below the grown hull
    assert s["exit_depth"] >= 1.7 - 0.01 and s["exit_depth_spheres"] > 0
    assert (f"exit: CA of residue 203 (the domain's other end, towards the next domain), "
            f"{s['exit_depth']:.2f} Å below the hull") in text


def test_real_shapes_of_several_domains_run_and_what_they_lack_is_refused_in_one_line(
        ff, scene, tmp_path, capsys):
    """Several domains with hull or spheres run from a file per domain (they were refused
    before: docs/guide/atoms-and-domains.md#shapes-of-several-domains); refused in one line:
    a further domain with no file to take its shape from, and no residue between two domains."""
    near, far, out = renumbered(tmp_path, 127), renumbered(tmp_path, 229), tmp_path / "r.json"
    for shape in ("hull", "spheres"):
        assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(near),
                            "--domain", str(far), "--domain-shape", shape, *FAST, "--linker", "6",
                            "--stop-after", "build", "--json", str(out)]) == 0
        r = json.loads(out.read_text())
        assert r["params"]["domain_linker"] == [26] and len(r["params"]["further_joints"]) == 1
        assert len(r["params"]["domain_exits"]) == 1
        assert r["sources"]["further_atoms"] == "ubq229.pdb: measured, hull atoms"
        assert r["sources"]["domain_exits"] == "ubq127.pdb: measured, the outgoing terminal CAs"
        out.unlink()
    for extra, message in (
            (["--domain", str(near), "--domain-diameters", "30", "--domain-linker", "4",
              "--domain-shape", "hull"],
             "domain_shape: hull with 2 domains per chain needs every domain's structure"),
            (["--domain", str(near), "--domain", str(far), "--domain-linker", "0",
              "--domain-shape", "hull"],
             "domain_linker: must be at least 1 residue between real-shaped domains"),
            # the covering spheres bulge past the atoms: one bead cannot hold them apart
            (["--domain", str(near), "--domain", str(far), "--domain-linker", "1",
              "--domain-shape", "spheres"],
             "domain_linker: 1 residue(s) between the domains cannot start the chain clear")):
        assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), *extra,
                            *FAST, "--json", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and not out.exists()
        assert err[0].startswith(f"fibrilfit: error: {message}"), err
