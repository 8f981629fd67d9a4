"""How many runs are driven: worker processes that import bpy once (`pool`, `worker`), where
they run (`executors`: this machine, Dask, SLURM via `slurm`), and the out-dir helpers that
sweep and search share (`outdir`). No bpy is imported here: the workers import it."""
