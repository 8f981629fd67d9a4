"""Property-based fuzzing of the build: any parameter set the validation accepts builds a valid
model, and a refused one builds nothing (the validation's own fuzzing: tests/unit/test_fuzz_validation.py)."""
import collections
import math

import numpy as np
from hypothesis import HealthCheck, event, example, given, settings, strategies as st

from fibrilfit.model import params as P
from fibrilfit.model.param_checks import estimated_objects
from fibrilfit.builders import build_model


def polygons(coord):
    """Any list of points: valid outlines, too few points, crossings, repeats."""
    return st.lists(st.tuples(coord, coord), min_size=0, max_size=8)


small_models = st.fixed_dictionaries({}, optional={
    "layers": st.integers(-1, 6), "linker": st.integers(-1, 8), "seed": st.integers(0, 9),
    "globule_diameter": st.floats(-5, 80, allow_nan=False) | st.just(math.nan),
    "residue_radius": st.floats(-1, 5, allow_nan=False), "residue_spacing": st.floats(-1, 8),
    "rise": st.floats(-1, 20, allow_nan=False), "twist": st.floats(-4, 4, allow_nan=False),
    "slab": st.tuples(*[st.floats(-1, 60, allow_nan=False)] * 3),
    "score_layers": st.integers(-1, 4), "protofilaments": st.integers(0, 7),
    "pf_rotation": st.none() | st.floats(-7, 7), "pf_rise": st.floats(-6, 6),
    "anchor": st.none() | st.tuples(st.floats(-60, 60), st.floats(-60, 60)),
    "core_outline": st.none() | polygons(st.floats(-40, 40)),
    "protocol": st.sampled_from(P.PROTOCOLS)})


def test_any_accepted_set_builds_a_valid_model(scene):
    """Both branches in a measured share: derandomized, the 150 examples (and the explicit one)
    are the same every run of one hypothesis version; measured 2026-11-27 on bpy 4.2, 5.0.1 and
    5.2.3: 26 built, 125 refused. The band (10-75 built of 151) leaves room for another
    hypothesis version's draws; a strategy that drifted to all refused (nothing built: the
    build's checks never run) or to all accepted (no refusal tested) fails."""
    seen = collections.Counter()

    @settings(max_examples=150, deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(small_models)
    # found by this test: the triangle with a fourth corner on an edge is one convex piece
    @example({"core_outline": [(0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (0.0, 0.0)]})
    def one(values):
        try:
            p = P.make_params(**values)
        except P.ParamError:
            assert not scene.objects  # refused before anything was built
            event("refused")
            seen["refused"] += 1
            return
        event("built")
        seen["built"] += 1
        from fibrilfit.builders import clear_model
        try:
            model = build_model(p, scene)
            if p.core_outline is None:
                assert len(scene.objects) == estimated_objects(p)
            else:  # its convex pieces may merge below the n - 2 triangles the estimate counts
                assert estimated_objects(p) - p.layers * (len(p.core_outline) - 2) \
                    < len(scene.objects) <= estimated_objects(p)
            centres = np.array([ob.matrix_world.translation for c in model.chain for ob in c])
            assert np.isfinite(centres).all()
            assert len(model.chain) == p.chains and all(len(c) == p.linker + 1 for c in model.chain)
            assert len(model.slabs) == p.layers
        finally:  # a failing example must not leave a model behind for the next one
            clear_model(scene)

    one()
    assert sum(seen.values()) == 151 and 10 <= seen["built"] <= 75, seen
