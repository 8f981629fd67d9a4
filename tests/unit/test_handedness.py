"""A twist's hand, said once (model/helix.py, handedness: the panel, `inspect` and the summary ask it)."""
from fibrilfit.model import helix


def test_the_hand_of_a_twist_and_of_none():
    assert helix.handedness(0.034) == "right-handed"
    assert helix.handedness(-0.0168) == "left-handed"
    assert helix.handedness(0.0) == helix.handedness(-0.0) == "no twist"
