"""The installable package (pyproject.toml, docs/guide/install.md#pip): the version said once (the
manifest), what `import fibrilfit` exports, the `fibrilfit` command's entry point, and the
dependencies each Python gets. `make test-pip` installs the built wheel in a fresh venv and runs
it; these are the seconds-long checks of the same promises from the checkout."""
import ast
import pathlib
import subprocess
import sys
import tomllib

from packaging.requirements import Requirement

ROOT = pathlib.Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
MANIFEST = tomllib.loads((ROOT / "fibrilfit" / "blender_manifest.toml").read_text(encoding="utf-8"))


def test_the_version_is_said_once_in_the_manifest():
    import fibrilfit
    assert "version" not in PYPROJECT["project"] and "version" in PYPROJECT["project"]["dynamic"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "fibrilfit.__version__"}
    assert fibrilfit.__version__ == MANIFEST["version"]


def test_the_command_and_python_m_print_the_version():
    for argv in ([sys.executable, "-m", "fibrilfit", "--version"],
                 [sys.executable, "headless.py", "--version"]):
        done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=60)
        assert (done.returncode, done.stdout) == (0, f"FibrilFit {MANIFEST['version']}\n"), argv
    assert PYPROJECT["project"]["scripts"] == {"fibrilfit": "fibrilfit.__main__:main"}


def test_the_command_has_headless_py_s_subcommands():
    from fibrilfit.cli import build_parser
    from fibrilfit.cli.commands import COMMANDS
    parser = build_parser("fibrilfit")
    sub = next(a for a in parser._actions if a.dest == "command")
    assert set(sub.choices) == set(COMMANDS) == {"run", "sweep", "inspect", "minimal-linker",
                                                 "largest-fraction", "report"}
    done = subprocess.run([sys.executable, "-m", "fibrilfit", "run", "--linker", "0"], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and done.stderr.startswith("fibrilfit: error: ") \
        and "linker" in done.stderr and len(done.stderr.splitlines()) == 1, done.stderr


def test_every_exported_name_exists():
    """`fibrilfit.__all__` names only what the package gives (it once exported a `params` that
    no longer existed); run_model and make_params are found without importing bpy."""
    import fibrilfit
    for name in fibrilfit.__all__:
        if name in fibrilfit.LAZY:
            module = ROOT / "fibrilfit" / (fibrilfit.LAZY[name].lstrip(".").replace(".", "/") + ".py")
            tree = ast.parse(module.read_text(encoding="utf-8"))
            assert name in {n.name for n in tree.body if isinstance(n, ast.FunctionDef)}, name
        else:
            assert getattr(fibrilfit, name) is not None, name
    assert {"run_model", "make_params", "__version__"} <= set(fibrilfit.__all__)


def requirements(python: str, extra: str = "") -> dict:
    """name -> specifier that pip installs for a Python version (the markers evaluated)."""
    env = {"python_version": python, "extra": extra}
    reqs = [Requirement(r) for r in PYPROJECT["project"]["dependencies"]]
    reqs += [Requirement(r) for r in PYPROJECT["project"]["optional-dependencies"].get(extra, [])]
    return {r.name: str(r.specifier) for r in reqs if not r.marker or r.marker.evaluate(env)}


def test_each_python_gets_the_bpy_and_numpy_it_is_tested_with():
    py311, py313, py312 = requirements("3.11"), requirements("3.13"), requirements("3.12")
    assert Requirement("bpy" + py311["bpy"]).specifier.contains("5.0.1")
    assert Requirement("bpy" + py311["bpy"]).specifier.contains("4.2.0")
    assert not Requirement("bpy" + py311["bpy"]).specifier.contains("5.2.3")  # Python 3.13 only
    assert Requirement("bpy" + py313["bpy"]).specifier.contains("5.2.3")
    assert not Requirement("numpy" + py311["numpy"]).specifier.contains("2.2.0")  # bpy 5.0: numpy<2
    assert Requirement("numpy" + py313["numpy"]).specifier.contains("2.2.0")
    assert "bpy" not in py312  # no bpy wheel for Python 3.12: inspect only
    for deps in (py311, py313):
        assert {"bpy", "numpy", "gemmi", "tqdm", "matplotlib"} == set(deps)
    assert {"distributed", "dask-jobqueue"} <= set(requirements("3.11", "cluster"))
