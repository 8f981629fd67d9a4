"""A run's linker span (docs/model/linker-integrity.md#linker-span) and the short fibril's
caveat (docs/model/end-effects.md), on fast runs: a finite fibril, a periodic cell and a real
shape held at its joint. The count itself is tested in closed form in
tests/unit/test_linker_span.py; here, that every run carries it with sane values."""
import pytest

from fibrilfit import pipeline
from fibrilfit.model import params as P
from fibrilfit.model.answer import free_end_warnings


def _span_ok(r):
    s = r["linker_stretch"]
    tol = r["params"]["stretch_tolerance"]
    assert r["accommodated"] is True  # an accommodated layout: no bond beyond the tolerance
    assert 0.0 < s["median"] <= s["worst"] <= 1.0 + tol
    return s


def test_a_finite_fibrils_run_carries_the_span_and_the_free_end_warning(scene):
    p = P.make_params(layers=4, frames=60)
    r = pipeline.run_model(p, scene)
    s = _span_ok(r)
    assert s["linkers"] == 4 and s["contour_A"] == pytest.approx(5 * 3.5 + p.residue_radius)
    assert 0 <= s["worst_linker"]["layer"] < 4 and "protofilament" not in s["worst_linker"]
    assert r["warnings"][:1] == free_end_warnings(p) and "free ends" in r["warnings"][0]


def test_a_periodic_cell_has_the_span_and_no_free_ends(scene):
    r = pipeline.run_model(P.make_params(periodic=10, linker=8, frames=30), scene)
    s = _span_ok(r)
    assert s["linkers"] == 10
    assert not any("free ends" in w for w in r["warnings"])


def test_a_real_shape_is_counted_to_its_joint(scene):
    atoms = [[10, 0, 0, 1.5], [-10, 0, 0, 1.5], [0, 10, 0, 1.5], [0, -10, 0, 1.5],
             [0, 0, 10, 1.5], [0, 0, -10, 1.5]]
    p = P.make_params(domain_shape="hull", domain_atoms=atoms, domain_joint=[[10.0, 0, 0]],
                      linker=8, layers=4, frames=60)
    r = pipeline.run_model(p, scene)
    s = _span_ok(r)
    assert s["contour_A"] == pytest.approx(8 * 3.5)  # L residues, 3.5 Å each, to the joint CA
