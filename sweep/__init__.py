"""Batch sweeps: a grid of runs on local worker processes or a Dask cluster, summarised.

`headless.py sweep` (cli.py) calls command.run. Nothing here is imported by register() or by a
plain `run`; tqdm, matplotlib and distributed are imported only when a sweep runs.
"""
