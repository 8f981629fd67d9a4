"""Refuse a Blender older than the manifest's minimum: one line, before anything else runs.

headless.py and register() call this first, so an old Blender (Debian's 3.4.1, say) is told
what it needs instead of failing halfway with a traceback. Plain Python that any Blender's
Python can run (no f-strings, no annotations) and no package imports.
"""
import os
import re
import sys

MANIFEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blender_manifest.toml")
EXIT_TOO_OLD = 2  # exits.EXIT_USAGE, spelled out so that this module imports nothing


def minimum():
    """The manifest's blender_version_min as a tuple of ints, e.g. (4, 2, 0)."""
    with open(MANIFEST, encoding="utf-8") as f:
        m = re.search(r'^blender_version_min\s*=\s*"(\d+)\.(\d+)\.(\d+)"', f.read(), re.M)
    return tuple(int(v) for v in m.groups())


def found():
    """This Blender's version: bpy.app.version inside Blender (bpy is always loaded there), else
    the installed bpy module's, read without importing it (commands such as `inspect` never
    need bpy, which takes a second or more to import). None when there is no bpy at all."""
    bpy = sys.modules.get("bpy")
    if bpy is not None:
        return tuple(bpy.app.version)
    try:
        from importlib.metadata import PackageNotFoundError, version
    except ImportError:  # Python < 3.8: only an old Blender has one
        import bpy
        return tuple(bpy.app.version)
    try:
        text = version("bpy")
    except PackageNotFoundError:
        return None
    m = re.match(r"(\d+)\.(\d+)(?:\.(\d+))?", text)
    return tuple(int(v or 0) for v in m.groups()) if m else None


def dotted(version):
    return ".".join(str(v) for v in version)


def refusal(version=None):
    """None if this Blender is new enough, else the one line that says what is needed."""
    version = version or found()
    need = minimum()
    if version is None or tuple(version)[:3] >= need:
        return None
    return "FibrilFit needs Blender {} or newer; this is Blender {}".format(
        dotted(need), dotted(version))


def exit_if_too_old():
    """For command lines: print the refusal to stderr and exit 2."""
    line = refusal()
    if line:
        print("fibrilfit: error: " + line, file=sys.stderr)
        sys.stderr.flush()
        sys.exit(EXIT_TOO_OLD)


def refuse_registration(line):
    """register() on an old Blender: in the background (a script or `--addons`), exit 2 like the
    command line; with a window, leave the add-on inert and say why in a popup."""
    print("fibrilfit: error: " + line, file=sys.stderr)
    sys.stderr.flush()
    import bpy
    if bpy.app.background:
        sys.exit(EXIT_TOO_OLD)  # Blender before 4.2 lets SystemExit through addon_utils.enable

    def popup():  # once the window is up; the line above is already on the console
        def draw(menu, _context):
            menu.layout.label(text=line)
        try:
            bpy.context.window_manager.popup_menu(draw, title="FibrilFit", icon="ERROR")
        except Exception:  # no window to show it in: the console line has to do
            pass
    bpy.app.timers.register(popup, first_interval=0.5)
