"""The task a Dask worker runs for one grid point.

Shipped to the workers by value (cloudpickle.register_pickle_by_value), so they need neither
FibrilFit nor bpy importable: it loads sweep/pool.py from the repository by path (ROOT must be
the same path on every worker, e.g. a shared file system) and hands the job to that Dask worker
process's own bpy subprocess, one job at a time.
"""


def run(root: str, job: dict, timeout: float | None = None) -> dict:
    import importlib.util
    import os
    import sys

    name = "_fibrilfit_sweep_pool"
    pool = sys.modules.get(name)
    if pool is None:
        spec = importlib.util.spec_from_file_location(name, os.path.join(root, "sweep", "pool.py"))
        pool = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(pool)
        pool = sys.modules.setdefault(name, pool)
    return pool.run_here(root, job, timeout)
