"""The Check section's Render and Export PDB buttons write what --render and --pdb write."""
import bpy
import gemmi
import numpy as np
import pytest

from fibrilfit.model import params as P
from fibrilfit.ui import properties
from fibrilfit.analysis.verdict import chain_positions
from fibrilfit.builders import find_model


@pytest.fixture
def checked(scene, ff):
    ff.register()
    properties.write_params(scene.fibrilfit, P.make_params(layers=6, linker=2, frames=40, seed=2))
    assert bpy.ops.fibrilfit.run_all() == {"FINISHED"}
    yield scene
    ff.unregister()


def test_buttons_are_greyed_out_before_a_check(scene, ff):
    ff.register()
    try:
        assert not bpy.ops.fibrilfit.render.poll() and not bpy.ops.fibrilfit.export_pdb.poll()
    finally:
        ff.unregister()


def test_export_pdb_button(checked, tmp_path):
    path = tmp_path / "ui.pdb"
    assert bpy.ops.fibrilfit.export_pdb(filepath=str(path)) == {"FINISHED"}
    st = gemmi.read_structure(str(path))
    atoms = np.array([[a.pos.x, a.pos.y, a.pos.z] for ch in st[0] for r in ch for a in r])
    want = chain_positions(find_model(checked)).reshape(-1, 3)
    assert atoms.shape == want.shape and np.abs(atoms - want).max() < 0.01


def test_render_button(checked, tmp_path):
    path = tmp_path / "ui.png"
    assert bpy.ops.fibrilfit.render(filepath=str(path)) == {"FINISHED"}
    img = bpy.data.images.load(str(path))
    assert tuple(img.size) == (640, 360)
    px = np.array(img.pixels[:]).reshape(-1, 4)
    assert px[:, :3].std() > 0.02  # not blank


def test_a_bad_path_is_reported_and_cancels(checked, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(RuntimeError, match="filepath"):
        bpy.ops.fibrilfit.export_pdb(filepath=str(blocker / "m.pdb"))
    assert not (blocker.parent / "m.pdb").exists()


def test_report_refused_in_one_sentence_without_matplotlib(scene, ff, tmp_path, monkeypatch):
    """Issue #33: the refusal was `FibrilFit failed: UsageError("...")`; now the sentence alone,
    and nothing written."""
    from fibrilfit import exits
    from fibrilfit.search import report
    real = report.importlib.util.find_spec
    monkeypatch.setattr(report.importlib.util, "find_spec",
                        lambda name: None if name == "matplotlib" else real(name))
    ff.register()
    try:
        with pytest.raises(RuntimeError) as err:
            bpy.ops.fibrilfit.report(directory=str(tmp_path / "r"), restarts=1, max_linker=2)
    finally:
        ff.unregister()
    message = str(err.value).strip()
    assert message == "Error: " + exits.missing_packages(["matplotlib"], "the report")
    assert not (tmp_path / "r").exists()
