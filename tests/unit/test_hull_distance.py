"""tests/hull_distance.py (qhull's Minkowski difference) against distances known in closed form:
the truth the shape tests (tests/blender/test_domain_shapes.py, test_several_shapes.py) use
instead of the checker's own GJK (fibrilfit.analysis.exact, which imports mathutils, is compared
with it there)."""
import numpy as np
import pytest
from hull_distance import hull_distance_qhull

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)


@pytest.mark.parametrize("shift, want", [((3.0, 0, 0), 2.0), ((2.0, 2.0, 0), np.sqrt(2.0)),
                                         ((2.0, 3.0, 4.0), np.sqrt(1 + 4 + 9)),
                                         ((0.5, 0.5, 0.5), 0.0), ((1.0, 0, 0), 0.0)])
def test_the_qhull_distance_of_two_cubes(shift, want):
    assert hull_distance_qhull(CUBE, CUBE + shift) == pytest.approx(want, abs=1e-9)


def test_a_point_over_a_face_and_a_point_off_an_edge():
    assert hull_distance_qhull(CUBE, [[0.3, 0.6, 2.5]]) == pytest.approx(1.5, abs=1e-9)
    assert hull_distance_qhull(CUBE, [[0.3, 2.0, 2.0]]) == pytest.approx(np.sqrt(2), abs=1e-9)

