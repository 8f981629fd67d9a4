"""A hetero-amyloid (issue #44 item 1): the letter B of a layers pattern puts a second domain, a
sphere of domain_b_diameter, on its layers (docs/model/occupancy.md#hetero). Cheap builds and
short bakes."""
import numpy as np
import pytest

from fibrilfit.builders.scene import INDEX, LAYER, PROTOFILAMENT, TAG
from fibrilfit.model import occupancy

pytestmark = pytest.mark.one_bpy


def _params(ff, **values):
    return ff.model.params.make_params(**{"layers": 6, "frames": 40, **values})


@pytest.mark.parametrize("protocol", ["tutorial", "inflate"])
def test_b_layers_carry_their_own_globule_on_a_bond_to_its_surface(scene, ff, protocol):
    """Odd layers (A) carry 30 Å globules, even ones (B) 40 Å, every chain its linker's beads;
    as built, every bond of every chain is at its own rest length, a B chain's last one at
    B's surface (the check would read a B chain measured by A's lengths as 30 % stretched)."""
    p = _params(ff, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, linker=5,
                protocol=protocol)
    model = ff.builders.build_model(p, scene)
    b = occupancy.second_domain(p)
    assert len(model.chain) == 6
    for members in model.chain:
        layer = members[0][LAYER]
        assert len(members) == p.linker + 1  # anchor, 4 residues, the globule
        assert [ob[TAG] for ob in members] == ["anchor"] + ["residue"] * 4 + ["globule"]
        assert [ob[INDEX] for ob in members] == list(range(6))
        globule = members[-1]
        want = 40.0 if b[layer, members[0].get(PROTOFILAMENT, 0)] else 30.0
        assert layer % 2 == (want == 40.0)  # A on layers 0, 2, 4; B on 1, 3, 5
        if protocol == "tutorial":  # (inflate starts them small: grown by the bake)
            assert max(globule.dimensions) == pytest.approx(want, abs=1e-3)
        else:
            assert globule.scale[0] == pytest.approx(want / 30.0)
    bonds = [ob for ob in scene.objects if ob.get(TAG) == "bond"]
    assert len(bonds) == 6 * p.linker
    if protocol == "tutorial":
        for members in model.chain:
            last = np.linalg.norm(np.subtract(members[-1].matrix_world.translation,
                                              members[-2].matrix_world.translation))
            want = (20.0 if members[0][LAYER] % 2 else 15.0) + p.residue_radius
            assert last == pytest.approx(want, abs=1e-4)
        r = ff.analysis.check_model(model)
        assert r["max_bond_stretch"] == pytest.approx(0.0, abs=1e-5)
        # as built the straight chains overlap (4.8 Å apart): each pair's depth is its own
        # two radii less the centres' distance
        c = np.asarray(r["globule_centres"])
        radius = np.where(np.arange(6) % 2, 20.0, 15.0)
        assert r["clashing_pairs"]
        for i, j, d in r["clashing_pairs"]:
            assert d == pytest.approx(radius[i] + radius[j] - np.linalg.norm(c[i] - c[j]),
                                      abs=1e-3)


def test_b_as_large_as_a_is_the_all_a_model_bit_for_bit(scene, ff):
    """B with A's diameter and linker builds and bakes the model of the all-A pattern of the
    same letters to the last digit (AB as AA, B. as A.)."""
    keys = ("globule_centres", "max_bond_stretch", "clashing_pairs", "verdict",
            "frames_simulated", "envelope", "accommodated")
    for hetero, plain in (("AB", "AA"), ("B.", "A.")):
        a = ff.pipeline.run_model(_params(ff, pattern="layers", pattern_layers=plain,
                                             linker=4), scene)
        h = ff.pipeline.run_model(_params(ff, pattern="layers", pattern_layers=hetero,
                                             linker=4, domain_b_diameter=30.0, linker_b=4),
                                     scene)
        for key in keys:
            assert h[key] == a[key], (hetero, key)
        assert h["occupancy"]["second_domain"]["diameter"] == 30.0


def test_a_hetero_run_records_b_and_judges_b_by_its_size(scene, ff):
    """A short bake of AB with a larger B on a linker too short to hold them: the result's
    params and occupancy block carry B, the bound counts A and B at their sizes, and the sphere
    check's pairs are those of the centres' depth at each globule's own radius."""
    r = ff.pipeline.run_model(_params(ff, pattern="layers", pattern_layers="AB",
                                         domain_b_diameter=40.0, linker=3, frames=2), scene)
    assert r["params"]["domain_b_diameter"] == 40.0 and r["params"]["linker_b"] is None
    assert r["occupancy"]["second_domain"]["subunits"] == [[1, 0], [3, 0], [5, 0]]
    assert "A and B each at its own size" in r["bound"]["method"]
    c = np.asarray(r["globule_centres"])
    radius = np.where(np.arange(6) % 2, 20.0, 15.0)
    depth = radius[:, None] + radius[None] - np.linalg.norm(c[:, None] - c[None], axis=-1)
    band = r["sphere_check"]["tolerance"]
    deep = {(i, j) for i, j in zip(*np.nonzero(np.triu(depth > band, 1)))}
    assert deep and deep == {(i, j) for i, j, _ in r["sphere_check"]["clashing_pairs"]}
    assert not r["accommodated"]  # two frames in: still pushing apart


def test_inflate_grows_each_globule_to_its_own_size(scene, ff):
    """Under inflate the globules start small and grow: at the end A's sphere is at scale 1
    and B's at d_B / d_A, and the judgement's pairs count each at its own size."""
    p = _params(ff, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, linker=8,
                protocol="inflate", grow_frames=20, hold_frames=10, regrow_cycles=0,
                near_cycles=0)
    r = ff.pipeline.run_model(p, scene)
    assert r["inflate"]["start_scale"] < 1.0
    model = ff.builders.find_model(scene)
    scales = {int(members[0][LAYER]): members[-1].matrix_world.to_scale()[0]
              for members in model.chain}
    for layer, s in scales.items():
        assert s == pytest.approx(40.0 / 30.0 if layer % 2 else 1.0, abs=1e-5), layer


def test_a_cell_images_b_at_its_own_size(scene, ff):
    """A periodic cell of AB: every image stands at S^m of its source as built, and after a
    short bake every image globule carries its source's scale (B's larger sphere above and
    below the cell too)."""
    from fibrilfit.builders.periodic import CELL, CHAIN, image_collection
    from fibrilfit.model import helix
    p = _params(ff, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, linker=6,
                periodic="auto", frames=20)
    assert p.periodic % 2 == 0
    model = ff.builders.build_model(p, scene)
    for ob in image_collection(model).objects:  # as built: at S^m of its source
        source = model.chain[ob[CHAIN]][ob[INDEX]]
        want = helix.apply_points(p, ob[CELL], np.array(source.matrix_world.translation)[None])
        assert np.allclose(ob.matrix_world.translation, want[0], atol=1e-3)
    r = ff.pipeline.run_model(p, scene)  # baked: each image carries its source's scale
    model = ff.builders.find_model(scene)
    images = list(image_collection(model).objects)
    globules = [ob for ob in images if model.chain[ob[CHAIN]][ob[INDEX]][TAG] == "globule"]
    assert globules and {model.chain[ob[CHAIN]][0][LAYER] % 2 for ob in globules} == {0, 1}
    for ob in globules:
        source = model.chain[ob[CHAIN]][ob[INDEX]]
        assert ob.scale[0] == pytest.approx(40.0 / 30.0 if source[LAYER] % 2 else 1.0)
    assert r["periodic"] and "sphere_check" in r


def test_the_pdb_writes_each_globule_at_its_own_radius(ff):
    """The coarse-grained PDB's B-factor column is each sphere's radius: A's 15 Å, B's 20 Å."""
    from fibrilfit.exports import pdb
    p = _params(ff, layers=4, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0)
    pos = np.zeros((4, p.linker + 1, 3))
    text = pdb.pdb_text(p, [(1, pos)])
    radii = [float(line[60:66]) for line in text.splitlines()
             if line.startswith("ATOM") and line[17:20] == "GLB"]
    assert radii == [15.0, 20.0, 15.0, 20.0]
