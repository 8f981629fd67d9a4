"""The one parameter definition: defaults, derived geometry, and refusals that name the range."""
import math

import pytest

from fibrilfit.model import params as P
from fibrilfit.model.param_checks import estimated_objects
from fibrilfit.model.chain import chain_x, rest_lengths


def test_defaults_are_the_tutorials():
    p = P.DEFAULTS
    assert p.slab == (40.0, 22.0, 4.8)
    assert (p.residue_radius, p.residue_spacing, p.linker) == (1.75, 3.5, 6)
    assert (p.globule_diameter, p.layers, p.rise, p.twist) == (30.0, 20, 4.8, 0.034)
    assert (p.gravity, p.seed, p.time_scale, p.frames) == (0.5, 0, 2.0, 250)


def test_chain_geometry_matches_the_tutorial():
    p = P.DEFAULTS
    assert p.anchor_x == pytest.approx(21.75)
    assert chain_x(p) == pytest.approx([21.75, 25.25, 28.75, 32.25, 35.75, 39.25, 56.0])
    assert rest_lengths(p) == pytest.approx([3.5] * 5 + [16.75])
    assert estimated_objects(p) == 280


BAD = [
    ({"slab": (0, 22, 4.8)}, "slab"),
    ({"slab": (40, -1, 4.8)}, "slab"),
    ({"slab": (40, 22)}, "slab"),
    ({"slab": ("nan", 22, 4.8)}, "slab"),
    ({"globule_diameter": 0}, "globule_diameter"),
    ({"globule_diameter": -30}, "globule_diameter"),
    ({"globule_diameter": math.nan}, "globule_diameter"),
    ({"globule_diameter": math.inf}, "globule_diameter"),
    ({"residue_radius": 0}, "residue_radius"),
    ({"linker": 0}, "linker"),
    ({"linker": 2.5}, "linker"),
    ({"layers": 0}, "layers"),
    ({"layers": "abc"}, "layers"),
    ({"frames": 0}, "frames"),
    ({"gravity": -0.1}, "gravity"),
    ({"rise": "x"}, "rise"),
    ({"seed": -1}, "seed"),
    ({"residue_spacing": 1.0}, "residue_spacing"),
    ({"score_layers": 10}, "score_layers"),
    ({"layers": 10_000}, "layers"),
    ({"colour": 1}, "colour"),
]


@pytest.mark.parametrize("values,name", BAD)
def test_bad_values_are_refused_naming_the_parameter(values, name):
    with pytest.raises(P.ParamError) as err:
        P.make_params(**values)
    assert err.value.param == name
    message = str(err.value)
    assert message.startswith(f"{name}: ") and "\n" not in message
    if name not in ("colour", "residue_spacing", "score_layers", "layers"):
        assert "from" in message and "to" in message  # the allowed range


def test_force_allows_large_models():
    assert P.make_params(layers=10_000, force=True).layers == 10_000


def test_strings_from_the_command_line_are_accepted():
    p = P.make_params(layers="8", twist="0.05", slab="40 22 4.8")
    assert (p.layers, p.twist, p.slab) == (8, 0.05, (40.0, 22.0, 4.8))


def test_validate_catches_params_made_directly():
    with pytest.raises(P.ParamError):
        P.validate(P.Params(linker=0))


def test_one_percent_format_for_every_display():
    from fibrilfit.exports.run_text import percent
    assert percent(0.05) == "5.0 %"
    assert percent(-0.00001) == "0.0 %"  # a tiny compression is not "-0.0 %"
    assert percent(-0.0123) == "-1.2 %"
    assert percent(7.971) == "797.1 %"


def test_a_params_is_validated_once_and_trusted_after(monkeypatch):
    p = P.make_params(linker=4)
    calls = []
    real = P.make_params
    monkeypatch.setattr(P, "make_params", lambda **kw: calls.append(kw) or real(**kw))
    assert P.validate(p) is p and P.validate(p, force=True) is p and not calls
    forced = real(force=True, layers=20000, linker=1)  # over the object limit: force lifts it
    with pytest.raises(P.ParamError, match="layers"):
        P.validate(forced)  # asked again without force: checked in full
    import dataclasses
    copied = dataclasses.replace(p, linker=-3)  # no mark: checked in full
    with pytest.raises(P.ParamError, match="linker"):
        P.validate(copied)
    with pytest.raises(P.ParamError, match="linker"):
        P.validate(P.Params(linker=0))


def test_the_defaults_are_validated_once_at_import(monkeypatch):
    calls = []
    real = P.make_params
    monkeypatch.setattr(P, "make_params", lambda **kw: calls.append(kw) or real(**kw))
    assert P.validate(P.DEFAULTS) is P.DEFAULTS and not calls
    assert P.DEFAULTS == P.Params()
