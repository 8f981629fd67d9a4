"""Fetch the wheels that blender_manifest.toml lists (gemmi, matplotlib and its compiled
dependencies for every platform and Python of the supported Blenders; tqdm and matplotlib's
pure-Python dependencies) into fibrilfit/wheels/, with pip download from PyPI. `make extension`
runs it.

    python tools/fetch_wheels.py          # missing ones only; other .whl files in wheels/ removed

The manifest is the one list: each file name gives pip the version, Python and platform tags.
"""
import pathlib
import subprocess
import sys
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "fibrilfit"  # the manifest and its wheels/ folder


def listed() -> list:
    manifest = tomllib.loads((PACKAGE / "blender_manifest.toml").read_text(encoding="utf-8"))
    return [PACKAGE / w for w in manifest.get("wheels", [])]


def pip_args(wheel: pathlib.Path) -> list:
    """gemmi-0.7.5-cp311-cp311-manylinux_2_27_x86_64.manylinux_2_28_x86_64.whl -> pip options.
    A build tag (gemmi-0.7.5-0-cp313-...) is ours: PyPI's file has none (see the manifest)."""
    parts = wheel.name[:-4].split("-")
    name, version, python, _abi, platforms = parts[:2] + parts[-3:]
    if platforms == "any":  # a pure-Python wheel (tqdm-4.70.1-py3-none-any.whl): one for all.
        # Asked for as such: of fonttools pip would otherwise take this machine's compiled wheel
        return ["--only-binary=:all:", "--no-deps", "--platform", "any", "--implementation", "py",
                "--abi", "none", "--python-version", "3.11", f"{name}=={version}"]
    args = ["--only-binary=:all:", "--no-deps", "--python-version", f"{python[2]}.{python[3:]}"]
    for platform in platforms.split("."):
        args += ["--platform", platform]
    return args + [f"{name}=={version}"]


def fetch(quiet: bool = True) -> list:
    wheels = listed()
    folder = PACKAGE / "wheels"
    folder.mkdir(exist_ok=True)
    for extra in set(folder.glob("*.whl")) - set(wheels):
        extra.unlink()  # the zip takes every file in wheels/: keep exactly the listed ones
    for wheel in wheels:
        if wheel.is_file():
            continue
        subprocess.run([sys.executable, "-m", "pip", "download", *(["--quiet"] if quiet else []),
                        *pip_args(wheel), "-d", str(folder)], check=True)
        parts = wheel.name.split("-")
        if len(parts) == 6:  # our build tag: rename PyPI's file
            (folder / "-".join(parts[:2] + parts[3:])).rename(wheel)
        if not wheel.is_file():
            sys.exit(f"fetch_wheels: pip did not produce {wheel.name} (is the manifest's name "
                     "exactly PyPI's?)")
    return wheels


if __name__ == "__main__":
    for w in fetch(quiet=False):
        print(w.relative_to(ROOT))
