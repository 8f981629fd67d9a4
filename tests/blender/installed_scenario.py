"""Drive the installed extension in a fresh interpreter; tests/blender/test_extension.py runs this.

    BLENDER_USER_RESOURCES=<tmp> python installed_scenario.py <zip> '<params as JSON>' [fibril]

Installs the zip into the temporary user folder with Blender's own operator, enables it, runs
every operator of the installed copy in the startup scene (whose Cube, Light and Camera stand for
the user's objects), then its command line (`blender -c fibrilfit`, through the callback that
register() hands to bpy.utils.register_cli_command), reads the fibril file (if given) with the
gemmi of the extension's wheel, and prints one line "RESULT <json>" of what it saw. Asserts
nothing itself.
"""
import contextlib
import io
import json
import os
import pathlib
import sys
import tempfile

import bpy
import addon_utils  # noqa: E402  (importable once bpy is)

STEPS = ("build_slab", "build_anchor", "build_linker", "build_globule", "replicate_layers",
         "bake", "check_intersections")


def fibrilfit_types():
    return sorted(name for name in dir(bpy.types) if name.startswith("FIBRILFIT_"))


CLI_COMMANDS = []   # (id, callback) for every register_cli_command call
CLI_RELEASED = []   # unregister_cli_command calls


def spy_on_cli_commands():
    register, unregister = bpy.utils.register_cli_command, bpy.utils.unregister_cli_command

    def spy_register(id_, execute):
        CLI_COMMANDS.append((id_, execute))
        return register(id_, execute)

    def spy_unregister(handle):
        CLI_RELEASED.append(handle)
        return unregister(handle)
    bpy.utils.register_cli_command = spy_register
    bpy.utils.unregister_cli_command = spy_unregister


def run_command(execute, args) -> dict:
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()) as printed:
        code = execute(args)
    return {"code": code, "stdout": printed.getvalue(), "stderr": err.getvalue()}


def main(zip_path: str, values: dict, fibril: str | None = None) -> dict:
    spy_on_cli_commands()
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
    ff.ui.properties.write_params(settings, ff.model.params.make_params(**values))

    def stored():
        root = ff.builders.scene.find_root(scene)
        return json.loads(root[ff.ui.operators.common.RESULT])

    out["steps"] = {}
    for op in STEPS:
        state = sorted(getattr(bpy.ops.fibrilfit, op)())
        out["steps"][op] = [state, len(scene.objects), ff.builders.model_stage(scene)]
    out["props"] = {k: getattr(settings, k) for k in ff.ui.properties.RESULTS}
    out["steps_result"] = stored()
    out["join"] = [sorted(bpy.ops.fibrilfit.join_globules()), len(scene.objects)]
    out["run_all"] = [sorted(bpy.ops.fibrilfit.run_all()), len(scene.objects), settings.verdict]
    out["run_all_result"] = stored()
    out["clear"] = [sorted(bpy.ops.fibrilfit.clear()), sorted(o.name for o in scene.objects)]
    # the API of the installed copy
    api = ff.run_model(ff.model.params.make_params(**values), scene)
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
    # last: the command resets the scene, and its sweep's workers import what they need
    out["cli_registered"] = [[id_, f"{fn.__module__}.{fn.__name__}"] for id_, fn in CLI_COMMANDS]
    out["cli_released"] = len(CLI_RELEASED)
    execute = CLI_COMMANDS[-1][1]  # the enabled copy's
    options = [a for k, v in values.items() for a in (f"--{k.replace('_', '-')}", str(v))]
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp, "r.json")
        out["cli_run"] = run_command(execute, ["run", *options, "--json", str(path)])
        out["cli_result"] = json.loads(path.read_text()) if path.exists() else None
    out["cli_bad"] = run_command(execute, ["run", "--layers", "0"])
    sweep_options = [a for a in options if a not in ("--seed", str(values.get("seed")))]
    with tempfile.TemporaryDirectory() as tmp:  # workers load the installed copy's files
        out["cli_sweep"] = run_command(execute, [
            "sweep", *sweep_options, "--seed-list", str(values["seed"]), "--workers", "1",
            "--no-plot", "--quiet", "--out", tmp])
        lines = pathlib.Path(tmp, "results.jsonl").read_text().splitlines()
        out["cli_sweep_results"] = [json.loads(line) for line in lines]
    # the workers reset to factory settings: the installed wheels must survive it (issue #33)
    home = os.environ["BLENDER_USER_RESOURCES"]
    out["wheels_after_sweep"] = sorted(
        name for p in sys.path if p.startswith(home) and "site-packages" in p
        for name in os.listdir(p) if not name.endswith(("-info", ".data", ".libs")))
    out["cli_enabled_after"] = [m for m in bpy.context.preferences.addons.keys() if m == name]
    return out


if __name__ == "__main__":
    print("RESULT " + json.dumps(main(sys.argv[1], json.loads(sys.argv[2]), *sys.argv[3:4])))
