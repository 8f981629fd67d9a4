"""The domain's real shape (geom/shape.py, issue #24): hull atoms, covering spheres, joint,
and the parameters that carry them. No bpy: the built meshes are tested in
tests/blender/test_domain_shapes.py."""
import numpy as np
import pytest
from fibrilfit.model import params as P
from fibrilfit.model.chain import body_radii, chain_radii, chain_x, globule_offset, rest_lengths
from fibrilfit.geom import shape
from fibrilfit.structure import body_frame, measure_domain, model_values, reading
from helpers import ROOT

DATA = ROOT / "tests" / "data"


@pytest.fixture(scope="module", params=["1gfl", "1ubq"])
def chain(request):
    return reading.load(DATA / f"{request.param}.pdb.gz", "--domain").chains[0]


def test_body_frame_is_the_file_minus_the_centroid(chain):
    centroid, local = body_frame(chain.heavy)
    assert np.allclose(local + centroid, chain.heavy)
    assert np.allclose(local.mean(axis=0), 0.0, atol=1e-9)


def test_hull_points_reach_past_every_atom_in_every_direction(chain):
    _, local = body_frame(chain.heavy)
    atoms = shape.hull_atoms(local, chain.heavy_radius)
    pts = shape.hull_points(atoms)
    u = shape.directions(5000)
    need = shape.grown_support(local, chain.heavy_radius, u)
    have = (pts @ u.T).max(axis=0)
    assert (have >= need - 1e-9).all()  # every atom's ball lies within the points' hull
    assert (have - need).max() <= shape.grow(1.8) + 1e-9  # and it departs by at most `grow`


def test_covering_spheres_cover_every_atom_and_are_reproducible(chain):
    _, local = body_frame(chain.heavy)
    s = shape.covering_spheres(local, chain.heavy_radius)
    reach = np.linalg.norm(local[:, None] - s[None, :, :3], axis=-1) + chain.heavy_radius[:, None]
    assert (reach <= s[None, :, 3] + 1e-9).any(axis=1).all()
    assert len(s) == shape.SPHERES
    assert np.array_equal(s, shape.covering_spheres(local, chain.heavy_radius))


def test_the_joint_is_the_terminal_ca_and_its_depth_at_least_its_radius():
    after = measure_domain(DATA / "1ubq.pdb.gz", follows=True)
    before = measure_domain(DATA / "1ubq.pdb.gz", follows=False)
    assert after.shape["joint_residue"] == 1 and before.shape["joint_residue"] == 76
    c = reading.load(DATA / "1ubq.pdb.gz", "--domain").chains[0]
    centroid, _ = body_frame(c.heavy)
    assert np.allclose(after.geometry["domain_joint"], c.ca[0] - centroid, atol=1e-3)
    for d in (after, before):  # a CA is a heavy atom: its own ball is inside the grown hull
        assert d.shape["joint_depth"] >= 1.7 - 0.01
    assert "geometry" not in after.to_dict() and after.to_dict()["shape"]["hull_atoms"] > 10


def test_params_take_a_shape_only_with_its_geometry():
    assert P.DEFAULTS.domain_shape == "sphere"
    assert chain_x(P.DEFAULTS)[-1] == chain_x(P.DEFAULTS)[-2] + 1.75 + 15.0  # unchanged
    with pytest.raises(P.ParamError, match="^domain_shape: must be one of sphere, hull, spheres"):
        P.make_params(domain_shape="cube")
    with pytest.raises(P.ParamError, match="^domain_shape: hull needs a domain structure"):
        P.make_params(domain_shape="hull")
    dom = measure_domain(DATA / "1ubq.pdb.gz")
    assert "domain_atoms" not in model_values(None, dom)  # the sphere's model: as before
    p = P.make_params(domain_shape="hull", **model_values(None, dom, shape="hull"))
    assert globule_offset(p) == pytest.approx(np.linalg.norm(dom.geometry["domain_joint"]))
    assert P.make_params(**p.to_dict()) == p  # the case file / sweep round trip
    assert p.replace(periodic=20).periodic == 20  # a cell's images carry the whole turn
    spheres = P.make_params(domain_shape="spheres", **model_values(None, dom, shape="spheres"))
    assert spheres.replace(protocol="inflate").protocol == "inflate"  # the children grow
    with pytest.raises(P.ParamError, match="^domain_atoms: must be a list"):
        p.replace(domain_atoms=[[1, 2, 3]])


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_a_real_shapes_reach_holds_its_body(shape):
    """A cell's images are built and moved by the shape's reach (Domain.reach): it holds
    the hull's points plus Bullet's margin (the spheres), and exceeds GFP's Rg sphere
    (docs/model/domain-shapes.md#periodic)."""
    from fibrilfit.geom import shape as sh
    dom = measure_domain(DATA / "1gfl.pdb.gz")
    p = P.make_params(domain_shape=shape, **model_values(None, dom, shape=shape))
    reach = p.domains[0].reach
    if shape == "hull":
        far = np.linalg.norm(sh.hull_points(p.domain_atoms), axis=1).max() + 0.1  # HULL_MARGIN
        assert far <= reach < far + 0.2
    else:
        s = np.asarray(p.domain_spheres)
        assert reach == pytest.approx((np.linalg.norm(s[:, :3], axis=1) + s[:, 3]).max())
    assert reach > p.globule_radius + 5.0
    assert body_radii(p)[p.linker] == reach
    assert list(body_radii(P.DEFAULTS)) == chain_radii(P.DEFAULTS)  # the sphere's: as before


def test_several_real_domains_carry_each_domains_shape_joint_and_exit():
    """Ubiquitin then GFP on one chain (docs/guide/atoms-and-domains.md#shapes-of-several-domains):
    each domain's own rows, joint and exit in its own body frame; the chain's rest lengths
    enter each domain at its joint and leave at its exit; the sphere's model takes none."""
    ubq = measure_domain(DATA / "1ubq.pdb.gz", outgoing=True)
    gfp = measure_domain(DATA / "1gfl.pdb.gz")
    assert "exit" in ubq.geometry and "exit" not in gfp.geometry
    assert not {"further_atoms", "domain_exits"} & set(model_values(None, ubq, more_domains=[gfp]))
    values = model_values(None, ubq, more_domains=[gfp], shape="hull")
    p = P.make_params(domain_shape="hull", linker=4, domain_linker=[5], **values)
    assert p.several_shapes and [d.member for d in p.domains] == [4, 10]
    assert np.allclose(p.domains[0].rows, ubq.geometry["domain_atoms"])
    assert np.allclose(p.domains[1].rows, gfp.geometry["domain_atoms"])
    assert np.allclose(p.domains[1].joint, gfp.geometry["domain_joint"])
    assert np.allclose(p.domain_exits[0], ubq.geometry["exit"])
    rest = rest_lengths(p)
    spacing = p.residue_spacing
    assert rest[3] == pytest.approx(spacing + np.linalg.norm(ubq.geometry["domain_joint"]))
    assert rest[4] == pytest.approx(np.linalg.norm(ubq.geometry["exit"]) + spacing)
    assert rest[9] == pytest.approx(spacing + np.linalg.norm(gfp.geometry["domain_joint"]))
    assert rest[5:9] == [spacing] * 4
    # spheres: each domain its own covering spheres
    q = P.make_params(domain_shape="spheres", linker=4, domain_linker=[5],
                      **model_values(None, ubq, more_domains=[gfp], shape="spheres"))
    assert np.allclose(q.domains[1].rows, gfp.geometry["domain_spheres"])
    # what is missing is refused in one line, naming the parameter
    with pytest.raises(P.ParamError, match="^domain_shape: hull with 2 domains per chain needs "
                                           "every domain's structure"):
        P.make_params(domain_shape="hull", domain_diameters=[30], domain_linker=[4],
                      **model_values(None, ubq, shape="hull"))
    with pytest.raises(P.ParamError, match="^domain_linker: must be at least 1 residue"):
        p.replace(domain_linker=[0])
