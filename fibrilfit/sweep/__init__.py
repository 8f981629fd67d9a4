"""Batch sweeps: a grid of runs on worker processes (batch/: this machine, Dask, SLURM),
summarised.

`headless.py sweep` (cli/batch_commands.py) calls command.run_sweep. Building the command line reads only
the option definitions (options.py and the plain-Python grid/gate/summary it names); tqdm,
matplotlib and distributed are imported only when a sweep runs, never by register() or a plain
`run`.
"""
