"""The sidebar's Import fibril… / Import domain…: parameters filled, measurements shown, the CA
trace beside the model under a tagged collection; bad files reported, nothing changed."""

import bpy
import numpy as np
import pytest

from fibrilfit.ui import properties
from fibrilfit.model.chain import chain_x
from fibrilfit.ui import structure_trace
from fibrilfit.builders.scene import TAG
from fibrilfit.ui import panels
from helpers import ROOT

DATA = ROOT / "tests" / "data"


@pytest.fixture
def ui(registered):
    return registered


def test_import_fibril_fills_parameters_and_adds_the_trace(ui, scene):
    assert bpy.ops.fibrilfit.import_fibril(filepath=str(DATA / "6cu7.pdb.gz")) == {"FINISHED"}
    p = properties.read_params(ui)
    m = structure_trace.measured(scene)["fibril"]
    assert p.rise == pytest.approx(m["rise"], abs=1e-5)
    assert p.twist == pytest.approx(m["twist"], abs=1e-6) and p.twist < 0
    (coll,) = [c for c in bpy.data.collections if c.get(TAG) == structure_trace.COLLECTION]
    (ob,) = coll.objects
    assert ob.get(TAG) == structure_trace.TRACE and ob.rigid_body is None
    assert len(ob.data.vertices) == 10 * 60 and len(ob.data.edges) == 10 * 59
    # aligned with the model: the axis is Z, the layers step by the rise along it
    z = np.array([v.co.z for v in ob.data.vertices]).reshape(10, 60).mean(axis=1)
    assert np.diff(z[:5]) == pytest.approx([4.825] * 4, abs=0.2)  # protofilament 0, bottom-up
    # on the model's core (issue #33): no offset, every CA within the core outline's reach of
    # the axis, and the file's 5 layers per protofilament on the model's layers, centred in its
    # 20: layers 7 to 11, each at its layer's height (the model's rise, the measured one)
    assert tuple(ob.location) == (0.0, 0.0, 0.0)
    co = np.array([v.co for v in ob.data.vertices])
    outline_reach = np.hypot(*np.asarray(p.core_outline, float).T).max()
    assert np.hypot(co[:, 0], co[:, 1]).max() <= outline_reach + 4.0  # a CA, not the hull
    assert z[:5] / p.rise == pytest.approx([7, 8, 9, 10, 11], abs=0.1)
    lines = panels.structure_lines(structure_trace.measured(scene))
    assert any("left-handed" in ln for ln in lines) and any("K97" in ln or "LYS97" in ln
                                                              for ln in lines)
    # importing again replaces the trace
    assert bpy.ops.fibrilfit.import_fibril(filepath=str(DATA / "8a9l.pdb.gz")) == {"FINISHED"}
    assert len(coll.objects) == 1 and properties.read_params(ui).twist > 0


def test_import_domain_sets_the_globule(ui, scene):
    assert bpy.ops.fibrilfit.import_domain(filepath=str(DATA / "1gfl.pdb.gz"), chain="A") == \
        {"FINISHED"}
    p = properties.read_params(ui)
    assert p.globule_diameter == pytest.approx(43.94, abs=0.01)
    # its CA trace beside layer 0's globule, at the model's scale (Å), clear of the globule
    (coll,) = [c for c in bpy.data.collections if c.get(TAG) == structure_trace.COLLECTION]
    (ob,) = [o for o in coll.objects if o.get(structure_trace.KIND) == "domain"]
    co = np.array([v.co for v in ob.data.vertices])
    assert len(co) == 230  # GFP chain A's CA, residues 2-231
    assert np.linalg.norm(co.mean(axis=0)) < 3.0  # about the heavy atoms' centroid
    globule = np.array([max(chain_x(p)) + p.globule_radius, 0.0, 0.0])
    assert (np.linalg.norm(co + np.array(ob.location) - globule, axis=1) > p.globule_radius).all()
    assert ob.location.x == pytest.approx(globule[0])
    assert any("Rg 17.02" in ln for ln in panels.structure_lines(
        structure_trace.measured(scene)))


def test_a_bad_file_is_reported_and_changes_nothing(ui, scene):
    before = properties.values(ui)
    with pytest.raises(RuntimeError, match="Fibril file: "):  # bpy.ops raises on an ERROR report
        bpy.ops.fibrilfit.import_fibril(filepath=str(DATA / "1ubq.pdb.gz"))
    assert properties.values(ui) == before
    assert structure_trace.find_collection(scene) is None


def test_the_panel_draws_with_imports(ui, scene):
    import types
    from ui_fakes import FakeLayout
    bpy.ops.fibrilfit.import_fibril(filepath=str(DATA / "2n0a.pdb.gz"))
    log = []
    panels.FIBRILFIT_PT_main.draw(types.SimpleNamespace(layout=FakeLayout(log)), bpy.context)
    assert log[0] == ("operator", "fibrilfit.import_fibril")  # the structures come first
    labels = [t for kind, t in log if kind == "label"]
    assert labels[:3] == ["Fibril 2n0a.pdb.gz", labels[1], labels[2]]
    assert labels[1].startswith("rise 4.89") and labels[2].startswith("right-handed")


def test_an_imported_domain_builds_as_its_hull(ui, scene, ff):
    """Import domain… keeps the domain's real shape (in the list of domains), so choosing Domain
    shape: hull later builds the hull without a new import; the sphere's model carries no
    shape, as the command line's `--domain` gives none (tests/blender/test_domain_list.py)."""
    assert bpy.ops.fibrilfit.import_domain(filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    sphere = properties.read_params(ui)
    assert sphere.domain_shape == "sphere" and sphere.domain_atoms is None
    assert chain_x(sphere) == chain_x(ff.model.params.make_params(
        globule_diameter=sphere.globule_diameter))  # the sphere's model as before
    ui.domain_shape = "hull"
    ui.layers = 2
    p = properties.read_params(ui)
    assert p.domain_shape == "hull" and p.domain_joint is not None
    model = ff.pipeline.build(p, scene)
    assert model.globules[0].rigid_body.collision_shape == "CONVEX_HULL"
