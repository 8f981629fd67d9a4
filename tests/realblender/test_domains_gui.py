"""Several domains and a full-length model from the sidebar, in Blender 4.3.2's window under Xvfb
(issue #33, docs/guide/sidebar.md#domains): domains_probe.py presses the panel's operators
(Import fibril…, Import domain… twice, then Import full-length model…, each with the path its
file browser would give, and Run all in the window); the parameters the panel ran with and the
verdict it shows must be those of `blender -b -c fibrilfit run` with the same options."""
import json

import pytest

from realblender.helpers import OUT, ROOT, chroot, inside, quote, read_json

pytestmark = pytest.mark.timeout(1500)  # two runs in the window and two on the command line

DATA = ROOT / "tests" / "data"
# Small and fast: 3 layers, 10 frames of the tutorial protocol, the panel's defaults otherwise
# (the question here is the parameters and the verdict being the command line's, not the fit).
VALUES = {"layers": 3, "frames": 10}
OPTIONS = ["--layers", "3", "--frames", "10"]


def renumbered(folder, shift: int):
    """Ubiquitin numbered from 1 + shift (as tests/blender/test_domains.py's)."""
    import gemmi
    st = gemmi.read_structure(str(DATA / "1ubq.pdb.gz"))
    for ch in st[0]:
        for res in ch:
            res.seqid.num += shift
    out = folder / f"ubq{shift}.pdb"
    st.write_pdb(str(out))
    return out


@pytest.fixture(scope="module")
def session(installed):
    """The files on the host (gemmi), the window's session in the chroot; returns the cases'
    files and what the panel showed."""
    from full_length_model import two_domain_model
    folder = OUT / "domains"
    folder.mkdir(parents=True, exist_ok=True)
    fibril = DATA / "6cu7.pdb.gz"
    near, far = renumbered(folder, 127), renumbered(folder, 229)
    full = two_domain_model(folder / "full_length.pdb")
    cases = [
        {"name": "two domains", "cli": ["--fibril", fibril, "--domain", near, "--domain", far],
         "imports": [["fibrilfit.import_fibril", {"filepath": inside(fibril)}],
                     ["fibrilfit.import_domain", {"filepath": inside(near)}],
                     ["fibrilfit.import_domain", {"filepath": inside(far)}]]},
        {"name": "full-length model", "cli": ["--fibril", fibril, "--full-length", full],
         "imports": [["fibrilfit.import_full_length", {"filepath": inside(full)}]]},
    ]
    (folder / "steps.json").write_text(json.dumps(
        {"values": VALUES, "cases": [{k: c[k] for k in ("name", "imports")} for c in cases]}))
    cp = chroot(f"python3 tests/realblender/domains_session.py {inside(folder)}", timeout=1200)
    results = read_json(folder / "results.json") if (folder / "results.json").exists() else {}
    assert cp.returncode == 0 and "error" not in results, (cp.stderr[-2000:],
                                                          results.get("error"))
    return cases, results


def test_the_panels_domains_run_as_the_command_line(session):
    cases, results = session
    assert results["blender"].startswith("4.3.2")
    shown = {r["name"]: r for r in results["cases"]}
    # what the imports put in the list: the numbering's linkers (26 between the ubiquitins; the
    # model's 15 between ubiquitin and GFP), the last domain's unused
    assert [d.split(",")[0] for d in shown["two domains"]["domains"]] == [
        "ubq127.pdb A 128-203", "ubq229.pdb A 230-305"]
    assert shown["two domains"]["linkers"][0] == 26
    assert [d.split(",")[0] for d in shown["full-length model"]["domains"]] == [
        "full_length.pdb A 118-193", "full_length.pdb A 209-438"]
    assert shown["full-length model"]["linkers"][0] == 15
    for case in cases:
        out = OUT / "domains" / f"{case['name'].replace(' ', '-')}.json"
        args = ["run", *(inside(a) if not isinstance(a, str) else a for a in case["cli"]),
                *OPTIONS, "--json", inside(out)]
        cp = chroot(f"blender -b -c fibrilfit {quote(args)}")
        assert cp.returncode == 0, cp.stderr[-2000:]
        ref, panel = read_json(out), shown[case["name"]]
        assert panel["params"] == ref["params"], case["name"]
        assert panel["verdict"] == ref["verdict"], case["name"]
        assert panel["clash_count"] == len(ref["clashing_pairs"]), case["name"]
        assert panel["accommodated"] == ref["accommodated"], case["name"]
        assert panel["max_bond_stretch"] == pytest.approx(ref["max_bond_stretch"], abs=1e-6)
    # the full-length model's linker from the core: 20 residues after K97, 21 with the anchor
    assert shown["full-length model"]["params"]["linker"] == 21
    assert shown["full-length model"]["params"]["domain_linker"] == [15]
