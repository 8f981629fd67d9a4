"""Mixed fibrils (issue #44): only the decorated subunits carry a chain and a domain; the check
judges those; a periodic cell's images follow their decorated sources; f = 1 is the model as
before. Cheap builds and short bakes (docs/model/occupancy.md)."""
import json

import numpy as np
import pytest

from helpers import ROOT, run_cli
from fibrilfit.builders import colours
from fibrilfit.builders.periodic import CELL, CHAIN, image_collection
from fibrilfit.builders.scene import INDEX, LAYER, PROTOFILAMENT, TAG
from fibrilfit.model import helix, occupancy


def _run(ff, scene, **values):
    p = ff.model.params.make_params(**values)
    return p, ff.pipeline.run_model(p, scene)


def test_full_occupancy_is_the_model_as_before(scene, ff):
    """f = 1 given in every way the pattern allows builds and bakes the same model to the last
    digit as a run that gives none of the new parameters (the same Bullet scene, the same order
    of objects). tests/blender/test_periodic.py::test_non_periodic_results_are_unchanged holds
    the recorded reference."""
    base = dict(layers=8, frames=40)
    _, plain = _run(ff, scene, **base)
    for extra in (dict(occupancy=1.0), dict(pattern="periodic", pattern_period=1),
                  dict(pattern="layers", pattern_layers="A"), dict(bare_tail=12)):
        _, r = _run(ff, scene, **base, **extra)
        assert "occupancy" not in r
        for key in ("globule_centres", "max_bond_stretch", "clashing_pairs", "verdict",
                    "frames_simulated", "envelope"):
            assert r[key] == plain[key], (extra, key)


def test_only_decorated_subunits_get_a_chain(scene, ff):
    p = ff.model.params.make_params(layers=20, occupancy=0.3, seed=4, bare_tail=5)
    model = ff.builders.build_model(p, scene)
    mask = occupancy.decorated(p)
    assert len(model.chain) == mask.sum() == 6 and len(model.tails) == 14
    assert [(m[0][LAYER], m[0][PROTOFILAMENT]) for m in model.chain] == \
        [tuple(x) for x in np.argwhere(mask).tolist()]
    assert all(not mask[t[0][LAYER], t[0][PROTOFILAMENT]] for t in model.tails)
    assert all(len(t) == 5 and t[0].rigid_body.type == "PASSIVE" for t in model.tails)
    tails = [ob for t in model.tails for ob in t]
    assert all(ob[TAG] == "tail" for ob in tails)
    assert all(tuple(ob.color) == pytest.approx(colours.COLORS["tail"]) for ob in tails)
    # every tail bead is bonded to the one before it, and a tail carries no globule
    bonds = [ob for ob in scene.objects if ob.get(TAG) == "tail_bond"]
    assert len(bonds) == 14 * 4
    assert all(ob.rigid_body_constraint.object1[LAYER] == ob.rigid_body_constraint.object2[LAYER]
               for ob in bonds)
    globule_layers = sorted(ob[LAYER] for ob in model.globules)
    assert globule_layers == np.flatnonzero(mask[:, 0]).tolist()
    # the picture's legend names the tails' colour, its note how many subunits carry the domain
    from fibrilfit.exports import render
    legend = dict(render.legend_entries(model, (), ()))
    assert legend["bare tail (subunit without the domain)"] == colours.COLORS["tail"]
    assert "on 6 of 20 subunits" in render.scale_note(model)
    # find_model reassembles the same split from the tags
    again = ff.builders.find_model(scene)
    assert [m[0].name for m in again.chain] == [m[0].name for m in model.chain]
    assert [t[0].name for t in again.tails] == [t[0].name for t in model.tails]


def test_a_single_decorated_subunit_fits_at_the_shortest_linker(scene, ff):
    """One decorated subunit in a 40-layer fibril meets no other domain: it fits at linker 1, the
    shortest the model builds (the default box core: a one-residue chain already clears it),
    where the fully decorated fibril does not."""
    with pytest.raises(ff.model.params.ParamError):
        ff.model.params.make_params(linker=0)
    _, one = _run(ff, scene, layers=40, linker=1, occupancy=1 / 40, frames=60)
    assert one["occupancy"]["decorated"] == 1 and one["accommodated"], one["answer"]
    assert len(one["globule_centres"]) == 1 and one["clashing_pairs"] == []
    _, full = _run(ff, scene, layers=40, linker=1, frames=60)
    assert not full["accommodated"]


def test_the_check_judges_only_decorated_domains(scene, ff):
    """At linker 1 a fully decorated fibril clashes; decorated every 7th layer (33.6 Å apart,
    more than the 30 Å globule) it fits: the bare subunits hold nothing to clash with. With
    decorated neighbours the clashes name the decorated chains, in their layers only."""
    _, sparse = _run(ff, scene, layers=15, linker=1, pattern="layers",
                     pattern_layers="A......", frames=30)
    assert sparse["accommodated"] and len(sparse["globule_centres"]) == 3
    assert sparse["occupancy"]["decorated_subunits"] == [[0, 0], [7, 0], [14, 0]]
    _, pair = _run(ff, scene, layers=10, linker=1, pattern="layers",
                   pattern_layers="AA...", frames=30)
    assert not pair["accommodated"]
    assert pair["occupancy"]["decorated_subunits"] == [[0, 0], [1, 0], [5, 0], [6, 0]]
    assert pair["max_bond_stretch"] > pair["params"]["stretch_tolerance"]
    assert all(0 <= i < j < 4 for i, j, *_ in pair["clashing_pairs"])


def test_clashes_are_named_in_the_decorated_subunits_layers(scene, ff):
    """Checked as built (the tutorial's start: neighbouring globules overlap), decorated layers
    0, 1, 5 and 6 of 10 clash: the check names chains 0-3 and flags exactly those layers."""
    p = ff.model.params.make_params(layers=10, linker=1, pattern="layers", pattern_layers="AA...")
    model = ff.builders.build_model(p, scene)
    r = ff.analysis.check_model(model)
    assert r["verdict"] == "intersection"
    assert {tuple(q[:2]) for q in r["clashing_pairs"]} >= {(0, 1), (2, 3)}
    assert all(0 <= i < j < 4 for i, j, *_ in r["clashing_pairs"])
    assert [k for k, c in enumerate(r["layer_clashes"]) if c] == [0, 1, 5, 6]


def test_a_lower_nested_fraction_never_needs_a_longer_linker(scene, ff):
    """Under one seed the random draws are nested (model/occupancy.py): the shortest linker that
    fits, scanned upward, is no longer at 25 % than at 50 %, nor at 50 % than at 100 % (16 layers,
    seed 0: measured 1, 3 and 5 residues, docs/model/occupancy.md#nested-draws)."""
    shortest = []
    for f in (0.25, 0.5, 1.0):
        for linker in range(1, 12):
            _, r = _run(ff, scene, layers=16, occupancy=f, linker=linker, seed=0, frames=150)
            if r["accommodated"]:
                shortest.append(linker)
                break
        else:
            shortest.append(99)
    assert shortest == sorted(shortest) and shortest[0] < shortest[-1] < 99, shortest


def test_a_periodic_cell_repeats_its_pattern_in_the_images(scene, ff):
    """Every image copies a decorated chain of the cell: image m of cell layer k stands at
    layer k + m·M of the infinite fibril, which the cell's pattern, repeated, decorates; and the
    image stands at S^m of its source."""
    p = ff.model.params.make_params(periodic=14, pattern="layers", pattern_layers="A.")
    model = ff.builders.build_model(p, scene)
    cell = occupancy.decorated(p)[:, 0]
    assert len(model.chain) == 7
    images = list(image_collection(model).objects)
    assert images
    for ob in images:
        source = model.chain[ob[CHAIN]][ob[INDEX]]
        k = source[LAYER] + ob[CELL] * p.periodic  # its layer in the infinite fibril
        assert cell[k % p.periodic]
        want = helix.apply_points(p, ob[CELL], np.array(source.matrix_world.translation)[None])
        assert np.allclose(ob.matrix_world.translation, want[0], atol=1e-3)


def test_a_seed_reproduces_its_pattern_in_the_result(scene, ff):
    _, a = _run(ff, scene, layers=12, occupancy=0.5, seed=9, frames=5)
    _, b = _run(ff, scene, layers=12, occupancy=0.5, seed=9, frames=5)
    _, c = _run(ff, scene, layers=12, occupancy=0.5, seed=10, frames=5)
    assert a["occupancy"]["decorated_subunits"] == b["occupancy"]["decorated_subunits"]
    assert a["occupancy"]["decorated_subunits"] != c["occupancy"]["decorated_subunits"]
    assert a["occupancy"]["seed"] == 9 and a["occupancy"]["decorated"] == 6


@pytest.mark.parametrize("args, name", [
    (("--occupancy", "0.01", "--layers", "20"), "occupancy"),
    (("--pattern", "layers", "--pattern-layers", "AB"), "pattern_layers"),
    (("--pattern", "periodic", "--occupancy", "0.5"), "occupancy"),
    (("--periodic", "13", "--pattern", "layers", "--pattern-layers", "A."), "pattern"),
])
def test_cli_refuses_a_bad_pattern_in_one_line(args, name, tmp_path):
    out = run_cli("run", *args, "--json", str(tmp_path / "r.json"))
    assert out.returncode == 2, out.stderr
    assert out.stderr.strip().count("\n") == 0 and name in out.stderr
    assert "Traceback" not in out.stderr + out.stdout
    assert not (tmp_path / "r.json").exists()


def test_cli_runs_a_mixed_fibril_and_its_json_meets_the_schema(tmp_path):
    import jsonschema
    out = run_cli("run", "--layers", "10", "--occupancy", "30%", "--bare-tail", "4", "--frames",
                  "20", "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["params"]["occupancy"] == 0.3 and r["occupancy"]["decorated"] == 3
    assert r["tail_clashes"]["beads"] == 7 * 4
    schema = json.loads((ROOT / "docs" / "reference" / "result.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(r)
    broken = {**r, "occupancy": {**r["occupancy"], "fraction": 1.5}}
    assert list(jsonschema.Draft202012Validator(schema).iter_errors(broken))


def test_a_domain_on_a_bare_tail_does_not_fit(scene, ff):
    """The check judges decorated domains against undecorated subunits' bare tails too. Built
    with its domains 7 layers (33.6 Å) apart, the model is clean; a tail bead moved into a
    globule is named with its depth, and that alone makes the run not accommodated."""
    from mathutils import Matrix
    p = ff.model.params.make_params(layers=15, linker=8, pattern="layers",
                                    pattern_layers="A......", bare_tail=3, frames=1)
    model = ff.builders.build_model(p, scene)
    clean = ff.analysis.check_model(model)
    assert clean["tail_clashes"]["pairs"] == [] and clean["tail_clashes"]["beads"] == 12 * 3
    assert clean["verdict"] == "successful" and clean["accommodated"]
    bead = model.tails[3][2]  # layer 4's last bead, into layer 7's globule
    assert (bead["fibrilfit_layer"], len(model.chain)) == (4, 3)
    bead.matrix_world = Matrix.Translation(model.chain[1][-1].matrix_world.translation)
    r = ff.analysis.check_model(model)
    assert r["tail_clashes"]["pairs"] == [[1, [4, 0, 2], pytest.approx(
        p.globule_radius + p.residue_radius, abs=1e-3)]]
    assert r["verdict"] == "successful" and r["linker_intact"] and not r["accommodated"]
    assert r["answer"] != "fits"


def test_the_panel_sets_a_fraction_and_a_pattern(registered):
    """The domain's section of the sidebar holds the fraction (in %) and the pattern, read into
    the model's parameters and written back."""
    from fibrilfit.ui import properties
    names = [f.name for f in properties.fields_in("Globule")]
    assert {"occupancy", "pattern", "pattern_period", "pattern_across", "pattern_layers",
            "bare_tail"} <= set(names)
    ui = registered
    assert ui.occupancy == pytest.approx(100.0)
    ui.occupancy, ui.layers = 25.0, 20
    p = properties.read_params(ui)
    assert p.occupancy == 0.25 and occupancy.decorated(p).sum() == 5
    ui.pattern, ui.pattern_layers, ui.occupancy = "layers", "A..", 100.0
    assert occupancy.decorated(properties.read_params(ui))[:, 0].tolist()[:6] == \
        [True, False, False] * 2
    properties.write_params(ui, ff_params(occupancy=0.1))
    assert ui.occupancy == pytest.approx(10.0) and ui.pattern == "random"


def test_a_build_from_the_panel_decorates_the_fraction_and_marks_the_bare_anchors(registered,
                                                                                 scene, tmp_path):
    """Half of 8 subunits set in the panel (50 %): the step buttons build round(f·N) = 4 chains;
    each other subunit gets a marker at its anchor's place, in the bare colour, that is no
    rigid body (the physics is the model's as before) and that the picture's legend names. The
    panel shows only the pattern's own settings."""
    import bpy
    from fibrilfit.builders import find_model
    from fibrilfit.exports import render
    from fibrilfit.ui import panels, properties
    ui = registered
    shown = lambda: {f.name for f in properties.fields_in("Globule") if panels.shown(f, ui)}
    assert {"occupancy", "pattern"} <= shown() and not shown() & {"pattern_period",
                                                                    "pattern_layers"}
    ui.pattern = "periodic"
    assert {"pattern_period", "pattern_across"} <= shown() and "occupancy" not in shown()
    ui.pattern, ui.layers, ui.occupancy = "random", 8, 50.0
    for step in ("build_slab", "build_anchor", "build_linker", "build_globule",
                 "replicate_layers"):
        assert getattr(bpy.ops.fibrilfit, step)() == {"FINISHED"}
    model = find_model(scene)
    mask = occupancy.decorated(properties.read_params(ui))
    assert len(model.chain) == mask.sum() == 4 and len(model.bare_anchors) == 4
    assert [(ob[LAYER], ob[PROTOFILAMENT]) for ob in model.bare_anchors] == \
        [tuple(x) for x in np.argwhere(~mask).tolist()]
    assert all(ob.rigid_body is None and ob[TAG] == "bare_anchor" for ob in model.bare_anchors)
    assert all(tuple(ob.color) == pytest.approx(colours.COLORS["bare_anchor"])
               for ob in model.bare_anchors)
    # at the place a decorated subunit's anchor would take: the same radius, its own layer
    decorated_anchor = model.chain[0][0].location
    for ob in model.bare_anchors:
        assert np.hypot(*ob.location[:2]) == pytest.approx(np.hypot(*decorated_anchor[:2]),
                                                           abs=1e-3)
        assert ob.location.z == pytest.approx(model.slabs[ob[LAYER]].location.z, abs=1e-3)
    legend = dict(render.legend_entries(model, (), ()))
    assert legend["bare anchor (subunit without the domain)"] == colours.COLORS["bare_anchor"]
    # the picture: the markers framed with the rest, their entry in the drawn legend
    from fibrilfit.exports import dressing
    points = dressing.model_points(model)
    for ob in model.bare_anchors:
        assert (points.min(axis=0) <= np.array(ob.location) + 1e-3).all()
        assert (np.array(ob.location) <= points.max(axis=0) + 1e-3).all()
    drawn = render.render_png(scene, tmp_path / "mixed.png", engine="workbench", size=(480, 270))
    assert "bare anchor (subunit without the domain)" in drawn["legend"]["entries"]


def ff_params(**values):
    from fibrilfit.model import params
    return params.make_params(**values)


def test_the_pdb_of_a_mixed_fibril_names_its_decorated_subunits(scene, ff, tmp_path):
    from fibrilfit.exports import pdb
    p = ff.model.params.make_params(layers=8, pattern="layers", pattern_layers="A...", frames=2)
    model = ff.builders.build_model(p, scene)
    out = pdb.write_pdb(tmp_path / "m.pdb", model, scene)
    text = (tmp_path / "m.pdb").read_text()
    members = len(model.chain[0])
    assert out["atoms_per_model"] == 2 * members
    assert sum(line.startswith("ATOM") for line in text.splitlines()) == 2 * members
    assert "(0, 0), (4, 0)" in " ".join(line[11:].strip() for line in text.splitlines()
                                        if line.startswith("REMARK"))


def test_the_atoms_of_a_mixed_fibril_keep_every_core_and_only_decorated_domains(ff, scene,
                                                                                 tmp_path):
    """`--pdb-atoms` of 6CU7 + ubiquitin decorated every other layer: every subunit's core chain
    is written (as deposited), linker beads and a domain only on the decorated ones."""
    import gemmi
    data = ROOT / "tests" / "data"
    out = tmp_path / "fibril.cif"
    assert ff.cli.main(["run", "--fibril", str(data / "6cu7.pdb.gz"), "--domain",
                        str(data / "1ubq.pdb.gz"), "--layers", "4", "--frames", "20",
                        "--pattern", "layers", "--pattern-layers", "A.", "--pdb-atoms",
                        str(out), "--json", str(tmp_path / "r.json")]) == 0
    r = json.loads((tmp_path / "r.json").read_text())
    pfs = r["params"]["protofilaments"]
    model = gemmi.read_structure(str(out))[0]
    names = {ch.name for ch in model}
    cores = {n for n in names if len(n) == 2}
    domains = {n for n in names if len(n) == 3}
    assert len(cores) == 4 * pfs and len(domains) == 2 * pfs
    assert {n[0] for n in domains} == {"0", "2"}
    for name in cores:
        beads = [res for res in model[name] if res.name == "UNK"]
        assert bool(beads) == (name[0] in "02"), name  # linkers on decorated subunits only
