"""The cluster page's settings (docs/guide/cluster.md), read from the code that has them, so the
page cannot state another value than the sweep uses (loaded by docs/hooks/page_numbers.py).

- `keep_every("dask")`: how long a Dask sweep waits for a result before it runs its watchdog
  again (`DaskExecutor.KEEP_EVERY`, fibrilfit/batch/executors.py), as "10 s";
- `keep_every("slurm")`: how often the SLURM sweep's watchdog asks squeue for its jobs
  (`SlurmExecutor.KEEP_EVERY`).

These are settings, not measurements. The package only (no bpy: executors imports Dask lazily)."""
from __future__ import annotations


def macros(numbers) -> dict:
    def keep_every(executor: str) -> str:
        from fibrilfit.batch.executors import DaskExecutor, SlurmExecutor
        kind = {"dask": DaskExecutor, "slurm": SlurmExecutor}[executor]
        return f"{kind.KEEP_EVERY:g} s"

    return {"keep_every": keep_every}
