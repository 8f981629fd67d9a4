"""Sweeps: grid specs, the Wilson interval, summary and gate, and real sweeps on worker
processes and a Dask LocalCluster (small models, so each run takes a fraction of a second)."""
import json
import sys
import pytest
from fibrilfit.model import params as P
from fibrilfit.sweep import gate, grid, summary
from fibrilfit.sweep.stats import wilson


def lines(path):
    return [json.loads(line) for line in path.read_text().splitlines()]


def test_lists_and_inclusive_ranges():
    assert grid.parse_spec("linker", "2,4,6") == ["2", "4", "6"]
    assert grid.parse_spec("linker", "1:12") == [str(i) for i in range(1, 13)]
    # Decimal steps: exactly four values, each as typed (no 0.030000000000000002)
    assert grid.parse_spec("twist", "0.02:0.05:0.01") == ["0.02", "0.03", "0.04", "0.05"]
    assert grid.parse_spec("linker", "1:3, 8,2") == ["1", "2", "3", "8"]
    assert grid.parse_spec("twist", "-0.05:-0.03:0.01") == ["-0.05", "-0.04", "-0.03"]
    assert grid.parse_spec("layers", "10:20:4") == ["10", "14", "18"]


@pytest.mark.parametrize("spec, says", [
    ("2,,4", "empty item"), ("", "empty value"), ("12:1", "grid would be empty"),
    ("1:3:0", "positive step"), ("1:3:-1", "positive step"), ("1:2:3:4", "is not a list"),
    ("a:3", "is not a list"), ("1:nan", "is not a list"), ("0:1:0.000001", "at most"),
])
def test_malformed_specs_name_the_parameter(spec, says):
    with pytest.raises(P.ParamError) as e:
        grid.parse_spec("linker", spec)
    assert e.value.param == "linker" and says in str(e.value) and "\n" not in str(e.value)


def test_every_grid_point_goes_through_make_params():
    pts = grid.build({"linker": ["1", "12"], "globule_diameter": ["30", "45"]}, ["0", "1"])
    assert len(pts) == 8
    assert [p.point["seed"] for p in pts] == [0] * 4 + [1] * 4  # seed-major: even coverage
    assert {(p.params["linker"], p.params["globule_diameter"]) for p in pts} == {
        (1, 30.0), (1, 45.0), (12, 30.0), (12, 45.0)}
    assert pts[0].params == P.make_params(linker=1, globule_diameter=30, seed=0).to_dict()
    # "6" and "6.0" are one point
    assert len(grid.build({"linker": ["6", "6.0"]}, ["0"])) == 1
    with pytest.raises(P.ParamError, match=r"^linker: must be an integer from 1 to 200"):
        grid.build({"linker": ["0", "5"]}, ["0"])
    with pytest.raises(P.ParamError, match=r"^score_layers: .* for 2 layers"):
        grid.build({"layers": ["2", "8"], "score_layers": ["1"]}, ["0"])


def test_seeds():
    assert grid.seed_values(None, None) == ["0"]
    assert grid.seed_values(3, None) == ["0", "1", "2"]
    assert grid.seed_values(None, "5:7,11") == ["5", "6", "7", "11"]
    with pytest.raises(P.ParamError, match="grid would be empty"):
        grid.seed_values(0, None)
    with pytest.raises(P.ParamError, match="not both"):
        grid.seed_values(2, "1,2")


@pytest.mark.parametrize("k, n, low, high", [
    # Newcombe RG (1998) Stat Med 17:857-872, Table I, method 3 (Wilson score, no continuity
    # correction); the same values as statsmodels' proportion_confint(k, n, method="wilson").
    (81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605), (0, 20, 0.0, 0.1611),
    (1, 29, 0.0061, 0.1718),
])
def test_wilson_interval_matches_published_values(k, n, low, high):
    lo, hi = wilson(k, n)
    assert lo == pytest.approx(low, abs=5e-5) and hi == pytest.approx(high, abs=5e-5)


def test_wilson_interval_edges():
    assert wilson(0, 3)[0] == 0.0 and wilson(3, 3)[1] == 1.0
    lo, hi = wilson(3, 3)
    assert lo == pytest.approx(3 / (3 + 1.959963984540054 ** 2))  # k = n: n / (n + z²)
    with pytest.raises(ValueError):
        wilson(1, 0)


def _record(linker, diameter, seed, accommodated, verdict, stretch, frames=250, status="ok"):
    p = P.make_params(linker=linker, globule_diameter=diameter, seed=seed).to_dict()
    if status != "ok":
        return {"params": p, "seed": seed, "status": status, "error": "boom"}
    return {"params": p, "seed": seed, "status": "ok", "accommodated": accommodated,
            "verdict": verdict, "max_bond_stretch": stretch, "frames_simulated": frames,
            "envelope": {"outer_diameter": 100.0 + 10 * seed}}

SYNTHETIC = [
    _record(2, 30, 0, False, "intersection", 1.5), _record(2, 30, 1, False, "successful", 0.9),
    _record(4, 30, 0, True, "successful", 0.01), _record(4, 30, 1, False, "intersection", 0.02),
    _record(6, 30, 0, True, "successful", 0.0, 200), _record(6, 30, 1, True, "successful", 0.02),
    _record(6, 30, 2, None, None, None, status="failed"),
    _record(6, 45, 0, False, "intersection", 0.03), _record(6, 45, 1, True, "successful", 0.01),
]


def test_summary_pools_seeds_per_grid_point():
    rows = summary.rows(SYNTHETIC)
    assert [(r.values["globule_diameter"], r.values["linker"]) for r in rows] == [
        (30.0, 2), (30.0, 4), (30.0, 6), (45.0, 6)]
    r2, r4, r6, r6b = rows
    assert (r2.n, r2.accommodated, r2.clash_fraction, r2.median_stretch) == (2, 0, 0.5, 1.2)
    assert (r4.fraction, r4.interval) == (0.5, wilson(1, 2))
    assert (r6.n, r6.failed, r6.fraction, r6.median_frames) == (2, 1, 1.0, 225)
    assert summary.varied(rows) == ["linker", "globule_diameter"]
    csv = summary.csv_text(rows).splitlines()
    assert csv[0].startswith("linker,globule_diameter,n,failed,accommodated,accommodated_fraction,"
                             "wilson95_low,wilson95_high,clash_fraction,median_stretch")
    assert csv[3] == (f"6,30,2,1,2,1.0000,{wilson(2, 2)[0]:.4f},1.0000,0.0000,0.010000,225,"
                      f"105.0,100.0,110.0,tutorial")  # the envelope's outer diameter: median,
    # min, max; then the protocol (issue #23)
    assert r6.metric("outer_diameter") == 105.0
    minimal = {m.group["globule_diameter"]: m for m in summary.minimal_linkers(rows, 0.95)}
    assert minimal[30.0].row is r6 and minimal[45.0].row is None and minimal[45.0].best is r6b
    text = summary.table(rows, 0.95)
    assert "globule_diameter 30: linker 6 (all 2 of 2 seeds accommodated" in text
    assert "globule_diameter 45: none in this sweep (best: linker 6, 1/2" in text
    assert "fraction of seeds whose relaxation found a clash-free layout" in text


def test_gate_requirements():
    rows = summary.rows(SYNTHETIC)
    ok = gate.parse("linker=6,globule_diameter=30:accommodated>=0.9")
    assert ok.selector == {"linker": 6.0, "globule_diameter": 30.0}
    bad = gate.parse("globule-diameter=45 : accommodated >= 0.9")
    everywhere = gate.parse("failed==0")
    met, failed = gate.check([ok, bad, everywhere], rows)
    assert met == ["requirement met: linker=6,globule_diameter=30:accommodated>=0.9: "
                   "accommodated 1 (2/2)"]
    assert failed[0] == ("requirement failed: globule-diameter=45 : accommodated >= 0.9: "
                         "globule_diameter=45: accommodated 0.5 (1/2), needs >= 0.9")
    assert failed[1:] == ["requirement failed: failed==0: linker=6, globule_diameter=30: "
                          "failed 1, needs == 0"]
    assert gate.check([gate.parse("linker=8:n>=1")], rows)[1] == [
        "requirement failed: linker=8:n>=1: no grid point has linker=8"]
    for text, says in [("linker=6", "METRIC OP NUMBER"), ("x>=1", "unknown metric"),
                       ("seed=1:n>=1", "pooled"), ("linker=a:n>=1", "not a number"),
                       ("colour=1:n>=1", "not a parameter"), ("n>=lots", "not a number")]:
        with pytest.raises(P.ParamError, match=says):
            gate.parse(text)


def test_phase_plot_layouts(tmp_path):
    from fibrilfit.sweep import plot
    rows = summary.rows(SYNTHETIC)
    assert plot.layout(rows) == ("lines", "linker", ["globule_diameter"])
    two = summary.rows([
        {**r, "params": {**r["params"], "twist": tw}} for r in SYNTHETIC[:6]
        for tw in (0.02, 0.04)])
    assert plot.layout(two) == ("heatmap", "linker", ["twist"])
    assert plot.layout(summary.rows([
        {**r, "params": {**r["params"], "twist": 0.01 * r["seed"]}} for r in SYNTHETIC
        if r["params"]["linker"] == 6])) == ("lines", "twist", ["globule_diameter"])
    for name, rs in (("lines.png", rows), ("heatmap.png", two)):
        plot.write(tmp_path / name, rs, 0.95)
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["heatmap.png", "lines.png"]


def test_workers_that_cannot_start_stop_the_sweep_with_one_line():
    from fibrilfit.batch.executors import ProcessExecutor, SweepError
    ex = ProcessExecutor(2)
    ex.worker_argv = [sys.executable, "-c", "import sys; print('no bpy here', file=sys.stderr); "
                                        "sys.exit(3)"]
    with ex, pytest.raises(SweepError, match="cannot start: worker pid .* exited with code 3: "
                                             "no bpy here"):
        ex.submit({"id": 0, "attempt": 1, "params": {}, "force": False})
        ex.wait()


U_CORE = [[-20, -11], [20, -11], [20, 11], [8, 11], [8, -3], [-8, -3], [-8, 11], [-20, 11]]


def test_geometry_parameters_are_sweep_axes(tmp_path):
    (tmp_path / "u.json").write_text(json.dumps(U_CORE))
    from fibrilfit import cli
    from fibrilfit.api.plans import SweepPlan, make_plan
    args = cli.build_parser().parse_args([
        "sweep", "--protofilaments", "1,2", "--pf-rotation", "auto,3.1294", "--pf-rise", "0:2:2",
        "--core-outline", f"box,{tmp_path / 'u.json'}", "--anchor", "0,21.75", "-12.75",
        "--out", str(tmp_path / "s")])
    plan, _ = make_plan(SweepPlan, {k: v for k, v in vars(args).items() if k != "command"})
    specs = grid.specs_from(plan.model)
    assert specs["protofilaments"] == ["1", "2"] and specs["pf_rise"] == ["0", "2"]
    assert specs["anchor"] == ["0 -12.75", "21.75 -12.75"]
    points = grid.build(specs, ["0"])
    # every point is validated before any run: an anchor inside the U's base is refused
    with pytest.raises(P.ParamError, match="^anchor: .*inside the core"):
        grid.build({**specs, "anchor": ["0 -5"]}, ["0"])
    seen = {(p.params["protofilaments"], p.params["pf_rotation"], p.params["pf_rise"],
             p.params["core_outline"] is None, tuple(p.params["anchor"])) for p in points}
    assert len(seen) == len(points) == 32
    assert all(p.point["core_outline"] in (None, [[float(x), float(y)] for x, y in U_CORE])
               for p in points)


def test_summary_names_outlines_and_derived_values():
    rows = summary.rows([
        {"params": P.make_params(linker=6).to_dict(), "accommodated": True, "verdict": "successful",
         "max_bond_stretch": 0.0, "frames_simulated": 100},
        {"params": P.make_params(linker=6, core_outline=U_CORE, anchor=(0, -1)).to_dict(),
         "accommodated": False, "verdict": "intersection", "max_bond_stretch": 0.0,
         "frames_simulated": 100}])
    assert [r.values["core_outline"] is None for r in rows] == [True, False]  # None sorts first
    text = summary.table(rows, 0.95)
    assert "8-point outline" in text and "auto" in text
    assert summary.csv_text(rows).splitlines()[0].startswith("linker,globule_diameter,core_outline,")
