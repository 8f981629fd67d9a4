"""Shared test helpers (conftest holds the fixtures)."""
import importlib.util
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def bench_module(name: str):
    """bench/<name>.py, imported (bench is scripts, not a package)."""
    spec = importlib.util.spec_from_file_location(f"bench_{name}", ROOT / "bench" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def makefile_bpy() -> dict[str, str]:
    """The bpy versions `make` installs, {"BPY": "5.0.1", "BPY_LTS": ..., "BPY_52": ...}, read from
    the Makefile (the one place they are set): a test pinned to one bpy names one of these
    (tests/unit/test_no_silent_skip.py), so bumping a version cannot turn it into a skip."""
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    found = dict(re.findall(r"^(BPY|BPY_LTS|BPY_52) \?= (\S+)\s*$", text, re.M))
    assert set(found) == {"BPY", "BPY_LTS", "BPY_52"}, f"the Makefile's bpy versions: {found}"
    return found


def snapshot_user(objects) -> dict:
    return {name: (ob.name, tuple(ob.location), ob.data.name, [c.name for c in ob.users_collection])
            for name, ob in objects.items()}


def run_cli(*args, timeout=600):
    """Run headless.py under this interpreter; return the CompletedProcess."""
    return subprocess.run([sys.executable, str(ROOT / "headless.py"), *args], capture_output=True,
                          text=True, timeout=timeout, cwd=ROOT)


def cli_in_process(*args):
    """`headless.py ARGS` run in this process, as headless.py calls it (fibrilfit.cli.entry.main,
    from the repository's root), for a refusal: it stops before any model is built, so the
    seconds of a fresh process's bpy import buy nothing. Returns what run_cli returns
    (returncode, stdout, stderr: what Python printed; C code's output is not captured). Each
    command keeps one refusal through run_cli, for the real process's stderr and exit code."""
    import contextlib
    import io

    from fibrilfit.cli import entry
    out, err = io.StringIO(), io.StringIO()
    with contextlib.chdir(ROOT), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = entry.main(list(args), prog="headless.py")
    return subprocess.CompletedProcess(["headless.py", *args], code, out.getvalue(), err.getvalue())


def synthetic_full_length(tmp_path, *, shift: int = 0, flat: bool = False, name="fl.pdb"):
    """A predicted full-length chain in 6CU7's numbering: a low-pLDDT N-terminal tail 1-37,
    the fibril core 38-97 (6CU7 chain A, confident: it must not count as a domain), a
    low-pLDDT linker 98-127, then ubiquitin as residues 128-203 (confident, with a 2-residue
    dip in a loop)."""
    import gemmi
    data = ROOT / "tests" / "data"
    six = gemmi.read_structure(str(data / "6cu7.pdb.gz"))
    ubq = gemmi.read_structure(str(data / "1ubq.pdb.gz"))
    st = gemmi.Structure()
    model = gemmi.Model("1")
    chain = gemmi.Chain("A")

    def ca_residue(num, xyz, b):
        r = gemmi.Residue()
        r.name, r.seqid = "GLY", gemmi.SeqId(num + shift, " ")
        a = gemmi.Atom()
        a.name, a.element, a.pos, a.b_iso = "CA", gemmi.Element("C"), gemmi.Position(*xyz), b
        r.add_atom(a)
        return r

    for n in range(1, 38):
        chain.add_residue(ca_residue(n, (-100 - 3.8 * n, 0, 0), 35.0))
    for res in six[0]["A"]:
        if 38 <= res.seqid.num <= 97:
            r = res.clone()
            r.seqid = gemmi.SeqId(res.seqid.num + shift, " ")
            for a in r:
                a.b_iso = 88.0
            chain.add_residue(r)
    for n in range(98, 128):
        chain.add_residue(ca_residue(n, (100 + 3.8 * (n - 98), 0, 0), 30.0))
    for res in ubq[0]["A"]:
        if res.het_flag == "H" or res.name == "HOH":
            continue
        r = res.clone()
        r.seqid = gemmi.SeqId(res.seqid.num + 127 + shift, " ")
        for a in r:
            a.b_iso = 60.0 if res.seqid.num in (46, 47) else 91.0
        chain.add_residue(r)
    if flat:
        for r in chain:
            for a in r:
                a.b_iso = 50.0
    model.add_chain(chain)
    st.add_model(model)
    st.setup_entities()
    out = tmp_path / name
    st.write_pdb(str(out))
    return out
