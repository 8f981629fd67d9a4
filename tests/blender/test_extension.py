"""The extension as users get it: the zip that Blender's own CLI builds, installed into a clean
bpy (a temporary user folder) with Blender's install operator, and driven through the installed copy.
"""
import json
import pathlib
import subprocess
import sys
import tomllib
import zipfile

import bpy
import pytest
from helpers import ROOT

SCENARIO = pathlib.Path(__file__).with_name("installed_scenario.py")
VALUES = dict(layers=8, linker=3, frames=80, seed=5)  # as ui_fakes.SMALL: it has clashes
PACKAGE = ROOT / "fibrilfit"  # the extension: its manifest inside, the zip built from it


def blender_ext() -> pathlib.Path:
    """Blender's extension CLI, shipped inside the bpy wheel."""
    path = pathlib.Path(bpy.utils.system_resource("SCRIPTS"), "addons_core", "bl_pkg", "cli",
                        "blender_ext.py")
    assert path.is_file(), path
    return path


def cli(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(blender_ext()), *args], capture_output=True,
                          text=True, timeout=300, cwd=ROOT)


PLATFORMS = {  # Blender's platform: what its wheels' platform tags hold
    "linux_x64": ("manylinux", "x86_64"), "windows_x64": ("win", "amd64"),
    "macos_arm64": ("macosx", "arm64"), "macos_x64": ("macosx", "x86_64")}


@pytest.fixture(scope="module")
def built_zips(tmp_path_factory) -> dict:
    """As `make extension`: the manifest's wheels from PyPI (cached in fibrilfit/wheels/), one
    zip per platform. {platform: zip}."""
    out = tmp_path_factory.mktemp("dist")
    fetched = subprocess.run([sys.executable, str(ROOT / "tools" / "fetch_wheels.py")],
                             capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert fetched.returncode == 0, fetched.stdout + fetched.stderr
    checked = cli("validate", str(PACKAGE))
    assert checked.returncode == 0, checked.stdout + checked.stderr
    built = cli("build", "--source-dir", str(PACKAGE), "--output-dir", str(out),
                "--split-platforms")
    assert built.returncode == 0, built.stdout + built.stderr
    zips = {z.stem.split("-")[-1]: z for z in out.glob("fibrilfit-*.zip")}
    assert set(zips) == set(PLATFORMS), zips
    return zips


@pytest.fixture(scope="module")
def built_zip(built_zips):
    """The one this machine installs (the tests run on Linux x86-64)."""
    return built_zips["linux_x64"]


@pytest.fixture(scope="module")
def installed(built_zip, tmp_path_factory):
    """Run installed_scenario.py in a fresh interpreter with its own user folder."""
    home = tmp_path_factory.mktemp("blender_user")
    env = {"BLENDER_USER_RESOURCES": str(home), "PATH": "/usr/bin:/bin", "HOME": str(home)}
    proc = subprocess.run([sys.executable, str(SCENARIO), str(built_zip), json.dumps(VALUES),
                           str(ROOT / "tests" / "data" / "6cu7.pdb.gz")],
                          capture_output=True, text=True, timeout=600, cwd=home, env=env)
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("RESULT ")]
    assert proc.returncode == 0 and lines, proc.stdout[-3000:] + proc.stderr[-3000:]
    result = json.loads(lines[-1][len("RESULT "):])
    result["home"] = home
    result["stderr"] = proc.stderr
    return result


def extension_files() -> set:
    """What the zip should hold: the package folder's files, less caches."""
    files = set()
    for path in PACKAGE.rglob("*"):
        rel = path.relative_to(PACKAGE)
        if path.is_dir() or "__pycache__" in rel.parts or rel.suffix in (".pyc", ".blend1"):
            continue
        files.add(rel.as_posix())
    return files


def test_the_zip_holds_only_the_extension(built_zip):
    with zipfile.ZipFile(built_zip) as zf:
        names = set(zf.namelist())
        manifest = zf.read("blender_manifest.toml").decode()
    assert {"blender_manifest.toml", "__init__.py", "ui/registration.py", "ui/panels.py"} <= names
    others = {w for w in manifest_wheels() if "manylinux" not in w and "-none-any" not in w}
    assert names == extension_files() - others  # the linux zip: no other platform's wheel
    for name in names:
        assert name.endswith(".py") or name in ("blender_manifest.toml", "README.md", "LICENSE") \
            or name.startswith("wheels/") and name.endswith(".whl")
    # the source manifest, and Blender's generated block naming this platform's wheels
    assert manifest.startswith((PACKAGE / "blender_manifest.toml").read_text(encoding="utf-8"))


def test_installed_and_enabled_it_shows_the_panel_in_the_fibrilfit_tab(installed):
    assert installed["install"] == ["FINISHED"]
    assert installed["enabled"] == ["bl_ext.user_default.fibrilfit"]
    # installed into the temporary user folder, not the user's own
    assert pathlib.Path(installed["module_file"]).is_relative_to(installed["home"])
    assert installed["panel"] == ["bl_ext.user_default.fibrilfit.ui.panels", "VIEW_3D", "UI",
                                  "FibrilFit"]
    assert installed["clone_imported"] == []  # everything ran from the installed copy


def test_the_installed_steps_give_a_verdict(installed):
    steps = installed["steps"]
    assert [state for state, _, _ in steps.values()] == [["FINISHED"]] * 7
    users = len(installed["user_objects"])
    assert [n - users for _, n, _ in steps.values()] == [1, 2, 6, 8, 64, 64, 64]
    assert [stage for _, _, stage in steps.values()] == [
        "slab", "anchor", "linker", "globule", "layers", "baked", "checked"]
    props = installed["props"]
    # VALUES are ui_fakes.SMALL, which clashes (test_ui asserts it; measured: 30 faces, 3 pairs
    # on bpy 4.2, 5.0 and 5.2)
    assert props["verdict"] == "intersection" and props["clash_count"] > 0
    assert props["verdict"] == installed["steps_result"]["verdict"]
    assert props["clash_count"] == len(installed["steps_result"]["clashing_pairs"])


def test_operators_and_the_api_agree_for_one_seed(installed):
    mine, run_all, api = (installed[k] for k in ("steps_result", "run_all_result", "api_result"))
    for key in ("verdict", "gravity", "intersecting_faces", "clashing_pairs", "max_bond_stretch",
                "max_bond_stretch_bake", "globule_centres", "accommodated", "seed", "params"):
        assert mine[key] == run_all[key] == api[key], key


def test_run_all_keeps_one_model_and_clear_removes_exactly_it(installed):
    whole = installed["steps"]["check_intersections"][1]
    assert installed["join"] == [["FINISHED"], whole + 1]  # the joined copy
    assert installed["run_all"][:2] == [["FINISHED"], whole]
    assert installed["run_all"][2] == installed["props"]["verdict"]
    assert installed["clear"] == [["FINISHED"], installed["user_objects"]]


def test_disable_enable_three_times_without_error_or_leftover(installed):
    assert installed["cycle_errors"] == []
    registered = installed["types"]
    assert registered and "FIBRILFIT_PT_main" in registered
    for off, on in installed["cycles"]:
        assert off == [[], False]
        assert on == [registered, True]


def test_the_installed_command_line_runs_like_headless(installed):
    """`blender -c fibrilfit ...`: the callback register() gave Blender, from the installed copy."""
    module = "bl_ext.user_default.fibrilfit.cli.entry.command"
    assert installed["cli_registered"] == [["fibrilfit", module]] * 4  # install + 3 re-enables
    assert installed["cli_released"] == 3                             # 3 disables
    run = installed["cli_run"]
    assert run["code"] == 0 and run["stderr"] == "" and "verdict:" in run["stdout"]
    mine = {k: v for k, v in installed["cli_result"].items()
            if k not in ("timings_s", "sources")}  # the command line adds where values came from
    assert mine == installed["api_result"]
    # the command reset the scene but not the preferences: FibrilFit is still enabled
    assert installed["cli_enabled_after"] == installed["enabled"]
    bad = installed["cli_bad"]
    assert bad["code"] == 2 and bad["stdout"] == ""
    assert bad["stderr"].startswith("fibrilfit: error: layers: ") and bad["stderr"].count("\n") == 1


def test_the_installed_command_line_sweeps_with_the_installed_files(installed):
    sweep = installed["cli_sweep"]
    assert sweep["code"] == 0, sweep["stderr"]
    (line,) = installed["cli_sweep_results"]
    assert line["status"] == "ok"
    for key in ("verdict", "gravity", "clashing_pairs", "max_bond_stretch", "params"):
        assert line[key] == installed["api_result"][key], key


def test_the_installed_wheels_outlive_the_sweeps_workers(installed):
    """A worker resets to factory settings before each run, which makes Blender uninstall the
    wheels of extensions it does not see enabled; the workers keep their own extensions folder
    (batch/pool.py's worker_env), so the installed copy keeps its matplotlib and gemmi."""
    assert installed["cli_sweep"]["code"] == 0
    assert {"matplotlib", "PIL", "gemmi", "contourpy", "kiwisolver", "fontTools", "tqdm",
            "dateutil"} <= set(installed["wheels_after_sweep"]), installed["wheels_after_sweep"]


def manifest_wheels() -> list:
    manifest = tomllib.loads((PACKAGE / "blender_manifest.toml").read_text(encoding="utf-8"))
    assert manifest["platforms"] == ["linux-x64", "windows-x64", "macos-arm64", "macos-x64"]
    return [w.removeprefix("./") for w in manifest["wheels"]]


def test_the_manifest_lists_every_wheel_for_every_platform_and_python():
    wheels = manifest_wheels()
    for plat, machine in PLATFORMS.values():
        for py in ("cp311", "cp313"):
            for name in ("gemmi", "matplotlib", "contourpy", "kiwisolver", "pillow"):
                (one,) = [w for w in wheels if w.startswith(f"wheels/{name}-") and
                          f"-{py}-" in w and plat in w and machine in w]
    # numpy is Blender's own: a second numpy would shadow it
    assert not any(w.startswith("wheels/numpy-") for w in wheels)


def test_each_zip_validates_and_carries_only_its_own_platforms_wheels(built_zips):
    wheels = manifest_wheels()
    pure = {w for w in wheels if w.endswith("-none-any.whl")}
    assert {w.split("/")[1].split("-")[0] for w in pure} >= {
        "tqdm", "cycler", "fonttools", "packaging", "pyparsing", "python_dateutil", "tzdata"}
    for platform, (plat, machine) in PLATFORMS.items():
        checked = cli("validate", str(built_zips[platform]))
        assert checked.returncode == 0, checked.stdout + checked.stderr
        with zipfile.ZipFile(built_zips[platform]) as zf:
            carried = {n for n in zf.namelist() if n.endswith(".whl")}
            manifest = zf.read("blender_manifest.toml").decode()
        own = {w for w in wheels if plat in w and machine in w}
        assert carried == own | pure, (platform, sorted(carried ^ (own | pure)))
        assert len(own) == 10  # gemmi, matplotlib, contourpy, kiwisolver, pillow x 2 Pythons
        generated = tomllib.loads(manifest)["build"]["generated"]  # what Blender installs by
        assert generated["platforms"] == [platform.replace("_", "-")]
        assert {w.removeprefix("./") for w in generated["wheels"]} == own | pure


def test_the_installed_copy_reads_structures_with_its_own_gemmi_wheel(installed):
    """Blender's installer unpacks the wheel for this platform into the user's extensions/.local
    site-packages and puts it on sys.path, in the bpy module too; the default model never
    imports gemmi."""
    assert installed["gemmi_loaded_by_the_model"] is False
    (local,) = installed["wheel_site_packages"]
    assert pathlib.Path(local).is_relative_to(installed["home"])
    assert pathlib.Path(installed["gemmi_file"]).is_relative_to(local)
    rise, twist, k = installed["fibril"]
    # tests/data/README.md's 6CU7: 4.825 Å per layer (the 4.8 default fails), left-handed, 2
    assert abs(rise - 4.825) < 0.002 and twist < 0 and k == 2
