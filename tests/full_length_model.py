"""A two-domain full-length model built from deposited pieces, for `--full-length`
(docs/guide/atoms-and-domains.md#full-length-models): no predicted model of a protein with an
amyloid core and two folded domains is in the repository, so this one is assembled from
tests/data/ in 6CU7's numbering, with pLDDT written into the B-factors as a predictor would:

    1-37     N-terminal tail, CA only, pLDDT 35 (disordered)
    38-97    6CU7 chain A, the fibril core (α-synuclein 38-97), pLDDT 88
    98-117   linker 1, 20 residues, CA only, pLDDT 30
    118-193  ubiquitin, 1UBQ chain A residues 1-76, pLDDT 91
    194-208  linker 2, 15 residues, CA only, pLDDT 30
    209-438  GFP, 1GFL chain A residues 1-230, pLDDT 90

Each piece keeps its deposited coordinates, moved along x so the pieces lie apart (a domain's
shape and size do not depend on where it sits); the linkers' CAs are 3.8 Å apart on lines
between them. Not a prediction: a test object whose right answer is known by construction.

    python tests/full_length_model.py OUT.pdb      # writes it (gemmi)
"""
from __future__ import annotations

import pathlib
import sys

DATA = pathlib.Path(__file__).resolve().parent / "data"
PIECES = [  # (first residue in the model, file, chain, first, last, pLDDT, shift along x)
    (38, "6cu7.pdb.gz", "A", 38, 97, 88.0, 0.0),
    (118, "1ubq.pdb.gz", "A", 1, 76, 91.0, 150.0),
    (209, "1gfl.pdb.gz", "A", 1, 230, 90.0, 300.0),
]
DISORDERED = [(1, 37, 35.0, (-100.0, -3.8)), (98, 117, 30.0, (60.0, 3.8)),
              (194, 208, 30.0, (220.0, 3.8))]  # (first, last, pLDDT, (x start, step))
DOMAINS = [(118, 193), (209, 438)]
LINKERS = [(98, 117, 20), (194, 208, 15)]


def two_domain_model(out: pathlib.Path) -> pathlib.Path:
    import gemmi
    residues = {}
    for first, last, plddt, (x0, step) in DISORDERED:
        for n in range(first, last + 1):
            r = gemmi.Residue()
            r.name, r.seqid = "GLY", gemmi.SeqId(n, " ")
            a = gemmi.Atom()
            a.name, a.element, a.b_iso = "CA", gemmi.Element("C"), plddt
            a.pos = gemmi.Position(x0 + step * (n - first), 40.0, 0.0)
            r.add_atom(a)
            residues[n] = r
    for start, name, chain, first, last, plddt, shift in PIECES:
        st = gemmi.read_structure(str(DATA / name))
        for res in st[0][chain]:
            if not first <= res.seqid.num <= last or res.name == "HOH":
                continue
            r = res.clone()
            r.seqid = gemmi.SeqId(res.seqid.num - first + start, " ")
            r.het_flag = "A"
            for a in r:
                a.b_iso = plddt
                a.pos = gemmi.Position(a.pos.x + shift, a.pos.y, a.pos.z)
            residues[r.seqid.num] = r
    chain = gemmi.Chain("A")
    for n in sorted(residues):
        chain.add_residue(residues[n])
    model = gemmi.Model("1")
    model.add_chain(chain)
    st = gemmi.Structure()
    st.add_model(model)
    st.setup_entities()
    st.write_pdb(str(out))
    return out


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: python tests/full_length_model.py OUT.pdb")
    print(two_domain_model(pathlib.Path(sys.argv[1])))
