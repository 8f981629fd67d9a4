"""The GUI test's session, run inside the trixie chroot by its python3 (tests/realblender/
test_gui.py starts it): Xvfb, Blender 4.3.2 with the installed extension, and a user's input
through xdotool: N opens the sidebar, Ctrl+Wheel over it turns to the FibrilFit tab; ubiquitin
and GFP imported (the probe's "domains", the paths their file browser gives), a click presses
Run all, Step by step › Bake (the probe's "bake"), a click on Report…, Clear (the probe's
"clear"): issue #45's route; then a mixed fibril (issue #44 item 5): the fraction 50 % set in the
panel (the probe's "mixed") and a click on Run all. Blender's side is read from gui_probe.py's state file;
screenshots are the X root (`import -window root`), cropped to the sidebar and the 3D View.

    python3 gui_session.py OUT_DIR SHOTS_DIR      (the structures: tests/data)

Writes OUT_DIR/session.json (what the test asserts on) and the PNGs; exits non-zero with one
line on stderr when a step cannot be done (no display, Blender never drew, no button found).
The kept screenshots go to OUT_DIR/screens/, each compared with its copy in SHOTS_DIR (the docs'
images, never written here): one that differs is listed in session.json's "changed" with, where
the sizes agree, its difference OUT_DIR/screens/diff-<name> (test_gui.py fails on it unless the
change is accepted).
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
WIDTH, HEIGHT = 1600, 1300  # tall enough for the sidebar with a result box and its span lines
MARK = (255, 0, 255)  # gui_probe.py's colours
PANEL = (0, 255, 255)
ADDON = "bl_ext.user_default.fibrilfit"
RUN_TIMEOUT = 600.0


class SessionError(RuntimeError):
    pass


def wait_for(what, fn, timeout, every=0.2):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = fn()
        if value:
            return value
        time.sleep(every)
    raise SessionError(f"timed out after {timeout:.0f} s waiting for {what}")


def runs(indices):
    """Runs of consecutive integers in a sorted array: [(first, last), ...]."""
    out = []
    for i in indices.tolist():
        if out and i == out[-1][1] + 1:
            out[-1][1] = i
        else:
            out.append([i, i])
    return [tuple(r) for r in out]


class Session:
    def __init__(self, out: pathlib.Path, shots: pathlib.Path, data: pathlib.Path):
        self.out, self.shots, self.data = out, shots, data
        self.screens = out / "screens"
        self.screens.mkdir(parents=True, exist_ok=True)
        self.probe = out / "probe"
        shutil.rmtree(self.probe, ignore_errors=True)
        self.probe.mkdir(parents=True)
        self.display = f":{90 + os.getpid() % 100}"
        self.env = {**os.environ, "DISPLAY": self.display, "FIBRILFIT_PROBE": str(self.probe)}
        self.procs = []
        self.log = {"steps": []}

    # ---- processes --------------------------------------------------------------------------
    def start(self):
        xvfb = subprocess.Popen(["Xvfb", self.display, "-screen", "0", f"{WIDTH}x{HEIGHT}x24",
                                 "-nolisten", "tcp"], stdout=subprocess.DEVNULL,
                                stderr=open(self.out / "xvfb.log", "w"))
        self.procs.append(xvfb)
        sock = pathlib.Path(f"/tmp/.X11-unix/X{self.display[1:]}")
        wait_for("Xvfb", lambda: sock.exists() or xvfb.poll() is not None, 30)
        if xvfb.poll() is not None:
            raise SessionError(f"Xvfb exited ({xvfb.returncode}): see {self.out}/xvfb.log")
        t0 = time.monotonic()
        blender = subprocess.Popen(
            ["blender", "--factory-startup", "--addons", ADDON, "--window-geometry", "0", "0",
             str(WIDTH), str(HEIGHT), "--python", str(HERE / "gui_probe.py")],
            env=self.env, stdout=open(self.out / "blender.log", "w"), stderr=subprocess.STDOUT)
        self.procs.append(blender)
        self.blender = blender
        wait_for("Blender's window (the probe's first state)",
                 lambda: self._alive() and (self.probe / "state.json").exists(), 180)
        self.log["startup_seconds"] = round(time.monotonic() - t0, 1)

    def _alive(self):
        if self.blender.poll() is not None:
            raise SessionError(f"Blender exited ({self.blender.returncode}): see "
                               f"{self.out}/blender.log")
        return True

    def stop(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()

    # ---- Blender's side -------------------------------------------------------------------------
    def state(self):
        self._alive()
        err = self.probe / "probe_error.txt"
        if err.exists():
            raise SessionError(f"the probe failed: {err.read_text()}")
        return json.loads((self.probe / "state.json").read_text())

    def fresh_state(self, n=3):
        """A state written at least n ticks after now (the UI has redrawn since)."""
        seq = self.state()["seq"]
        return wait_for("the probe", lambda: (s := self.state())["seq"] >= seq + n and s, 30)

    def command(self, cmd, theme, timeout=30):
        (self.probe / "command").write_text(cmd)
        wait_for(f"the probe's '{cmd}'", lambda: self.state()["theme"] == theme, timeout)
        return self.fresh_state()

    def view(self):
        views = self.state()["views"]
        if len(views) != 1:
            raise SessionError(f"expected one 3D View in the factory layout, found {len(views)}")
        return views[0]

    def screen_rect(self, r):
        """A region's rectangle (Blender: from the window's bottom left) in X root pixels
        (from the top left): x0, y0, x1, y1."""
        h = self.state()["window"]["height"]
        return r["x"], h - r["y"] - r["height"], r["x"] + r["width"], h - r["y"]

    # ---- the user's side --------------------------------------------------------------------
    def xdo(self, *args):
        subprocess.run(["xdotool", *map(str, args)], env=self.env, check=True)

    def hover(self, rect):
        x0, y0, x1, y1 = rect
        self.xdo("mousemove", (x0 + x1) // 2, (y0 + y1) // 2)
        time.sleep(0.3)

    def screenshot(self, path):
        subprocess.run(["import", "-window", "root", str(path)], env=self.env, check=True,
                       stderr=subprocess.DEVNULL)
        return path

    def crop(self, src, rect, name):
        """The screenshot `name` cropped to rect into OUT_DIR/screens/, and compared with the
        docs' copy SHOTS_DIR/name."""
        x0, y0, x1, y1 = rect
        new = self.screens / name
        subprocess.run(["convert", str(src), "-crop", f"{x1 - x0}x{y1 - y0}+{x0}+{y0}", "+repage",
                        "-strip", "-colors", "256", str(new)], check=True)  # small for git
        change = self.difference(self.shots / name, new, self.screens / f"diff-{name}")
        if change:
            self.log.setdefault("changed", {})[name] = change
        self.log.setdefault("screenshots", []).append(name)

    @staticmethod
    def difference(old, new, diff) -> str:
        """"" when old and new are the same picture: same size and no pixel apart by more than
        20 % of the range. Two runs' crops of the same screen differ in a few hundred dithered
        pixels of the 256-colour palette (measured 2026-11-25 on result.png, 1322 × 876: 1325
        pixels differ at all, 251 by over 2 %, 5 by over 10 %, none by 15 %); a changed word or
        colour differs by far more. Otherwise what differs, the differing pixels marked in diff."""
        if not old.exists():
            return f"no {old.name} in the docs yet"
        cp = subprocess.run(["compare", "-metric", "AE", "-fuzz", "20%", str(old), str(new),
                             str(diff)], capture_output=True, text=True)
        count = cp.stderr.strip().split()[:1]
        if cp.returncode == 0 and count == ["0"]:
            diff.unlink(missing_ok=True)
            return ""
        if cp.returncode == 1:
            return f"{count[0]} pixels differ by over 20 % (marked in {diff.name})"
        return f"not comparable ({cp.stderr.strip()[:200]})"  # e.g. another size

    def pixels(self, path):
        raw = subprocess.run(["convert", str(path), "-depth", "8", "rgb:-"], check=True,
                             capture_output=True).stdout
        return np.frombuffer(raw, np.uint8).reshape(HEIGHT, WIDTH, 3)

    def step(self, text):
        self.log["steps"].append(text)

    # ---- the test ------------------------------------------------------------------------------
    def run(self):
        self.start()
        view = self.view()
        window_region = self.screen_rect(view["regions"]["WINDOW"])
        self.hover(window_region)
        self.xdo("key", "Escape")  # the splash screen, as a user closes it
        time.sleep(0.5)
        self.step("Esc closed the splash screen")
        self.xdo("key", "n")  # the sidebar, as a user opens it
        wait_for("the sidebar after N", lambda: self.view()["sidebar"], 20)
        self.step("N opened the sidebar")
        ui = self.screen_rect(self.fresh_state()["views"][0]["regions"]["UI"])
        # Find the buttons: operator buttons and the sidebar's inactive tabs flat magenta,
        # then the theme back as it was before the screenshots that are kept.
        self.hover(window_region)
        self.command("mark", "marked")
        self.open_tab(ui, window_region)
        marked = self.pixels(self.screenshot(self.out / "marked.png"))
        self.command("unmark", "normal")
        before = self.screenshot(self.out / "before.png")
        self.crop(before, self.panel_rect(marked, ui), "panel-before.png")  # "Start here"
        # Two domains, as Import domain… twice leaves them (issue #45 item 1's route)
        state = self.command(f"domains {self.data}", "domains", timeout=300)  # two imports
        if state.get("refused") or len(state["domains"]) != 2:
            raise SessionError(f"the two domains were not imported: {state.get('refused')} "
                               f"{state['domains']}")
        self.step("imported ubiquitin and GFP chain A (Import domain… twice)")
        self.hover(window_region)
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-domains.png"))
        self.command("unmark", "normal")
        run_all = self.find_run_all(marked, ui)
        domains = self.screenshot(self.out / "domains.png")
        self.crop(domains, self.panel_rect(marked, ui), "panel-domains.png")
        self.log["state_before"] = self.state()
        # Press Run all: a real click.
        t0 = time.monotonic()
        self.xdo("mousemove", *run_all, "click", "1")
        self.xdo("mousemove", (window_region[0] + window_region[2]) // 2, window_region[3] - 40)
        self.step(f"clicked Run all at {run_all}")
        progress = self.watch_bake()
        self.log["run_seconds"] = round(time.monotonic() - t0, 1)
        self.log["progress_shots"] = progress
        after_state = self.fresh_state(5)
        ui = self.screen_rect(after_state["views"][0]["regions"]["UI"])
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-after.png"))
        self.command("unmark", "normal")
        after = self.screenshot(self.out / "after.png")
        self.crop(after, self.panel_rect(marked, ui), "panel-after.png")
        self.crop(after, self.screen_rect(after_state["views"][0]["area"]), "result.png")
        self.log["state_after"] = after_state
        self.log["after_pixels"] = self.colour_counts(self.pixels(after),
                                                      self.screen_rect(after_state["views"][0]
                                                                       ["regions"]["WINDOW"]))
        self.bake_step_by_step()
        self.report(window_region)
        self.clear(window_region)
        self.mixed(window_region)

    def bake_step_by_step(self):
        """Step by step › Bake on the two domains' model Run all built: it must bake (issue #45
        item 1: it refused, "changed from 10 to [10]")."""
        self.command("bake", "bake")
        state = wait_for("the step-by-step bake", lambda: (s := self.state()).get("refused")
                         or s["stage"] == "baked" and s, RUN_TIMEOUT, every=1.0)
        if isinstance(state, str):
            raise SessionError(f"Step by step › Bake refused: {state}")
        self.step("Step by step › Bake baked the two domains' model")
        self.log["state_bake"] = self.fresh_state()

    def clear(self, away):
        """Clear: the model gone, and the results with it (issue #45 item 2)."""
        state = self.command("clear", "clear")
        if state.get("refused"):
            raise SessionError(f"Clear refused: {state['refused']}")
        self.step("Clear")
        state = self.fresh_state(5)
        self.log["state_cleared"] = state
        ui = self.screen_rect(state["views"][0]["regions"]["UI"])
        self.hover(away)
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-cleared.png"))
        self.command("unmark", "normal")
        shot = self.screenshot(self.out / "cleared.png")
        self.crop(shot, self.panel_rect(marked, ui), "panel-cleared.png")

    def mixed(self, away):
        """A mixed fibril: the fraction 50 % typed by the probe on the small model, a click on
        Run all (found as before), and the model and result the panel's run made."""
        self.command("mixed", "mixed")
        self.step("the probe typed the fraction 50 % (8 layers)")
        ui = self.screen_rect(self.fresh_state()["views"][0]["regions"]["UI"])
        self.hover(away)
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-mixed.png"))
        self.command("unmark", "normal")
        run_all = self.find_run_all(marked, ui)
        t0 = time.monotonic()
        self.xdo("mousemove", *run_all, "click", "1")
        self.hover(away)
        self.step(f"clicked Run all at {run_all} (50 %)")
        self.watch_bake()
        self.log["mixed_seconds"] = round(time.monotonic() - t0, 1)
        self.log["state_mixed"] = self.fresh_state(5)

    def report(self, away):
        """Report… on a small model (test_report.py's): the values typed by the probe, then a
        click on Report… (the button row below Run all's), Return in the folder chooser (it
        offers the folder and settings the probe set), and the panel's report box."""
        folder = self.out / "report"
        folder.mkdir(parents=True, exist_ok=True)  # as a user picks an existing folder
        self.command(f"small {folder}", "small")
        self.step("the probe typed a small model's values and the report's folder")
        ui = self.screen_rect(self.fresh_state()["views"][0]["regions"]["UI"])
        self.hover(away)
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-report.png"))
        self.command("unmark", "normal")
        x, y = self.find_button_below_run_all(marked, ui)
        t0 = time.monotonic()
        self.xdo("mousemove", x, y, "click", "1")
        self.step(f"clicked Report… at {(x, y)}")
        wait_for("the folder chooser", lambda: any(
            "FILE_BROWSER" in w["areas"] for w in self.state()["windows"]), 60)
        time.sleep(1.0)
        self.hover(away)
        self.xdo("key", "Return")
        self.step("Return in the folder chooser")
        state = wait_for("the panel's report", lambda: (s := self.state())["report_summary"]
                         and s, RUN_TIMEOUT, every=1.0)
        self.log["report_seconds"] = round(time.monotonic() - t0, 1)
        state = self.fresh_state(5)
        self.log["state_report"] = state
        ui = self.screen_rect(state["views"][0]["regions"]["UI"])
        self.hover(away)
        self.command("mark", "marked")
        marked = self.pixels(self.screenshot(self.out / "marked-reported.png"))
        self.command("unmark", "normal")
        shot = self.screenshot(self.out / "reported.png")
        self.crop(shot, self.panel_rect(marked, ui), "panel-report.png")

    def find_button_below_run_all(self, img, ui):
        """The centre of the button row right below Run all's (Report…)."""
        self.find_run_all(img, ui)
        rows = self.log["button_rows"]
        heights = [b - a for a, b in rows]
        below = rows[heights.index(max(heights)) + 1]
        x0, _, x1, _ = ui
        return (x0 + x1 - 40) // 2, (below[0] + below[1]) // 2

    def open_tab(self, ui, away):
        """Click the sidebar's tabs (the marked ones, in a strip at its right edge) from the
        bottom up until the probe says the FibrilFit tab is open."""
        x0, y0, x1, y1 = ui
        img = self.pixels(self.screenshot(self.out / "tabs.png"))
        strip = img[y0:y1, max(x1 - 40, x0):x1].astype(int)
        mask = np.abs(strip - MARK).sum(axis=2) < 30
        tabs = runs(np.flatnonzero(mask.sum(axis=1) > 3))
        if not tabs:
            raise SessionError("no sidebar tab found (marked screenshot tabs.png)")
        seen = [self.state()["views"][0]["category"]]
        for top, bottom in reversed(tabs):
            cols = np.flatnonzero(mask[top:bottom + 1].any(axis=0))
            x = max(x1 - 40, x0) + int(cols.mean())
            y = y0 + (top + bottom) // 2
            self.xdo("mousemove", x, y, "click", "1")
            self.hover(away)
            category = self.fresh_state()["views"][0]["category"]
            seen.append(category)
            if category == "FibrilFit":
                self.step(f"clicked the sidebar's tab at {(x, y)}: FibrilFit "
                          f"(tabs seen: {' > '.join(seen)})")
                return
        raise SessionError(f"no sidebar tab opened FibrilFit (tabs seen: {seen})")

    def find_run_all(self, img, ui):
        """Run all: of the marked (magenta) buttons in the sidebar, the tallest row (the panel
        draws it larger than the others), its left button. Returns its centre."""
        x0, y0, x1, y1 = ui
        sub = img[y0:y1, x0:x1].astype(int)
        mask = (np.abs(sub - MARK).sum(axis=2) < 30)
        mask[:, -40:] = False  # the tabs
        rows = runs(np.flatnonzero(mask.sum(axis=1) > 20))  # button rows
        if not rows:
            raise SessionError("no operator button found in the sidebar (marked screenshot)")
        heights = [b - a + 1 for a, b in rows]
        top, bottom = rows[int(np.argmax(heights))]
        self.log["button_rows"] = [[int(a) + y0, int(b) + y0] for a, b in rows]
        if sorted(heights)[-1] == sorted(heights + [0])[-2]:
            raise SessionError(f"two button rows are equally tall ({heights}): cannot tell "
                               f"Run all's row")
        # Run all is the left half of its row (Clear the right half, marked too once a model
        # exists): the row spans the panel's width, as the first row (Import fibril/domain) does
        first_top, first_bottom = rows[0]
        full = np.flatnonzero(mask[first_top:first_bottom + 1].any(axis=0))
        cols = np.flatnonzero(mask[top:bottom + 1].any(axis=0))
        x = x0 + int(cols[0] + (full[-1] - full[0]) // 4)
        y = y0 + (top + bottom) // 2
        self.log["run_all_button"] = [int(x), int(y)]
        return int(x), int(y)

    def panel_rect(self, img, ui):
        """The sidebar's rectangle down to the bottom of its last panel (marked PANEL)."""
        x0, y0, x1, y1 = ui
        mask = np.abs(img[y0:y1, x0:x1].astype(int) - PANEL).sum(axis=2) < 30
        rows = np.flatnonzero(mask.sum(axis=1) > 20)
        if rows.size == 0:
            raise SessionError("no panel found in the sidebar (marked screenshot)")
        return x0, y0, x1, min(y1, y0 + int(rows[-1]) + 8)

    def watch_bake(self):
        """Until the panel shows a verdict; screenshots of the status bar while it bakes."""
        shots, end = [], time.monotonic() + RUN_TIMEOUT
        while time.monotonic() < end:
            s = self.state()
            if s["verdict"]:
                self.step(f"the panel shows verdict '{s['verdict']}' at frame {s['frame']}")
                return shots
            if s["model_objects"] and s["frame"] > 5 and len(shots) < 3 and (
                    not shots or time.monotonic() - shots[-1]["t"] > 2):
                path = self.screenshot(self.out / f"baking{len(shots)}.png")
                shots.append({"frame": s["frame"], "t": time.monotonic(),
                              "status": self.status_bar(path, len(shots))})
            time.sleep(0.2)
        raise SessionError(f"no verdict {RUN_TIMEOUT:.0f} s after Run all")

    def status_bar(self, path, n):
        """The status bar (the window's bottom 26 px) cropped for the log."""
        dst = self.out / f"baking-status{n}.png"
        subprocess.run(["convert", str(path), "-crop", f"{WIDTH}x26+0+{HEIGHT - 26}", "+repage",
                        str(dst)], check=True)
        return dst.name

    def colour_counts(self, img, rect):
        x0, y0, x1, y1 = rect
        sub = img[y0:y1, x0:x1].astype(int)
        r, g, b = sub[..., 0], sub[..., 1], sub[..., 2]
        return {"reddish": int(((r > 150) & (g < 80) & (b < 80)).sum()),
                "yellowish": int(((r > 150) & (g > 110) & (b < 90)).sum()),
                "pixels": int(r.size)}


def main():
    out, shots = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    session = Session(out, shots, HERE.parent / "data")
    try:
        session.run()
        session.log["ok"] = True
    except (SessionError, subprocess.CalledProcessError) as exc:
        session.log["error"] = str(exc)
        print(f"gui test: {exc}", file=sys.stderr)
        try:  # what the screen showed, for the one who reads the error
            session.screenshot(out / "failure.png")
        except (OSError, subprocess.CalledProcessError):
            pass
    finally:
        session.stop()
        (out / "session.json").write_text(json.dumps(session.log, indent=1))
    return 0 if session.log.get("ok") else 1


if __name__ == "__main__":
    sys.exit(main())
