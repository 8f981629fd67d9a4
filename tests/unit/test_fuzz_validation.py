"""Property-based fuzzing of the parameter validation: any input either builds a valid model or
is refused with ParamError, never anything else."""
import collections
import dataclasses
import math
from hypothesis import event, given, settings, strategies as st
from fibrilfit.model import params as P

FIELDS = {f.name: f.metadata for f in dataclasses.fields(P.Params)}

junk = st.one_of(
    st.none(), st.booleans(), st.text(max_size=6), st.binary(max_size=4),
    st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**12, 10**12),
    st.lists(st.floats(-1e3, 1e3), max_size=4), st.dictionaries(st.text(max_size=2), st.integers()),
)


def near_range(meta):
    lo, hi = meta["min"], meta["max"]
    if "choices" in meta:
        return st.sampled_from([*meta["choices"], "", "Tutorial ", "other"])
    if meta["kind"] is bool:
        return st.booleans()
    if meta["kind"] is str:  # free text (a per-layer pattern): its letters and others
        return st.text(alphabet="AB.a x", max_size=5)
    if meta["kind"] is int:
        return st.integers(int(lo) - 3, min(int(hi) + 3, 10**7))
    return st.floats(lo - 1.0, hi + 1.0, allow_nan=False) | st.sampled_from([lo, hi, 0.0, -0.0])

SMALLER = {"layers": (1, 3000), "score_layers": (0, 5)}  # keeps combination limits reachable


def in_range(meta, name=None):
    if name in SMALLER:
        return st.integers(*SMALLER[name])
    if "choices" in meta:
        return st.sampled_from(meta["choices"])
    if meta["kind"] is bool:
        return st.booleans()
    if meta["kind"] is str:  # free text (a per-layer pattern): patterns it accepts
        return st.sampled_from(["A", "A.", ".A", "A..", "AA."])
    if meta["kind"] is int:
        return st.integers(int(meta["min"]), min(int(meta["max"]), 10**7))
    return st.floats(meta["min"], meta["max"])


def polygons(coord):
    """Any list of points: valid outlines, too few points, crossings, repeats."""
    return st.lists(st.tuples(coord, coord), min_size=0, max_size=8)


def shaped(name, each, points):
    """A value of this field's shape (three for the slab, `size` for a tuple, a polygon for
    points: `points()`) whose numbers are drawn from `each`."""
    meta = FIELDS[name]
    if name == "slab":
        return st.tuples(each, each, each)
    if meta["size"]:
        return st.tuples(*[each] * meta["size"])
    if meta["kind"] == "points":
        return points()
    return each


def good_value(name):
    """Every number within its range: refused, if at all, only as a combination."""
    meta = FIELDS[name]
    good = shaped(name, in_range(meta, name), lambda: polygons(st.floats(-60, 60)))
    return st.one_of(good, st.none(), st.just("auto")) if meta["derived"] else good


def value_for(name):
    meta = FIELDS[name]
    edge = shaped(name, near_range(meta), lambda: polygons(near_range({**meta, "kind": float})))
    good = good_value(name)
    # mostly valid values, so that accepted sets are common too, with every kind of bad one
    return st.one_of(*[good] * 24, edge, edge.map(str), junk)

known_sets = st.fixed_dictionaries({}, optional={name: value_for(name) for name in FIELDS})

unknown_sets = st.dictionaries(st.text(min_size=1, max_size=8), junk, min_size=1, max_size=2)

# Sets of 4-12 fields, every value in range: most sets above hold some bad value and are
# refused, so without these an accepted set of more than three fields never occurs (a check
# that refused every larger set passed the 1500 examples before).
valid_sets = st.lists(st.sampled_from(sorted(FIELDS)), min_size=4, max_size=12,
                      unique=True).flatmap(
    lambda names: st.fixed_dictionaries({name: good_value(name) for name in names}))

param_sets = st.one_of(known_sets, known_sets, known_sets,
                       st.builds(lambda a, b: {**a, **b}, known_sets, unknown_sets),
                       valid_sets, valid_sets)


SEEN = collections.Counter()


@settings(max_examples=1500, deadline=None, derandomize=True, database=None)
@given(param_sets)
def _accepted_or_refused_with_paramerror_only(values):
    try:
        p = P.make_params(**values)
    except P.ParamError as exc:
        assert exc.param and "\n" not in str(exc)
        event("refused")
        SEEN["refused"] += 1
        return
    event("accepted")
    SEEN["accepted"] += 1
    SEEN[f"accepted {len(values)}"] += 1
    for f in dataclasses.fields(P.Params):
        v = getattr(p, f.name)
        if v is None:  # a derived default, or an empty list (kind "list": e.g. one domain)
            assert f.metadata["derived"] or f.metadata["kind"] == "list"
            continue
        if "choices" in f.metadata:
            assert v in f.metadata["choices"]
            continue
        if f.metadata["kind"] is str:  # free text: a per-layer pattern of known letters
            assert isinstance(v, str) and v and set(v) <= set("AB.")
            continue
        if f.metadata["kind"] == "points":
            v = [x for xy in v for x in xy]
            assert len(v) >= 6
        if f.metadata["kind"] == "rows":  # rows of `size` numbers (a domain's shape)
            assert all(len(row) == f.metadata["size"] for row in v)
            v = [x for row in v for x in row]
        for x in (v if isinstance(v, (tuple, list)) else (v,)):
            assert isinstance(x, (int, float)) and math.isfinite(x)
            if f.metadata["kind"] is not bool:
                assert f.metadata["min"] <= x <= f.metadata["max"]
    assert P.validate(p) == p


def test_validation_accepts_or_refuses_with_paramerror_only():
    """Both branches are exercised, in a measured share, and accepted sets of every size: with
    derandomize the 1500 examples are the same for one hypothesis version and the same tests run
    before in the process: measured 2026-11-27 with hypothesis 6.170.17 (.venv and .venv52), 292
    accepted (19.5 %), 279 of them with more than three fields, the largest with 12, 1208 refused
    (this file alone); 340 accepted, 326 above three fields, after test_bound.py's hypothesis
    tests in the same process. So the bands, not one count, are asserted: a strategy that drifted
    to all refused, to mostly accepted, or to no accepted set above three fields fails, and a
    validation that refused every set of more than three fields (planted in a scratch copy: 13
    accepted, none above three) fails here."""
    SEEN.clear()
    _accepted_or_refused_with_paramerror_only()
    sizes = {int(k.split()[1]): n for k, n in SEEN.items() if k.startswith("accepted ")}
    many = sum(n for size, n in sizes.items() if size > 3)
    assert SEEN["accepted"] + SEEN["refused"] == 1500
    assert 100 <= SEEN["accepted"] <= 600 and many >= 0.8 * SEEN["accepted"], SEEN
    assert max(sizes) == 12, SEEN
