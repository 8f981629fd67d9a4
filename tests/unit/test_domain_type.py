"""The domain as a type (model/domains.py): Params.domains built from the flat parameters, and the
shape table's reach, equal to the values the code gave before the domains had a type."""
import numpy as np
import pytest
from fibrilfit.model import domains, params as P
from fibrilfit.model.chain import body_radii, chain_radii
from fibrilfit.structure import measure_domain, model_values
from helpers import ROOT

DATA = ROOT / "tests" / "data"

# The reach of each real shape's domains, as model/helix.py computed it at commit 4a82a1a
# (globule_reach, domain_reaches: printed with repr by running that commit's helix.py on these
# Params). 1ubq measured with and without its outgoing exit gives the same rows.
OLD_REACH = {
    ("1ubq", "hull"): 27.487743914421166,
    ("1gfl", "hull"): 30.824521699353674,
    ("1ubq", "spheres"): 28.328227531676482,
    ("1gfl", "spheres"): 32.535127493351936,
}


@pytest.fixture(scope="module")
def measured():
    return {"1ubq": measure_domain(DATA / "1ubq.pdb.gz", outgoing=True),
            "1gfl": measure_domain(DATA / "1gfl.pdb.gz")}


def test_one_sphere_domain_is_a_list_of_one():
    (d,) = P.DEFAULTS.domains
    assert (d.index, d.member, d.diameter, d.radius) == (0, P.DEFAULTS.linker, 30.0, 15.0)
    assert d.shape is domains.SHAPES["sphere"] and not d.shape.real
    assert d.rows is None and d.joint is None and d.exit is None and d.linker is None
    assert d.reach == 15.0
    assert list(body_radii(P.DEFAULTS)) == chain_radii(P.DEFAULTS)


def test_several_sphere_domains_each_have_their_size_member_and_linker():
    p = P.make_params(linker=5, domain_diameters=[20, 12], domain_linker=[3, 4])
    ds = p.domains
    assert [d.member for d in ds] == domains.member_indices(p) == [5, 9, 14]
    assert [d.diameter for d in ds] == [30.0, 20.0, 12.0]
    assert [d.linker for d in ds] == [3, 4, None]
    assert [d.reach for d in ds] == [15.0, 10.0, 6.0] == [d.radius for d in ds]
    assert all(d.rows is None and d.joint is None and d.exit is None for d in ds)


@pytest.mark.parametrize("shape", ["hull", "spheres"])
@pytest.mark.parametrize("name", ["1ubq", "1gfl"])
def test_a_real_domains_reach_is_the_old_code_s(measured, name, shape):
    p = P.make_params(domain_shape=shape, **model_values(None, measured[name], shape=shape))
    (d,) = p.domains
    assert d.shape is domains.SHAPES[shape] and d.shape.real
    assert d.reach == OLD_REACH[name, shape]
    assert np.array_equal(d.rows, np.asarray(getattr(p, d.shape.rows)))
    assert np.array_equal(d.joint, np.asarray(p.domain_joint[0]))
    assert d.exit is None and d.linker is None
    radii = body_radii(p)
    assert radii[p.linker] == OLD_REACH[name, shape] > p.globule_radius
    assert list(np.delete(radii, p.linker)) == list(np.delete(chain_radii(p), p.linker))


@pytest.mark.parametrize("shape", ["hull", "spheres"])
def test_several_real_domains_each_have_their_own_rows_joint_and_exit(measured, shape):
    ubq, gfp = measured["1ubq"], measured["1gfl"]
    p = P.make_params(domain_shape=shape, linker=4, domain_linker=[5],
                      **model_values(None, ubq, more_domains=[gfp], shape=shape))
    first, second = p.domains
    key = "domain_atoms" if shape == "hull" else "domain_spheres"
    assert np.allclose(first.rows, ubq.geometry[key]) and np.allclose(second.rows, gfp.geometry[key])
    assert np.allclose(first.joint, ubq.geometry["domain_joint"])
    assert np.allclose(second.joint, gfp.geometry["domain_joint"])
    assert np.allclose(first.exit, ubq.geometry["exit"]) and second.exit is None
    assert (first.linker, second.linker) == (5, None)
    assert (first.member, second.member) == (4, 10)
    assert [d.reach for d in p.domains] == [OLD_REACH["1ubq", shape], OLD_REACH["1gfl", shape]]


def test_the_shape_table_holds_every_shape_the_parameters_offer():
    assert tuple(domains.SHAPES) == P.DOMAIN_SHAPES
    assert {s.collision for s in domains.SHAPES.values()} == {"SPHERE", "CONVEX_HULL", "COMPOUND"}
    assert [s.name for s in domains.SHAPES.values() if s.margin is not None] == ["hull"]
    rows = np.array([[3.0, 4.0, 0.0, 2.0], [0.0, 0.0, 1.0, 1.0]])
    assert domains.SHAPES["spheres"].reach(rows) == 7.0
    assert domains.SHAPES["hull"].reach(rows) == pytest.approx(5.0 + 2.0 / 0.93 + 0.11)
