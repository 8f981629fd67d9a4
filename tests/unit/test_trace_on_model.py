"""structure/trace.py's on_model: the imported fibril's CA trace on the model's frame (issue
#33): a whole number of layers along the model's screw, so every file layer sits on a model
layer, the file's stack centred in the model's."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from fibrilfit.structure.trace import on_model, relative_layers

RISE, TWIST = 4.8, math.radians(-1.5)


def layer_points(m: int) -> np.ndarray:
    """Three CA of a chain at layer m of a perfect screw, in the layer frame."""
    xy = np.array([[10.0, 0.0], [12.0, 3.0], [9.0, -4.0]])
    c, s = math.cos(m * TWIST), math.sin(m * TWIST)
    turned = xy @ np.array([[c, -s], [s, c]]).T
    return np.column_stack([turned, np.full(3, m * RISE)])


def test_relative_layers_count_from_each_protofilaments_reference_chain():
    fib = SimpleNamespace(layer_chains=[["A", "B", "C", "D", "E"], ["F", "G", "H"]],
                          anchors=[{"chain": "C"}, {"chain": "F"}])
    assert relative_layers(fib) == [-2, -1, 0, 1, 2, 0, 1, 2]


@pytest.mark.parametrize("model_layers", [20, 5, 4])
def test_file_layers_land_on_model_layers_centred(model_layers):
    layers = [-2, -1, 0, 1, 2]
    chains = [(f"c{m}", np.arange(3), layer_points(m)) for m in layers]
    moved, s = on_model(chains, layers, model_layers, RISE, TWIST)
    model_layer = [m + s for m in layers]
    for (_, _, xyz), k in zip(moved, model_layer):
        # exactly where the model's layer k puts the same chain: phase kept, on the axis
        assert np.allclose(xyz, layer_points(k), atol=1e-9)
    # centred: as many model layers below the file's stack as above (to one)
    below, above = model_layer[0], model_layers - 1 - model_layer[-1]
    assert abs(below - above) <= 1
    if model_layers == 20:
        assert model_layer == [7, 8, 9, 10, 11]


def test_the_radius_from_the_axis_is_kept():
    layers = [0, 1]
    chains = [("a", np.arange(3), layer_points(0)), ("b", np.arange(3), layer_points(1))]
    moved, _ = on_model(chains, layers, 20, RISE, TWIST)
    for (_, _, before), (_, _, after) in zip(chains, moved):
        assert np.allclose(np.hypot(*before[:, :2].T), np.hypot(*after[:, :2].T))
