"""`--full-length` on a two-domain model built from deposited pieces (tests/full_length_model.py:
6CU7's core, a 20-residue linker, ubiquitin, a 15-residue linker, GFP) finds both domains, at
their deposited sizes, and both linkers."""
import pytest
from full_length_model import DOMAINS, LINKERS, two_domain_model
from helpers import ROOT

from fibrilfit import structure as S
from fibrilfit.structure import full_length

DATA = ROOT / "tests" / "data"


def test_the_two_domains_and_linkers_are_found(tmp_path):
    model = two_domain_model(tmp_path / "two.pdb")
    core = S.measure_fibril(DATA / "6cu7.pdb.gz").core_residues
    seg = full_length.segment(model, core)
    assert seg.core == [38, 97] and seg.residues == [1, 438]
    assert [(d["first"], d["last"]) for d in seg.domains] == DOMAINS
    assert [(k["first"], k["last"], k["length"]) for k in seg.linkers] == LINKERS
    # 2·√(5/3)·Rg of 1UBQ and of 1GFL chain A: tests/data/README.md's Rg 11.73 and 17.02 Å
    assert [d["diameter"] for d in seg.domains] == pytest.approx([30.28, 43.94], abs=0.02)
    assert [d["plddt_mean"] for d in seg.domains] == pytest.approx([91.0, 90.0])
