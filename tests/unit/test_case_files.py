"""Case files: load, save, round trip, options that win, and refusals naming the key."""
import tomllib
import pytest
from helpers import ROOT
from hypothesis import given, settings, strategies as st
from fibrilfit.model import cases, params as P


@settings(max_examples=60, deadline=None)
@given(twist=st.floats(-3.14, 3.14), diameter=st.floats(0.5, 500), linker=st.integers(1, 200),
       settle=st.booleans(),
       name=st.text(st.characters(blacklist_categories=("Cs",)), max_size=40))
def test_the_writer_reads_back_exactly(twist, diameter, linker, settle, name):
    p = P.make_params(twist=twist, globule_diameter=diameter, linker=linker, settle=settle,
                      force=True)  # a twist beyond ±0.2 rad needs force (issue #23)
    text = cases.dumps(cases.Case({"name": name}, {}).resolved(p))
    back = cases.from_dict(tomllib.loads(text))
    assert back.make_params(force=True) == p and back.meta == {"name": name}


def test_every_parameter_is_a_case_key():
    """The schema is params.Params: a parameter added there is accepted by itself. (A default
    of None, worked out from other parameters, is left out: TOML has no null.)"""
    text = cases.dumps(cases.Case({}, {}).resolved(P.DEFAULTS))
    assert set(tomllib.loads(text)["params"]) == {f.name for f in P.fields()
                                                  if getattr(P.DEFAULTS, f.name) is not None}
    for name, value in P.DEFAULTS.to_dict().items():
        case = cases.from_dict({"params": {name: value}} if value is not None else {})
        assert case.make_params() == P.DEFAULTS, name


def test_examples_load():
    """Every gallery case is valid and says where it comes from and which numbers are estimates."""
    paths = sorted((ROOT / "examples").glob("*.toml"))
    assert len(paths) >= 6
    for path in paths:
        case = cases.load(path)
        case.make_params()
        assert {"name", "observed", "expected", "estimates"} <= set(case.meta), path.name
        assert case.meta.keys() & {"citation", "source"}, path.name
        assert case.seeds, path.name


def test_sweep_grid_takes_inline_points():
    from fibrilfit.sweep import grid
    square = [[-20, -12], [20, -12], [20, 12], [-20, 12]]
    values = {**{f.name: None for f in P.fields() if f.name != "core_outline"},
              "core_outline": square}
    (point,) = grid.build(grid.specs_from(values), ["0"])
    assert point.params["core_outline"] == square


def test_integer_parameters_that_take_a_word():
    case = cases.from_dict({"params": {"periodic": "auto", "score_layers": "all",
                                       "globule_diameter": 30.0}})
    p = case.make_params()
    assert p.periodic > 0 and p.score_layers == 0
    with pytest.raises(cases.CaseError, match="params.periodic: must be a number"):
        cases.from_dict({"params": {"periodic": "some"}})


def test_a_case_of_several_domains_in_a_cell_under_inflate_loads(tmp_path):
    """Several domains per chain with inflate and a periodic cell, from a case file (#24)."""
    path = tmp_path / "tdp.toml"
    path.write_text('name = "three domains"\n[params]\nprotofilaments = 2\nlinker = 8\n'
                    'globule_diameter = 31.0\ndomain_diameters = [31.0, 30.0]\n'
                    'domain_linker = [4, 4]\nrise = 4.78\nperiodic = "auto"\n'
                    'protocol = "inflate"\n')
    p = cases.load(path).make_params()
    assert p.protocol == "inflate" and p.periodic == 13 and [d.member for d in p.domains] == [8, 13, 18]
