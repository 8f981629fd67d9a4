"""Exit codes and the usage error, shared by every command (cli/, sweep/, search/, ...).

Plain Python with no package imports, so any command module can import it without importing
cli/commands.py (which imports the commands).
"""

EXIT_OK, EXIT_INTERSECTION, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130
EXIT_OUTPUT_FAILED = 3  # the run completed but a --pdb/--render output could not be written
EXIT_FAILED = 4  # an unexpected error (a bug or a broken Blender): one line on stderr


class UsageError(Exception):
    """Bad command-line input: printed as one line, exit code 2."""


# The packages the extension's zips bundle as wheels (blender_manifest.toml); distributed and
# dask_jobqueue (--executor dask/slurm) are not bundled.
BUNDLED = ("gemmi", "matplotlib", "tqdm", "PIL")
PIP_NAMES = {"PIL": "pillow", "dask_jobqueue": "dask-jobqueue"}
SHOWN = {"PIL": "Pillow"}  # a module's name as its users know the package


def platform_zip() -> str:
    """The extension zip `make extension` makes for this machine (docs/guide/install.md#which-zip)."""
    import pathlib
    import platform
    import tomllib
    manifest = pathlib.Path(__file__).with_name("blender_manifest.toml")
    version = tomllib.loads(manifest.read_text(encoding="utf-8"))["version"]
    arch = "arm64" if platform.machine().lower() in ("arm64", "aarch64") else "x64"
    system = {"Darwin": "macos", "Windows": "windows"}.get(platform.system(), "linux")
    return f"fibrilfit-{version}-{system}_{arch}.zip"


def where_running() -> str:
    """'extension' (the installed zip, inside Blender), 'blender' (a checkout run by a Blender
    binary: blender -P headless.py), or 'python' (the bpy module, or plain Python)."""
    import sys
    if __package__.startswith("bl_ext."):
        return "extension"
    bpy = sys.modules.get("bpy")
    if bpy is not None and getattr(getattr(bpy, "app", None), "binary_path", ""):
        return "blender"
    return "python"


def missing_packages(names, needed_by: str, where: str | None = None) -> str:
    """One sentence: `needed_by` needs the Python packages `names`, missing here, and what to do
    where this runs. Inside Blender that is the extension zip that bundles them, not a
    `pip install` into a Python that is not Blender's."""
    import sys
    names = list(names)
    shown = [SHOWN.get(n, n) for n in names]
    listed = shown[0] if len(shown) == 1 else ", ".join(shown[:-1]) + " and " + shown[-1]
    package = f"the Python package{'s' if len(names) > 1 else ''} {listed}"
    pip = " ".join(PIP_NAMES.get(n, n) for n in names)
    bundled = all(n in BUNDLED for n in names)
    where = where or where_running()
    if where == "extension" and bundled:
        return (f"{needed_by} needs {package}, which the FibrilFit extension bundles but this "
                f"Blender has not unpacked: install the zip made for this machine "
                f"({platform_zip()}) again (Edit > Preferences > Get Extensions > Install from "
                f"Disk) and restart Blender")
    if where == "blender" and bundled:
        return (f"{needed_by} needs {package}, which this Blender's own Python does not have: "
                f"install the FibrilFit extension zip made for this machine ({platform_zip()}, "
                f"which bundles {'them' if len(names) > 1 else 'it'}) and run `blender -b -c fibrilfit ...`, or use the bpy module "
                f"(make run)")
    if where in ("extension", "blender"):
        return (f"{needed_by} needs {package}, which Blender does not ship and the FibrilFit "
                f"extension does not bundle: install {'them' if len(names) > 1 else 'it'} into this Blender's Python "
                f"({sys.executable} -m pip install {pip})")
    return (f"{needed_by} needs {package}, which this Python ({sys.executable}) does not have: "
            f"pip install {pip}")
