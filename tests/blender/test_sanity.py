"""Physical sanity of the default model over several seeds: verdicts move the right way.

Thresholds come from measurement (docs/model/default-model.md#default-model; 12 layers, 250 frames, seeds 0-4,
bpy 5.0.1 and 4.2.0 identical): accommodated seeds per globule size × linker length were

    globule \\ linker   1    2    3    4    6    8
    8 Å                5    5    5    5    5    5
    15 Å               0    0    5    5    5    5
    20 Å               0    0    5    5    5    5
    30 Å               0    0    0    0    5    5
    40 Å               0    0    0    0    5    5

and the worst bond stretch at the end grew with globule size for short linkers (linker 1:
31-41 % at 15 Å, 62-73 % at 30 Å, 71-78 % at 40 Å). 12 layers keep each bake under a second;
the whole file takes ~17 s.
"""
from functools import lru_cache

import bpy
import numpy as np
import pytest

from fibrilfit.model import params as P
from fibrilfit import pipeline

SEEDS = (0, 1, 2)


@lru_cache(maxsize=None)
def run(globule: float, linker: int, seed: int) -> tuple:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    r = pipeline.run_model(P.make_params(layers=12, globule_diameter=globule, linker=linker,
                                         seed=seed), bpy.context.scene)
    return r["verdict"], r["accommodated"], r["max_bond_stretch"], len(r["clashing_pairs"])


def accommodated(globule, linker) -> int:
    return sum(run(globule, linker, s)[1] for s in SEEDS)


def stretches(globule, linker) -> list[float]:
    return [run(globule, linker, s)[2] for s in SEEDS]


def test_longer_linkers_accommodate_more(scene):
    counts = [accommodated(30.0, linker) for linker in (1, 2, 4, 6, 8)]
    assert counts == sorted(counts)
    assert counts[0] == counts[1] == 0 and counts[-2] == counts[-1] == len(SEEDS)


def test_bigger_globules_fit_less_and_pull_harder(scene):
    sizes = (8.0, 15.0, 20.0, 30.0, 40.0)
    counts = [accommodated(g, 3) for g in sizes]
    assert counts == sorted(counts, reverse=True)
    assert counts[0] == len(SEEDS) and counts[-1] == 0
    median = [float(np.median(stretches(g, 1))) for g in sizes[1:]]
    assert all(b > a for a, b in zip(median, median[1:])), median


@pytest.mark.parametrize("globule", [15.0, 30.0, 40.0])
def test_very_short_linkers_clash_and_stretch(scene, globule):
    for seed in SEEDS:
        verdict, ok, stretch, pairs = run(globule, 1, seed)
        assert verdict == "intersection" and pairs > 0 and not ok
        assert stretch > 0.25  # measured 31-78 %


@pytest.mark.parametrize("globule", [30.0, 40.0])
def test_long_linkers_accommodate(scene, globule):
    for seed in SEEDS:
        verdict, ok, stretch, pairs = run(globule, 8, seed)
        assert verdict == "successful" and ok and pairs == 0
        assert stretch < 0.01  # measured under 0.1 %


@pytest.mark.parametrize("linker", [1, 2, 3])
def test_tiny_globules_always_fit(scene, linker):
    for seed in SEEDS:
        verdict, ok, stretch, pairs = run(8.0, linker, seed)
        assert verdict == "successful" and ok and pairs == 0
