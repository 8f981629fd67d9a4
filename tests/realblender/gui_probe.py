"""Runs inside the GUI Blender of the GUI test (`blender --python gui_probe.py`): it presses
nothing. Every 0.2 s it writes what Blender knows and a screenshot cannot say (window and region
rectangles, the sidebar's tab, the panel's verdict, the model and the 3D Views) to
$FIBRILFIT_PROBE/state.json, and it obeys commands from $FIBRILFIT_PROBE/command:
"mark" paints operator buttons and inactive tabs one flat colour and the panels another (theme
colours), so the test can find the buttons and the panels' extent in a screenshot; "unmark"
restores the theme; "small DIR" types a small model's values into the panel (the domain list
emptied, as its remove button does) and sets the report's folder and settings (what Report…'s
chooser then offers), standing in for typing them; "mixed" types MIXED (half of the subunits
decorated: the fraction 50 % in the Globule section) and empties the verdict, so the next Run all
is seen; "domains DIR" types ROUTE's layers and
frames and imports ubiquitin and GFP chain A from DIR with Import domain… (the path its file
browser gives); "bake" presses Step by step ›
Bake (the operator as its button calls it, modal, in the window) and "clear" Clear, each noting
a refusal in the state's "refused". The other clicks and keys come from xdotool.
"""
import json
import os
import pathlib

import bpy
from bpy_extras import view3d_utils

PROBE = pathlib.Path(os.environ["FIBRILFIT_PROBE"])
MARK = (1.0, 0.0, 1.0, 1.0)   # magenta: no other widget in the default theme has it
PANEL = (0.0, 1.0, 1.0, 1.0)  # cyan: the panels' extent
_saved = {}
_state = {"seq": 0, "theme": "normal"}


def _themed():
    """(theme struct, property, colour) the mark paints: operator buttons and the sidebar's
    inactive tabs MARK, the panels' background and headers PANEL (to crop the screenshots)."""
    theme = bpy.context.preferences.themes[0]
    w, space = theme.user_interface.wcol_tool, theme.view_3d.space
    return [(w, "inner", MARK), (w, "inner_sel", MARK), (w, "outline", MARK),
            (w, "show_shaded", False), (space, "tab_inactive", MARK),
            (space.panelcolors, "back", PANEL), (space.panelcolors, "header", PANEL),
            (space.panelcolors, "sub_back", PANEL)]


def _mark():
    for struct, name, colour in _themed():
        if not hasattr(struct, name):
            continue
        old = getattr(struct, name)
        _saved.setdefault((struct.as_pointer(), name), (struct, name, old if isinstance(old, bool)
                                                       else tuple(old)))
        setattr(struct, name, colour if isinstance(colour, bool) else colour[:len(old)])


def _unmark():
    for struct, name, value in _saved.values():
        setattr(struct, name, value)


def _rect(r):
    return {"x": r.x, "y": r.y, "width": r.width, "height": r.height}


def _views(window):
    out = []
    for area in window.screen.areas:
        if area.type != "VIEW_3D":
            continue
        space = area.spaces.active
        regions = {r.type: r for r in area.regions}
        item = {"area": _rect(area), "regions": {t: _rect(r) for t, r in regions.items()},
                "sidebar": space.show_region_ui,
                "category": getattr(regions["UI"], "active_panel_category", None),
                "shading": [space.shading.type, space.shading.color_type],
                "view_location": list(space.region_3d.view_location),
                "view_distance": space.region_3d.view_distance}
        item["model_in_view"] = _model_in_view(regions["WINDOW"], space.region_3d)
        out.append(item)
    return out


def _model_objects():
    scene = bpy.context.scene
    try:
        from bl_ext.user_default.fibrilfit.builders.scene import find_root
    except ImportError:
        return []
    root = find_root(scene)
    if root is None:
        return []
    return [ob for c in (root, *root.children_recursive) for ob in c.objects]


def _model_in_view(region, rv3d):
    """The share of the model's objects whose centres project inside the 3D View's region."""
    obs = [ob for ob in _model_objects() if ob.type == "MESH"]
    if not obs:
        return None
    inside = 0
    for ob in obs:
        p = view3d_utils.location_3d_to_region_2d(region, rv3d, ob.matrix_world.translation)
        inside += p is not None and 0 <= p.x <= region.width and 0 <= p.y <= region.height
    return inside / len(obs)


def _colours():
    """Viewport colours of the model's globules: {colour as hex: count} of the material each
    shows in Solid mode (its object's slot or its mesh's)."""
    out = {}
    for ob in _model_objects():
        if ob.type != "MESH":
            continue
        mat = ob.material_slots[0].material if ob.material_slots else None
        if mat is None:
            out.setdefault("no material", {}).setdefault(ob.get("fibrilfit", "?"), 0)
            out["no material"][ob.get("fibrilfit", "?")] += 1
            continue
        key = "#" + "".join(f"{round(c * 255):02x}" for c in mat.diffuse_color[:3])
        role = ob.get("fibrilfit", "?")
        out.setdefault(role, {}).setdefault(key, 0)
        out[role][key] += 1
    return out


# tests/realblender/test_report.py's small model: 12 Å domains on 3 layers, inflate, short
SMALL = {"layers": 3, "globule_diameter": 12.0, "linker": 3, "protocol": "inflate",
         "grow_frames": 20, "hold_frames": 20, "regrow_cycles": 0}


def _small(folder):
    s = bpy.context.scene.fibrilfit
    if len(s.domains):  # a small single globule: the list's domains removed
        from bl_ext.user_default.fibrilfit.ui import domain_list
        s.domains.clear()
        domain_list.filled(s, None, first_changed=True)
    for name, value in SMALL.items():
        setattr(s, name, value)
    s.report_dir, s.report_restarts, s.report_max_linker = folder, 2, 4
    # the file browser in the main window (Preferences > Interface > Temporary Editors), under
    # the pointer, so that Return reaches it without a window manager to focus a new window
    bpy.context.preferences.view.filebrowser_display_type = "SCREEN"


# A mixed fibril from the panel (issue #44 item 5): the small model (after "small") on 8 layers,
# the fraction 50 % (the panel shows it in %), a short bake of the tutorial's protocol
MIXED = {"layers": 8, "occupancy": 50.0, "pattern": "random", "protocol": "tutorial",
         "frames": 20}


def _mixed():
    s = bpy.context.scene.fibrilfit
    for name, value in MIXED.items():
        setattr(s, name, value)
    s.verdict = ""
    _state["mixed_asked"] = True  # the state reads the mixed model from now on


def _mixed_state():
    """The built model's subunits (decorated: chains; the others: markers) and what the last
    result records of the pattern and the fraction (scene's model root, its check's JSON)."""
    try:
        from bl_ext.user_default.fibrilfit.builders import find_model
    except ImportError:
        return None
    model = find_model(bpy.context.scene)
    if model is None:
        return None
    result = json.loads(model.root.get("fibrilfit_result", "{}"))
    return {"subunits": model.params.chains, "decorated": len(model.chain),
            "globules": len(model.globules), "bare_anchors": len(model.bare_anchors),
            "bare_anchor_bodies": sum(ob.rigid_body is not None for ob in model.bare_anchors),
            "occupancy": result.get("occupancy"),
            "params_occupancy": (result.get("params") or {}).get("occupancy")}


def _in_view3d(fn):
    """`fn()` with the window and its 3D View as a button press gives them; a refusal (an
    operator's ERROR report raises) kept in the state's "refused"."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "UI")
    try:
        with bpy.context.temp_override(window=window, area=area, region=region):
            fn()
    except RuntimeError as exc:
        _state["refused"] = str(exc)


# The two domains' model a little shorter than the defaults' (20 layers, 250 frames): Run all and
# then Step by step › Bake each bake it, in minutes each on a loaded machine (the question is the
# route, not the fit); test_gui.py's reference runs the same values
ROUTE = {"layers": 8, "frames": 80}


def _domains(folder):
    s = bpy.context.scene.fibrilfit
    for name, value in ROUTE.items():
        setattr(s, name, value)
    ops = bpy.ops.fibrilfit
    _in_view3d(lambda: (ops.import_domain(filepath=f"{folder}/1ubq.pdb.gz"),
                        ops.import_domain(filepath=f"{folder}/1gfl.pdb.gz", chain="A")))


def _stage():
    try:
        from bl_ext.user_default.fibrilfit.builders import model_stage
    except ImportError:
        return None
    return model_stage(bpy.context.scene)


def _windows(wm):
    out = []
    for w in wm.windows:
        out.append({"x": w.x, "y": w.y, "width": w.width, "height": w.height,
                    "areas": sorted(a.type for a in w.screen.areas)})
    return out


def _tick():
    try:
        cmd_file = PROBE / "command"
        if cmd_file.exists():
            cmd = cmd_file.read_text().strip()
            cmd_file.unlink()
            if cmd == "mark":
                _mark()
            elif cmd == "unmark":
                _unmark()
            elif cmd.startswith("small "):
                _small(cmd.split(" ", 1)[1])
            elif cmd.startswith("domains "):
                _domains(cmd.split(" ", 1)[1])
            elif cmd == "mixed":
                _mixed()
            elif cmd == "bake":
                _in_view3d(lambda: bpy.ops.fibrilfit.bake("INVOKE_DEFAULT"))
            elif cmd == "clear":
                _in_view3d(lambda: bpy.ops.fibrilfit.clear())
            _state["theme"] = {"mark": "marked", "unmark": "normal"}.get(
                cmd, cmd.split(" ", 1)[0] if cmd.split(" ", 1)[0] in (
                    "small", "domains", "bake", "clear", "mixed") else _state["theme"])
            for window in bpy.context.window_manager.windows:
                for area in window.screen.areas:
                    area.tag_redraw()
        wm = bpy.context.window_manager
        window = wm.windows[0]
        s = bpy.context.scene
        ff = getattr(s, "fibrilfit", None)
        user = {ob.name: list(ob.location) for ob in s.objects if "fibrilfit" not in ob}
        _state.update({
            "seq": _state["seq"] + 1,
            "window": {"width": window.width, "height": window.height},
            "views": _views(window),
            "verdict": ff.verdict if ff else None,
            "clash_count": ff.clash_count if ff else None,
            "accommodated": ff.accommodated if ff else None,
            "model_objects": len(_model_objects()),
            "colours": _colours(),
            "user_objects": user,
            "frame": s.frame_current,
            "windows": _windows(wm),
            "report_summary": json.loads(ff.report_summary) if ff and ff.report_summary
            else None,
            "minimal_map": bool(ff and ff.minimal_map),
            "domains": [e.name for e in ff.domains] if ff else [],
            "stage": _stage(),
            "mixed": _mixed_state() if _state.get("mixed_asked") else None,
        })
        tmp = PROBE / "state.json.tmp"
        tmp.write_text(json.dumps(_state))
        tmp.replace(PROBE / "state.json")
    except Exception as exc:  # keep ticking; the test sees the error
        (PROBE / "probe_error.txt").write_text(repr(exc))
    return 0.2


bpy.app.timers.register(_tick, first_interval=1.0, persistent=True)
