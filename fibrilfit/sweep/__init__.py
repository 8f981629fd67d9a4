"""Batch sweeps: a grid of runs on worker processes (batch/: this machine, Dask, SLURM),
summarised.

`fibrilfit sweep` (cli/commands.py, through api/batch.py) calls driver.run_sweep. Building the
command line reads only the sweep's plan (plans.py and the plain-Python gate it names); tqdm,
matplotlib and distributed are imported only when a sweep runs, never by register() or a plain
`run`.
"""
