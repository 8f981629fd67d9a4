"""The task a Dask worker runs for one grid point.

Shipped to the workers by value, so they need neither FibrilFit nor bpy importable: it loads
pool.py by the path the executor read from the module itself (pool.__file__; the package must
be at the same path on every worker, e.g. a shared file system) and hands the job to that Dask
worker process's own bpy subprocess, one job at a time.
"""


def make_task():
    """The task function. Made here, nested, because pickle cannot find a nested function by
    name: Dask's serializer then falls back to cloudpickle, which ships its code by value."""

    def run_task(pool_file: str, job: dict, timeout: float | None = None) -> dict:
        import importlib.util
        import sys

        name = "_fibrilfit_sweep_pool"
        pool = sys.modules.get(name)
        if pool is None:
            spec = importlib.util.spec_from_file_location(name, pool_file)
            pool = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(pool)
            pool = sys.modules.setdefault(name, pool)
        return pool.run_here(job, timeout)

    return run_task
