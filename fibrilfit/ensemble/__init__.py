"""The model's ensemble: every valid layout of the hard-core model equally likely, sampled by
Monte Carlo with symmetric moves (docs/model/ensemble.md#ensemble). Plain numpy, no bpy.

system.py says what a layout is (chains of hard spheres at fixed bond lengths, fixed anchors,
the core as an obstacle, a periodic cell's screw images); sampler.py samples it; observables.py
reads what a microscope would see from the samples (outer diameter, radial density of domain
mass) and whether the run converged (two halves, effective sample size).
"""
