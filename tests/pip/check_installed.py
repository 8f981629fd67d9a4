"""The pip route, checked in a fresh venv (`make test-pip`): run by that venv's Python after
`pip install fibrilfit-*.whl`, from a folder outside the checkout, so what runs is the installed
package and its `fibrilfit` command, with the dependencies pip declared (pyproject.toml).

    out/pip/venv/bin/python tests/pip/check_installed.py CHECKOUT WHEEL

Each check prints what it found; the first that fails exits 1 with what it got instead.
"""
import json
import pathlib
import subprocess
import sys
import sysconfig
import tomllib
import zipfile


def main(checkout: pathlib.Path, wheel: pathlib.Path) -> int:
    bin_dir = pathlib.Path(sys.executable).parent
    fibrilfit = str(bin_dir / "fibrilfit")
    data = checkout / "tests" / "data"
    version = tomllib.loads((checkout / "fibrilfit" / "blender_manifest.toml")
                           .read_text(encoding="utf-8"))["version"]

    def run(*argv):
        cp = subprocess.run(argv, capture_output=True, text=True, timeout=600)
        if cp.returncode != 0:
            fail(f"{' '.join(argv)} exited {cp.returncode}: {cp.stderr.strip()[-500:]}")
        return cp.stdout

    # The wheel holds the package alone: no tests, tools, docs, nor the extension's wheels/.
    names = zipfile.ZipFile(wheel).namelist()
    extra = [n for n in names if not (n.startswith("fibrilfit/") and (n.endswith(".py") or n ==
             "fibrilfit/blender_manifest.toml")) and not n.startswith(f"fibrilfit-{version}.dist-info/")]
    check(not extra and "fibrilfit/__main__.py" in names,
          f"the wheel holds fibrilfit/'s {len(names)} files and metadata only", f"also {extra}")

    # The installed copy, not the checkout's fibrilfit/ (this script runs outside the checkout).
    where = run(sys.executable, "-c", "import fibrilfit; print(fibrilfit.__file__)").strip()
    site = sysconfig.get_paths()["purelib"]
    check(where.startswith(site), f"fibrilfit imported from {site}", where)
    got = run(fibrilfit, "--version").strip()
    check(got == f"FibrilFit {version}", f"fibrilfit --version: FibrilFit {version}", got)
    got = run(sys.executable, "-m", "fibrilfit", "--version").strip()
    check(got == f"FibrilFit {version}", f"python -m fibrilfit --version: FibrilFit {version}", got)

    # A model: bpy came with the package. 4 layers at the defaults, seed 0 (measured: successful,
    # accommodated, with bpy 5.0.1 on Python 3.11, 2026-11-25).
    result = json.loads(run(fibrilfit, "run", "--layers", "4", "--json", "-"))
    got = (result["params"]["layers"], result["fibrilfit_version"], result["verdict"],
           result["accommodated"], result["answer"])
    check(got == (4, version, "successful", True, "fits"),
          f"run --layers 4 --json -: layers 4, version {version}, successful, accommodated, fits",
          got)

    # Structure files: gemmi came with the package (inspect as in docs/guide/install.md#pip).
    text = run(fibrilfit, "inspect", "--fibril", str(data / "6cu7.pdb.gz"),
               "--domain", str(data / "1ubq.pdb.gz"))
    for line in ("  rise 4.825 ± 0.041 Å, twist -0.01678 ± 0.00196 rad (-0.961° per layer, left-handed)",
                 "  rg 11.73 Å, globule_diameter 30.28 Å (2·√(5/3)·Rg; largest dimension 44.0 Å)"):
        check(line in text.splitlines(), f"inspect printed {line.strip()!r}", text)
    return 0


def check(ok: bool, claim: str, got="") -> None:
    if not ok:
        fail(f"{claim}; got: {got}")
    print(f"pip: ok: {claim}")


def fail(what: str) -> None:
    print(f"pip: FAILED: {what}", file=sys.stderr)
    sys.exit(1)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: check_installed.py CHECKOUT WHEEL")
    sys.exit(main(pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()))
