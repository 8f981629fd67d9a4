"""Real fibril geometry (issue #14): protofilaments, a core outline, anchors anywhere."""
import math
import pytest
from fibrilfit.model import helix, params as P

U_CORE = [[-20, -11], [20, -11], [20, 11], [8, 11], [8, -3], [-8, -3], [-8, 11], [-20, 11]]


def test_derived_defaults_follow_the_other_parameters():
    p = P.make_params(pf_rotation="auto", anchor="auto", core_outline="box", protofilaments=3)
    assert (p.pf_rotation, p.anchor, p.core_outline) == (None, None, None)
    assert p.pf_angle == pytest.approx(2 * math.pi / 3)
    assert p.replace(slab=(50, 22, 4.8)).anchor_xy == (26.75, 0.0)  # not frozen at 21.75


def test_chain_layers_are_layer_major():
    layer, pf = helix.chain_layers(P.make_params(layers=3, protofilaments=2))
    assert layer.tolist() == [0, 0, 1, 1, 2, 2] and pf.tolist() == [0, 1, 0, 1, 0, 1]

BAD_GEOMETRY = [
    ({"core_outline": [[0, 0], [10, 0]]}, "core_outline", "at least 3 points"),
    ({"core_outline": [[0, 0], [10, 10], [10, 0], [0, 10]]}, "core_outline", "intersects itself"),
    ({"core_outline": [[0, 0], [10, 0], [20, 0]]}, "core_outline", "intersects itself"),  # folds back
    ({"core_outline": [[0, 0], [10, 0], [math.nan, 5]]}, "core_outline", "finite"),
    ({"anchor": (0, 0)}, "anchor", "inside the core"),
    ({"core_outline": U_CORE, "anchor": (0, -8)}, "anchor", "inside the core"),
    ({"anchor": (-21.75, 0), "protofilaments": 2, "pf_rotation": math.pi / 2,
      "slab": (40, 60, 4.8)}, "anchor", "inside the core"),
    ({"protofilaments": 0}, "protofilaments", "from 1 to 6"),
    ({"protofilaments": 7}, "protofilaments", "from 1 to 6"),
    ({"protofilaments": 2, "pf_rotation": 0.0}, "pf_rotation", "on top of"),
    ({"protofilaments": 2, "pf_rotation": 0.05}, "pf_rotation", "on top of"),
    ({"protofilaments": 2, "pf_rotation": 0.0, "pf_rise": 4.8}, "pf_rotation", "on top of"),
    ({"anchor": (21.75, 0, 1)}, "anchor", "two coordinates"),
]


@pytest.mark.parametrize("values,name,why", BAD_GEOMETRY, ids=lambda v: str(v)[:40])
def test_bad_geometry_is_refused_in_one_line_naming_the_parameter(values, name, why):
    with pytest.raises(P.ParamError) as err:
        P.make_params(**values)
    message = str(err.value)
    assert err.value.param == name and message.startswith(f"{name}: ") and "\n" not in message
    assert why.replace("on top of", "apart") in message


def test_anchors_apart_check_sees_the_next_layer():
    # protofilament 1 turned by 0.3 rad is 6.5 Å from protofilament 0: allowed
    P.make_params(protofilaments=2, pf_rotation=0.3)
    # turned by 0.1 rad (2.2 Å away in the plane) but raised 4.8 Å: no overlap in its own
    # layer, yet on layer 1's protofilament 0 (2.2 Å away): refused, naming both
    with pytest.raises(P.ParamError, match="apart"):
        P.make_params(protofilaments=2, pf_rotation=0.1, pf_rise=4.8, twist=0.0)
    P.make_params(protofilaments=2, pf_rotation=0.1, pf_rise=4.8, twist=0.0, layers=1)
