"""The domains GUI test's session, run inside the trixie chroot by its python3
(tests/realblender/test_domains_gui.py starts it): Xvfb, and Blender 4.3.2 in a window with the
installed extension and domains_probe.py, which drives the sidebar's operators and quits.

    python3 domains_session.py DIR      # DIR holds steps.json; results.json is written there

Exits non-zero with one line on stderr when Blender never writes its results.
"""
import os
import pathlib
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
ADDON = "bl_ext.user_default.fibrilfit"
TIMEOUT = 900.0


def main():
    out = pathlib.Path(sys.argv[1])
    (out / "results.json").unlink(missing_ok=True)
    display = f":{190 + os.getpid() % 50}"
    env = {**os.environ, "DISPLAY": display, "FIBRILFIT_DOMAINS": str(out)}
    xvfb = subprocess.Popen(["Xvfb", display, "-screen", "0", "1600x1000x24", "-nolisten",
                             "tcp"], stdout=subprocess.DEVNULL,
                            stderr=open(out / "xvfb.log", "w"))
    try:
        sock = pathlib.Path(f"/tmp/.X11-unix/X{display[1:]}")
        end = time.monotonic() + 30
        while not sock.exists() and xvfb.poll() is None and time.monotonic() < end:
            time.sleep(0.2)
        blender = subprocess.run(
            ["blender", "--factory-startup", "--addons", ADDON, "--window-geometry", "0", "0",
             "1600", "1000", "--python", str(HERE / "domains_probe.py")],
            env=env, stdout=open(out / "blender.log", "w"), stderr=subprocess.STDOUT,
            timeout=TIMEOUT)
    finally:
        xvfb.terminate()
        xvfb.wait(10)
    if not (out / "results.json").exists():
        print(f"domains gui test: Blender exited ({blender.returncode}) with no results: see "
              f"{out}/blender.log", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
