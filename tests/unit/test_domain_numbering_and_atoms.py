"""Domains as they are (issue #24), the parts that need no bpy: the linker from the files'
numbering, the body frame, and the atoms of a decorated fibril (placed rigidly, read back)."""
import math

import gemmi  # requirements-dev installs it: missing, this fails (never skips)
import numpy as np
import pytest
from helpers import ROOT, synthetic_full_length

from fibrilfit import structure as S  # noqa: E402
from fibrilfit.model.chain import chain_radii, chain_x, rest_lengths  # noqa: E402
from fibrilfit.exports import mmcif  # noqa: E402
from fibrilfit.model import params as P  # noqa: E402
from fibrilfit.model.param_checks import estimated_objects  # noqa: E402
from fibrilfit.structure import atoms as A, mapping  # noqa: E402

DATA = ROOT / "tests" / "data"


def renumbered(tmp_path, name: str, shift: int):
    """1UBQ with every residue number shifted (a domain in another protein's numbering)."""
    st = gemmi.read_structure(str(DATA / "1ubq.pdb.gz"))
    for ch in st[0]:
        for res in ch:
            res.seqid.num += shift
    out = tmp_path / name
    st.write_pdb(str(out))
    return out


@pytest.fixture(scope="module")
def six():
    return S.measure_fibril(DATA / "6cu7.pdb.gz")


def test_the_linker_is_the_residues_between_anchor_and_domain(six, tmp_path):
    dom = S.measure_domain(renumbered(tmp_path, "d128.pdb", 127))  # residues 128-203
    assert six.anchors[0]["residue"] == 97 and dom.residues[0] == 128
    values = S.model_values(six, dom)
    assert values["linker"] == 31  # 98..127: 30 residues between, plus the anchor
    assert "30 residues between LYS97" in mapping.linker_source(six, dom, explicit=False)
    said = mapping.linker_source(six, dom, explicit=True)
    assert said.startswith("the --linker option") and "gives 31" in said


def test_numbering_that_does_not_follow_the_anchor_is_not_used(six):
    dom = S.measure_domain(DATA / "1ubq.pdb.gz")  # 1-76: before K97, not after it
    assert "linker" not in S.model_values(six, dom)
    assert "not from numbering" in mapping.linker_source(six, dom, explicit=False)
    # on the N side (anchor V38) the same domain precedes the core: 38 - 76 < 0, refused too
    n_side = S.measure_fibril(DATA / "6cu7.pdb.gz", terminus="N")
    assert n_side.anchors[0]["residue"] == 38 and "linker" not in S.model_values(n_side, dom)


def test_a_domain_before_an_n_terminal_anchor(tmp_path):
    fib = S.measure_fibril(DATA / "7ymn.pdb.gz", terminus="N")  # anchor 304
    dom = S.measure_domain(renumbered(tmp_path, "d200.pdb", 199))  # 200-275
    assert S.model_values(fib, dom)["linker"] == 304 - 275  # 276..303 between, plus the anchor


def test_the_body_frame_is_the_centroid_unrotated():
    xyz = np.random.default_rng(1).normal(size=(50, 3)) * 7 + [3, -2, 40]
    centroid, local = S.body_frame(xyz)  # the one rule, shared with --domain-shape
    assert np.allclose(centroid, xyz.mean(axis=0)) and np.allclose(local + centroid, xyz)
    ubq = A.domain_atoms(DATA / "1ubq.pdb.gz")
    assert np.allclose(ubq.xyz.mean(axis=0), 0, atol=1e-9)
    assert len(ubq) == S.measure_domain(DATA / "1ubq.pdb.gz").atoms


def _rotation(rng):
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def test_placed_domains_are_rigid_and_the_file_reads_back(six, tmp_path):
    p = P.make_params(layers=3, linker=4, **{
        k: v for k, v in S.model_values(six).items() if k not in ("linker",)})
    ubq = A.domain_atoms(DATA / "1ubq.pdb.gz")
    sources = A.sources(DATA / "6cu7.pdb.gz", six, [ubq])
    rng = np.random.default_rng(7)
    mats = np.zeros((p.chains, 4, 4))
    for c in range(p.chains):
        mats[c, :3, :3] = _rotation(rng) * (1 + 1e-7)  # float32-like noise is taken out
        mats[c, :3, 3] = rng.normal(size=3) * 50
        mats[c, 3, 3] = 1
    positions = rng.normal(size=(p.chains, p.linker + 1, 3))
    atoms = mmcif.decorated_atoms(p, positions, mats, sources)
    out = tmp_path / "d.cif"
    info = mmcif.write(out, atoms, mmcif.header({"params": p.to_dict(), "seed": 0}))
    st = gemmi.read_structure(str(out))
    assert len(st[0]) == info["chains"] == 2 * p.chains
    assert sum(1 for _ in st[0].all()) == info["atoms"]
    want = np.linalg.norm(ubq.xyz[:, None] - ubq.xyz[None], axis=-1)
    for c in range(p.chains):
        ch = st[0][mmcif.chain_name(c // 2, c % 2, 0)]
        xyz = np.array([a.pos.tolist() for r in ch for a in r])
        got = np.linalg.norm(xyz[:, None] - xyz[None], axis=-1)
        assert np.abs(got - want).max() < 0.005
        assert np.allclose(xyz.mean(axis=0), mats[c, :3, 3], atol=0.002)  # centroid at origin
    doc = gemmi.cif.read(str(out))
    assert doc[0].find_value("_struct.title").startswith("'FibrilFit decorated fibril")
    params = doc[0].get_mmcif_category("_fibrilfit_param.")
    assert dict(zip(params["name"], params["value"]))["linker"] == "4"
    assert math.isclose(float(dict(zip(params["name"], params["value"]))["rise"]), p.rise)


def test_a_full_length_model_is_cut_into_its_domain_and_linker(six, tmp_path):
    from fibrilfit.structure import full_length
    seg = full_length.segment(synthetic_full_length(tmp_path), six.core_residues)
    assert seg.core == [38, 97] and seg.residues == [1, 203]
    assert [(d["first"], d["last"]) for d in seg.domains] == [(128, 203)]  # the dip bridged
    assert seg.domains[0]["plddt_mean"] == pytest.approx((74 * 91 + 2 * 60) / 76, abs=0.01)
    ubq = S.measure_domain(DATA / "1ubq.pdb.gz")
    assert seg.domains[0]["diameter"] == pytest.approx(ubq.globule_diameter, abs=0.01)
    assert [(k["first"], k["last"], k["length"]) for k in seg.linkers] == [(98, 127, 30)]
    # without the fibril the confident core is a domain too (it is 60 residues)
    alone = full_length.segment(synthetic_full_length(tmp_path), None)
    assert [(d["first"], d["last"]) for d in alone.domains] == [(38, 97), (128, 203)]


def test_a_full_length_model_must_cover_the_core_and_carry_plddt(six, tmp_path):
    from fibrilfit.structure import full_length
    with pytest.raises(S.StructureError, match="--full-length: .*do not cover the fibril's "
                                               "core 38-97"):
        full_length.segment(synthetic_full_length(tmp_path, shift=500), six.core_residues)
    with pytest.raises(S.StructureError, match="--full-length: .*no pLDDT .*every B-factor "
                                               "is 50"):
        full_length.segment(synthetic_full_length(tmp_path, flat=True), six.core_residues)


def test_several_domains_in_the_one_parameter_definition():
    one = P.DEFAULTS
    (d,) = one.domains
    assert d.member == one.linker and d.radius == one.globule_radius
    assert chain_x(one) == [21.75, 25.25, 28.75, 32.25, 35.75, 39.25, 56.0]  # the tutorial's
    p = P.make_params(linker=4, globule_diameter=25, domain_diameters="30, 20",
                      domain_linker="3,2")
    assert p.domain_diameters == (30.0, 20.0) and p.domain_linker == (3, 2)
    assert [d.member for d in p.domains] == [4, 8, 11] and len(chain_radii(p)) == 12
    assert chain_radii(p)[4] == 12.5 and chain_radii(p)[8] == 15.0 and chain_radii(p)[11] == 10
    # beads 3.5 Å apart, a globule touching its neighbours
    assert np.allclose(rest_lengths(p), [3.5, 3.5, 3.5, 14.25, 14.25, 3.5, 3.5, 16.75, 16.75,
                                          3.5, 11.75])
    assert estimated_objects(p) == 20 * (1 + 2 * 12 - 1)
    assert P.make_params(**p.to_dict()) == p and p.to_dict()["domain_linker"] == [3, 2]
    assert P.make_params(domain_diameters="none").domain_diameters is None
    # under every protocol and in a periodic cell (docs/guide/atoms-and-domains.md#several-domains)
    cell = P.make_params(globule_diameter=20, domain_diameters="40", domain_linker="1",
                         periodic="auto", protocol="inflate")
    assert cell.widest_diameter == 40 and cell.periodic == 17  # ceil(2 · 40 / 4.8)
    assert P.DEFAULTS.widest_diameter == P.DEFAULTS.globule_diameter
    for bad, words in (({"domain_diameters": "30", "domain_linker": "2,3"}, "got 2 value"),
                       ({"domain_diameters": "30,x", "domain_linker": "1,1"}, "must be a number"),
                       ({"domain_diameters": "30", "domain_linker": "-1"}, "from 0 to 500"),
                       # a cell must clear the widest domain's own image: 40 / 4.8 -> 9 layers
                       ({"globule_diameter": 20, "domain_diameters": "40", "domain_linker": "1",
                         "periodic": 8}, "40 Å globules .* at least 9 layers")):
        with pytest.raises(P.ParamError, match=words):
            P.make_params(**bad)


def test_a_sweep_takes_lists_of_domains_separated_by_semicolons():
    from fibrilfit.sweep import grid
    values = {f.name: None for f in P.fields()}
    values["domain_diameters"], values["domain_linker"] = "30,20;25,25", "3,2"
    specs = grid.specs_from(values)
    assert specs["domain_diameters"] == ["30,20", "25,25"] and specs["domain_linker"] == ["3,2"]
