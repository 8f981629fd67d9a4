"""exits.missing_packages: a missing package refused in one sentence whose advice fits where it
runs (issue #33: inside Blender "pip install matplotlib" was wrong; the zip bundles it)."""
import sys

from fibrilfit import exits


def test_in_the_installed_extension_the_advice_is_the_zip_for_this_machine():
    line = exits.missing_packages(["matplotlib"], "the report", where="extension")
    assert line.startswith("the report needs the Python package matplotlib, which the FibrilFit "
                           "extension bundles")
    assert exits.platform_zip() in line and "pip" not in line and "\n" not in line


def test_in_blender_from_a_checkout_the_advice_is_the_extension():
    line = exits.missing_packages(["tqdm", "PIL"], "the sweep", where="blender")
    assert line.startswith("the sweep needs the Python packages tqdm and Pillow, which this "
                           "Blender's own Python does not have: install the FibrilFit extension")
    assert "blender -b -c fibrilfit" in line and "pip" not in line


def test_a_package_the_zip_does_not_bundle_goes_into_blenders_python():
    line = exits.missing_packages(["distributed"], "--executor dask", where="extension")
    assert line.endswith(f"install it into this Blender's Python ({sys.executable} -m pip "
                         f"install distributed)")


def test_outside_blender_the_advice_is_pip():
    line = exits.missing_packages(["PIL"], "a .gif", where="python")
    assert line == (f"a .gif needs the Python package Pillow, which this Python "
                    f"({sys.executable}) does not have: pip install pillow")
    assert exits.where_running() == "python"  # the test venv: the package from the checkout


def test_the_platform_zip_is_one_that_make_extension_builds():
    import tomllib
    from pathlib import Path
    manifest = tomllib.loads((Path(exits.__file__).with_name("blender_manifest.toml"))
                             .read_text(encoding="utf-8"))
    platforms = [p.replace("-", "_") for p in manifest["platforms"]]
    assert exits.platform_zip() in {f"fibrilfit-{manifest['version']}-{p}.zip" for p in platforms}
