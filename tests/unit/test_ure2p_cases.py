"""The Ure2p cases (issue #47 item 4, issue #48 item 6): numbers-only cores built from published
numbers (Baxa et al. 2003: a 4 nm core, one molecule per 0.45 nm by STEM). Each number the case
files' notes derive is recomputed here from the published ones, so a case cannot drift from
what its notes say (docs/validation.md#ure2p)."""
import math
import re

import pytest
from helpers import ROOT

from fibrilfit.model import cases

EXAMPLES = ROOT / "examples"
FULL = "ure2p_full_length"
FUSIONS = {"ure2p_pd_barnase": 110, "ure2p_pd_carbonic_anhydrase": 259, "ure2p_pd_gst": 218,
           "ure2p_pd_gfp": None}  # residues of the fused protein's sphere (GFP: its structure)
CORE_DIAMETER = 40.0  # Å, the 4 nm core (Baxa 2003)
PER_MOLECULE = 4.5  # Å along the axis per molecule (STEM mass-per-length, 1 per 0.45 nm)
CORE_END = 65  # the core's last ordered residue: the end of Ure2p1-65 (Edskes et al. 1999)
C_DOMAIN_START = 97  # the C-domain, 97-354
PROTEIN_DENSITY = 0.81  # Da/Å³ (1.35 g/cm³), docs/model/ensemble.md#observables
RESIDUE_MASS = 110.0  # Da


def load(name):
    case = cases.load(EXAMPLES / f"{name}.toml")
    return case, case.make_params()


@pytest.mark.parametrize("name", [FULL, *FUSIONS])
def test_the_core_is_the_published_4_nm_fibre_of_one_molecule_per_4_5_angstrom(name):
    case, p = load(name)
    # one molecule per 4.5 Å: one protofilament of one molecule a layer at that rise
    assert p.protofilaments == 1 and p.rise == PER_MOLECULE == p.slab[2]
    # the slab is 4 nm wide, its depth giving a 4 nm disc's area, and the anchor at its edge
    assert p.slab[0] == CORE_DIAMETER
    assert p.slab[0] * p.slab[1] == pytest.approx(math.pi * (CORE_DIAMETER / 2) ** 2, rel=0.02)
    assert p.anchor_xy == pytest.approx((CORE_DIAMETER / 2 + p.residue_radius, 0.0))
    assert (p.layers, p.score_layers) == (40, 10)  # as the gallery's other 40-layer cases
    assert case.meta["expected"] == "fits" and "Baxa" in case.meta["citation"]
    assert "not read here" in case.meta["notes"] and "not checked" in case.meta["notes"]
    assert {"slab", "twist", "linker"} <= set(case.meta["estimates"])


def test_the_linker_runs_from_the_cores_end_to_the_c_domain():
    """Linker = the residues between the core's last ordered residue (65) and the C-domain's
    first (97), plus the anchor: 66-96 (31) + 1 = 32; the notes say so, and give the other
    choices of core (1-89: 8; a 42-residue core 1-42: 55)."""
    case, p = load(FULL)
    assert p.linker == C_DOMAIN_START - 1 - CORE_END + 1 == 32
    m = re.search(r"Linker (\d+): residues (\d+)-(\d+) \((\d+)\), plus the anchor",
                  case.meta["notes"])
    L, a, b, k = (int(x) for x in m.groups())
    assert (a, b, k, L) == (CORE_END + 1, C_DOMAIN_START - 1, b - a + 1, k + 1)
    assert "would be 8" in case.meta["notes"] and "55 (residues 43-96" in case.meta["notes"]


def test_the_4_nm_core_holds_about_42_residues_as_the_notes_say():
    """The mass a 4 nm core can hold per molecule at protein density: 4.6 kDa, 42 residues."""
    case, _ = load(FULL)
    mass = math.pi * (CORE_DIAMETER / 2) ** 2 * PER_MOLECULE * PROTEIN_DENSITY
    assert round(mass / 1000, 1) == 4.6 and round(mass / RESIDUE_MASS) == 42
    assert "4.6 kDa" in case.meta["notes"] and "about 42 residues" in case.meta["notes"]


@pytest.mark.parametrize("name", FUSIONS)
def test_a_fusion_takes_the_prion_domain_1_89_and_the_core_end_65(name):
    case, p = load(name)
    assert p.linker == 89 - CORE_END + 1 == 25
    assert "residues 66-89 (24), plus the anchor" in case.meta["notes"]
    assert "PMC122756" in case.meta["citation"]


def test_one_sphere_per_subunit_and_gfp_from_its_structure():
    """A dimer's two domains are two spheres (one domain per subunit), said in the notes; the
    spheres of the others' sizes are test_gallery_files.py's (SIZED); GFP is 1GFL's Rg sphere
    (tests/data/README.md, 43.9 Å), as the other GFP cases'."""
    case, p = load("ure2p_pd_gfp")
    assert p.globule_diameter == 43.9 and "1GFL" in case.meta["notes"]
    assert "each subunit's GST its own sphere" in load("ure2p_pd_gst")[0].meta["notes"]
    assert "each subunit's C-domain is its own sphere" in load(FULL)[0].meta["notes"]
    assert "residues 97-354, one sphere of 258 residues" in load(FULL)[0].meta["notes"]
