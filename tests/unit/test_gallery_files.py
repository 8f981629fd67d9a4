"""The gallery's cases built from deposited files (issue #47 items 3-4): each case file loads and
makes the model `run --case` makes, from its file, on the right terminus; the arithmetic its notes
state (the linker from a domain boundary, a domain's sphere from its size) is the case's number;
the new controls cite their experiment; the HET-s case waits for the β-solenoid reader and says so.

The files (tests/data/README.md, "The gallery's cores from files") are measured once per module:
each takes 5-15 s. Rise and twist are compared with shared/structures/README.md's, measured by a
script independent of FibrilFit."""
import copy
import math
import re

import pytest
from helpers import ROOT

from fibrilfit.api.model import resolve
from fibrilfit.api.plans import RunPlan, make_plan
from fibrilfit.model import cases
from fibrilfit.structure.domain import RG_TO_DIAMETER

EXAMPLES = ROOT / "examples"
# case: the file, the terminus on the domain's side, the anchor residue, protofilaments, and the
# independent rise (Å) and twist (°) (None: not measured there), with the rise's tolerance
FROM_FILES = {
    "tdp43_8qx9": ("8qx9", "N", 304, 2, 4.78, -1.77),
    "hnrnpdl2_7zir": ("7zir", "N", 345, 1, 4.80, -4.83),
    "ripk3_7da4": ("7da4", "N", 448, 1, 4.60, -7.13),
    "orb2_6vps": ("6vps", "C", 206, 3, 4.72, -1.54),
    "taurd_6qjh_gfp": ("6qjh", "C", 330, 1, None, None),
    "asyn_2n0a_yfp": ("2n0a", "C", 97, 1, 4.896, 1.761),
    "sup35_9xbo": ("9xbo", "C", 132, 1, 4.81, -1.31),
}
# The independent values are given to 2 decimals (rounding 0.005); 6VPS's differ more: FibrilFit
# averages every layer pair of the three protofilaments (4.752 ± 0.006 Å, -1.531°), the other
# script one protofilament's neighbours (4.72 Å, -1.54°), 0.7 % in the rise, not resolved here.
TOLERANCE = {"orb2_6vps": (0.035, 0.012)}
# Rg = 2.2 N^0.38 Å (docs/validation.md#sphere-from-size), the sphere with that Rg
SKOLNICK = (2.2, 0.38)


def sphere_from_size(residues: int) -> float:
    a, b = SKOLNICK
    return RG_TO_DIAMETER * a * residues ** b


@pytest.fixture(scope="module")
def model():
    """model(case): (the case, the Params `run --case` makes, the fibril as measured)."""
    from fibrilfit.structure import fibril
    seen = {}
    real = fibril.measure

    def measure(*args, **kwargs):
        key = repr((args, sorted(kwargs.items())))
        if key not in seen:
            seen[key] = real(*args, **kwargs)
        return copy.deepcopy(seen[key])

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(fibril, "measure", measure)

        def make(name):
            path = EXAMPLES / f"{name}.toml"
            plan, _ = make_plan(RunPlan, {}, case=str(path), command="run")
            case = cases.load(path)
            geometry = measure(case.structure["fibril"],
                               terminus=case.structure.get("terminus", "C"))
            return case, resolve(plan).p, geometry
        yield make


@pytest.mark.parametrize("name", FROM_FILES)
def test_a_case_from_its_file_builds_on_the_domains_terminus(model, name):
    file, terminus, anchor, pfs, rise, twist = FROM_FILES[name]
    case, p, geometry = model(name)
    assert case.structure["fibril"].endswith(f"tests/data/{file}.pdb.gz")
    assert case.structure.get("terminus", "C") == terminus
    assert geometry.anchors[0]["residue"] == anchor
    first, last = geometry.core_residues
    assert anchor == (first if terminus == "N" else last)  # the core's end on the domain's side
    # the model is the file's: nothing of the old slab or of the numbers is left
    assert not {"rise", "twist", "slab", "protofilaments"} & set(case.params)
    assert p.protofilaments == pfs and p.rise == pytest.approx(geometry.rise, abs=1e-3)
    assert p.core_outline  # the core's outline, not a slab
    if rise is not None:
        d_rise, d_twist = TOLERANCE.get(name, (0.006, 0.006))
        assert p.rise == pytest.approx(rise, abs=d_rise)
        assert math.degrees(p.twist) == pytest.approx(twist, abs=d_twist)
    assert p.linker == case.params["linker"]


@pytest.mark.parametrize("name", [n for n in FROM_FILES if n != "orb2_6vps"])
def test_the_linker_is_the_residues_from_the_domain_to_the_anchor(model, name):
    """"Linker L: residues a-b (k) plus the anchor": k = b - a + 1, L = k + 1, and the stretch
    ends next to the anchor the file gives (Orb2's 200 is the parameter's cap, stated)."""
    case, _, geometry = model(name)
    m = re.search(r"Linker (\d+): [^.]*?residues (\d+)-(\d+) \((\d+)\),? plus the anchor",
                  case.meta["notes"])
    L, a, b, k = (int(x) for x in m.groups())
    assert (k, L, case.params["linker"]) == (b - a + 1, k + 1, L)
    anchor = geometry.anchors[0]["residue"]
    assert (b + 1 if case.structure.get("terminus") == "N" else a - 1) == anchor


SIZED = ["tdp43_8qx9", "hnrnpdl2_7zir", "ripk3_7da4", "orb2_6vps", "hets_2kj3_full_length",
         "ure2p_full_length", "ure2p_pd_barnase", "ure2p_pd_carbonic_anhydrase", "ure2p_pd_gst",
         "sup35_9xbo"]


@pytest.mark.parametrize("name", SIZED)
def test_a_domain_with_no_structure_is_the_sphere_of_its_size(name):
    case = cases.load(EXAMPLES / f"{name}.toml")
    m = re.search(r"one sphere of (\d+) residues[,:] ([\d.]+) Å", case.meta["notes"])
    residues, said = int(m[1]), float(m[2])
    assert said == round(sphere_from_size(residues), 1) == case.params["globule_diameter"]
    assert "globule_diameter" in case.meta["estimates"] and "domain" not in case.structure


def test_the_size_formula_gives_the_measured_spheres_of_gfp_and_ubiquitin():
    """The rule against the two domains at hand (tests/data/README.md's Rg spheres: 1GFL chain A,
    230 residues modelled, 43.9 Å; 1UBQ, 76 residues, 30.3 Å): within 3 %."""
    assert sphere_from_size(230) == pytest.approx(43.9, rel=0.03)
    assert sphere_from_size(76) == pytest.approx(30.3, rel=0.03)
    assert sphere_from_size(230) != pytest.approx(43.9, rel=0.01)  # 2 % off: said on the page


@pytest.mark.parametrize("name, expected, who", [
    ("taurd_6qjh_gfp", "does not fit", "Kaniyappan"), ("asyn_2n0a_yfp", "fits", "van Ham"),
    ("hets_2kj3_full_length", "does not fit", "Greenwald")])
def test_a_control_names_its_experiment_and_what_was_not_read(name, expected, who):
    case = cases.load(EXAMPLES / f"{name}.toml")
    meta = case.meta
    assert meta["expected"] == expected and who in meta["citation"]
    assert "not read here" in meta["notes"] and "not checked" in meta["notes"]
    assert len(case.seeds) >= 3 and case.make_params().linker == case.params["linker"]


def test_taurd_is_on_the_tau_core_inside_its_construct():
    """6QJH (core 272-330) lies inside TauRD (244-372); 5O3L's core (306-378) runs past 372."""
    case = cases.load(EXAMPLES / "taurd_6qjh_gfp.toml")
    assert case.structure["fibril"].endswith("6qjh.pdb.gz")
    assert "5O3L" in (EXAMPLES / "taurd_6qjh_gfp.toml").read_text(encoding="utf-8")
    assert case.structure["domain"].endswith("1gfl.pdb.gz") and case.structure["terminus"] == "C"


def test_the_het_s_case_is_read_as_a_solenoid():
    """Its file loads and makes parameters; 2KJ3 is read as a β-solenoid (two rungs a molecule,
    docs/guide/structures.md#beta-solenoids), so the case runs (its row: docs/validation.md)."""
    from fibrilfit import structure
    case = cases.load(EXAMPLES / "hets_2kj3_full_length.toml")
    p = case.make_params()
    assert p.linker == 1 and case.structure["terminus"] == "N"
    assert "waiting" not in case.meta["name"] and "Waits for" not in case.meta["notes"]
    assert case.structure["fibril"].endswith("2kj3.pdb.gz")
    g = structure.measure_fibril(EXAMPLES / case.structure["fibril"], terminus="N")
    assert g.rungs == 2


def test_sup35_is_built_on_both_pieces_of_its_core(model):
    """9XBO's chain is ordered in two segments, 5-65 and 102-132, both in the core: the case's
    model has both in its outline, its anchor on Gln132 (the C-domain follows the M domain), and
    its linker is the M domain after the core to the C-domain's start (Sup35 N 1-123, M 124-253,
    C 254-685): residues 133-253 plus the anchor, 122; the unordered 66-101 are not linker. The
    C-domain (254-685, 432 residues) is the sphere of its size."""
    case, p, geometry = model("sup35_9xbo")
    assert geometry.core_segments == [[5, 65], [102, 132]]
    a = geometry.anchors[0]
    assert (a["residue"], a["residue_name"], geometry.terminus) == (132, "GLN", "C")
    m_end, c_start, c_end = 253, 254, 685
    assert p.linker == (m_end - a["residue"]) + 1 == 122 and c_start == m_end + 1
    assert p.globule_diameter == round(sphere_from_size(c_end - c_start + 1), 1) == 57.0
    assert geometry.tail_residues == [] and p.protofilaments == 1
    assert "examples/numbers/sup35_9xbo.toml" in (EXAMPLES / "sup35_9xbo.toml").read_text(
        encoding="utf-8")
    old = cases.load(EXAMPLES / "numbers" / "sup35_9xbo.toml")  # the numbers-only version
    assert old.params["linker"] == 121 and "slab" in old.params and not old.structure


# What the gallery's table shows a reader comes from these files' words: no reference a reader
# cannot follow (an issue number, the developers' shared folder). examples/numbers/ is a record
# kept byte for byte, and not shown as a row.
INTERNAL = re.compile(r"(?<![\w&/`])#\d+\b|\bissues? #?\d+\b|\bshared/(?:structures|notes)\b"
                      r"|\bthe task\b")


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_a_case_file_names_no_internal_reference(path):
    found = INTERNAL.findall(path.read_text(encoding="utf-8"))
    assert not found, f"{path.name}: {found}"


def test_the_internal_reference_check_finds_them():
    assert INTERNAL.findall("as quoted in issue #36; per issue #15; see shared/structures/README.md;"
                            " as given in the task") == ["issue #36", "issue #15",
                                                         "shared/structures", "the task"]
    assert not INTERNAL.findall("PMC3079393; tests/data/README.md; doi:10.1038/s41467-023-35854-0")
