"""One sweep worker: imports bpy once, then runs the models it is sent, one at a time.

Started by pool.py as `python fibrilfit/batch/worker.py` (bpy module), or inside Blender as
`blender -b --factory-startup -P fibrilfit/batch/worker.py`. It imports the package it belongs
to from its own folder (found from __file__), as `fibrilfit`, whatever the installed name.
Protocol: one JSON object per line, jobs on stdin, replies on the original stdout; everything
else printed (by Blender, Bullet or Python) goes to stderr, so it can never corrupt a reply. It
exits when its input ends.
"""
import importlib.util
import json
import os
import pathlib
import signal
import socket
import sys
import threading
import time
import traceback


def _package():
    """The package this file belongs to (two folders up), imported as `fibrilfit` by its path:
    a script run by path has no package, and Blender's -P puts no folder on sys.path."""
    folder = pathlib.Path(__file__).resolve().parents[1]
    spec = importlib.util.spec_from_file_location(
        "fibrilfit", folder / "__init__.py", submodule_search_locations=[str(folder)])
    module = sys.modules["fibrilfit"] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _exit_with_parent() -> None:
    """End this worker, even mid-run, once whoever started it is gone (killed sweep, closed Dask
    worker): its runs would be recorded by no one."""
    parent = os.getppid()
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(1)


def main() -> int:
    replies = os.fdopen(os.dup(1), "w", encoding="utf-8", buffering=1)
    os.dup2(2, 1)
    # Ctrl-C reaches the whole process group: the parent decides, the worker just finishes.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_exit_with_parent, daemon=True).start()

    import bpy
    ff = _package()
    me = {"host": socket.gethostname(), "pid": os.getpid()}
    if os.environ.get("SLURM_JOB_ID"):  # a SLURM job's worker (--executor slurm) names its job
        me["slurm_job"] = os.environ["SLURM_JOB_ID"]

    def send(message):
        replies.write(json.dumps(message) + "\n")

    send({"ready": True, "blender_version": bpy.app.version_string, **me})
    for line in sys.stdin:
        if not line.strip():
            continue
        job = json.loads(line)
        send({"started": job["id"]})
        t = time.perf_counter()
        try:
            force = bool(job.get("force"))
            p = ff.model.params.make_params(force=force, **job["params"])
            bpy.ops.wm.read_factory_settings(use_empty=True)
            result = ff.pipeline.run_model(p, bpy.context.scene, force=force)
            reply = {"id": job["id"], "ok": True, "result": json.loads(json.dumps(result))}
        except Exception as exc:  # recorded with the point; the worker stays up for the next one
            traceback.print_exc()
            reply = {"id": job["id"], "ok": False, "error": f"{type(exc).__name__}: {exc}"}
        send({**reply, "worker": me, "seconds": round(time.perf_counter() - t, 3)})
    return 0


if __name__ == "__main__":
    sys.exit(main())
