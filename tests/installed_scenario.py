"""Drive the installed extension in a fresh interpreter; tests/test_extension.py runs this.

    BLENDER_USER_RESOURCES=<tmp> python installed_scenario.py <zip> '<params as JSON>' [fibril]

Installs the zip into the temporary user folder with Blender's own operator, enables it, runs
every operator of the installed copy in the startup scene (whose Cube, Light and Camera stand for
the user's objects), reads the fibril file (if given) with the gemmi of the extension's wheel,
and prints one line "RESULT <json>" of what it saw. Asserts nothing itself.
"""
import json
import os
import sys

import bpy
import addon_utils  # noqa: E402  (importable once bpy is)

STEPS = ("build_slab", "build_anchor", "build_linker", "build_globule", "replicate_layers",
         "bake", "check_intersections")


def fibrilfit_types():
    return sorted(name for name in dir(bpy.types) if name.startswith("FIBRILFIT_"))


def main(zip_path: str, values: dict, fibril: str | None = None) -> dict:
    out = {}
    out["install"] = sorted(bpy.ops.extensions.package_install_files(
        filepath=zip_path, repo="user_default", enable_on_install=True))
    enabled = [m for m in bpy.context.preferences.addons.keys() if m.endswith(".fibrilfit")]
    out["enabled"] = enabled
    name = enabled[0]
    ff = sys.modules[name]
    out["module_file"] = ff.__file__
    panel = bpy.types.FIBRILFIT_PT_main
    out["panel"] = [panel.__module__, panel.bl_space_type, panel.bl_region_type,
                    panel.bl_category]
    out["types"] = fibrilfit_types()

    scene = bpy.context.scene
    out["user_objects"] = sorted(o.name for o in scene.objects)
    settings = scene.fibrilfit
    ff.properties.write_params(settings, ff.params.make_params(**values))

    def stored():
        root = ff.builders.scene.find_root(scene)
        return json.loads(root[ff.operators.common.RESULT])

    out["steps"] = {}
    for op in STEPS:
        state = sorted(getattr(bpy.ops.fibrilfit, op)())
        out["steps"][op] = [state, len(scene.objects), ff.builders.model_stage(scene)]
    out["props"] = {k: getattr(settings, k) for k in ff.properties.RESULTS}
    out["steps_result"] = stored()
    out["join"] = [sorted(bpy.ops.fibrilfit.join_globules()), len(scene.objects)]
    out["run_all"] = [sorted(bpy.ops.fibrilfit.run_all()), len(scene.objects), settings.verdict]
    out["run_all_result"] = stored()
    out["clear"] = [sorted(bpy.ops.fibrilfit.clear()), sorted(o.name for o in scene.objects)]
    api = ff.run(ff.params.make_params(**values), scene)  # the API of the installed copy
    out["api_result"] = {k: v for k, v in api.items() if k != "timings_s"}
    bpy.ops.fibrilfit.clear()

    errors = []
    cycles = []
    for _ in range(3):
        addon_utils.disable(name, default_set=True, handle_error=errors.append)
        off = [fibrilfit_types(), hasattr(bpy.types.Scene, "fibrilfit")]
        addon_utils.enable(name, default_set=True, handle_error=errors.append)
        on = [fibrilfit_types(), hasattr(bpy.types.Scene, "fibrilfit")]
        cycles.append([off, on])
    out["cycles"] = cycles
    out["cycle_errors"] = [repr(e) for e in errors]
    out["clone_imported"] = sorted(m for m in sys.modules if m.split(".")[0] == "fibrilfit")
    out["gemmi_loaded_by_the_model"] = "gemmi" in sys.modules  # it must be lazy
    if fibril:
        # Blender unpacks the extension's wheel for this platform and Python into the user's
        # extensions/.local site-packages and appends that folder to sys.path. The test venv
        # has its own gemmi earlier on sys.path: put Blender's folder first, so that the import
        # below can only succeed from the extension's wheel.
        home = os.environ["BLENDER_USER_RESOURCES"]
        local = [p for p in sys.path if p.startswith(home) and "site-packages" in p]
        out["wheel_site_packages"] = local
        for p in local:
            sys.path.remove(p)
        sys.path[:0] = local
        import gemmi
        out["gemmi_file"] = gemmi.__file__
        g = ff.structure.measure_fibril(fibril)
        out["fibril"] = [g.rise, g.twist, g.protofilaments]
    return out


if __name__ == "__main__":
    print("RESULT " + json.dumps(main(sys.argv[1], json.loads(sys.argv[2]), *sys.argv[3:4])))
