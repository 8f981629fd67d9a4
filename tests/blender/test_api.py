"""The Python API (fibrilfit.api) gives the command line's answer: restarts, the minimal-linker
walk and the report on 6CU7 + ubiquitin, each run once through `fibrilfit ...` (cli.main, in
this process) and once from Python with the same values, compared value for value. Small
settings (3-4 layers, 2 restarts, short walks) keep each case under a minute; the answers are
the measured ones at these settings (bpy 4.2, 5.0, 5.2)."""
import json

import pytest

from helpers import ROOT

DATA = ROOT / "tests" / "data"

FIBRIL, DOMAIN = str(DATA / "6cu7.pdb.gz"), str(DATA / "1ubq.pdb.gz")
FILES = ["--fibril", FIBRIL, "--domain", DOMAIN]

# The API and the command line are the same code on every bpy (what the physics gives on each bpy
# is other files' question): on the Makefile's BPY only (tests/blender/conftest.py). About 105 s.
pytestmark = pytest.mark.one_bpy


def test_restarts_from_python_match_run_restarts(scene, ff, tmp_path, capsys):
    from fibrilfit import api
    out = tmp_path / "cli.json"
    assert ff.cli.main(["run", *FILES, "--layers", "4", "--linker", "8", "--restarts", "2",
                        "--workers", "2", "--quiet", "--json", str(out)]) == 0
    cli = json.loads(out.read_text())
    py = api.restarts(2, fibril=FIBRIL, domain=DOMAIN, layers=4, linker=8, workers=2,
                      quiet=True)
    assert py.restarts["p_fit"] == cli["restarts"]["p_fit"] == 1.0
    assert py.restarts["best_seed"] == cli["restarts"]["best_seed"]
    assert [r["accommodated"] for r in py.restarts["runs"]] == \
        [r["accommodated"] for r in cli["restarts"]["runs"]]
    assert (py.answer, py.verdict) == (cli["answer"], cli["verdict"]) == ("fits", "successful")
    assert py.data["sources"] == cli["sources"]
    assert json.loads(py.to_json())["params"] == cli["params"]


def test_the_minimal_linker_walk_from_python_matches_the_command(scene, ff, tmp_path, capsys):
    from fibrilfit import api
    common = ["--layers", "3", "--restarts", "2", "--max-linker", "6", "--workers", "2",
              "--no-plot", "--quiet"]
    assert ff.cli.main(["minimal-linker", *FILES, *common, "--out", str(tmp_path / "cli")]) == 0
    cli = json.loads((tmp_path / "cli" / "minimal_linker.json").read_text())
    py = api.minimal_linker(fibril=FIBRIL, domain=DOMAIN, layers=3, restarts=2, max_linker=6,
                            workers=2, no_plot=True, quiet=True, out=str(tmp_path / "py"))
    keys = ("globule_diameter", "minimal_linker", "p_fit", "linker_below", "p_fit_below",
            "restarts", "restarts_below", "floor", "tried")
    assert [{k: r[k] for k in keys} for r in py.rows] == [{k: r[k] for k in keys}
                                                          for r in cli["rows"]]
    assert py.minimal() == cli["rows"][0]["minimal_linker"] == 2
    # the model as given: the command line's values are its words, Python's are numbers
    assert {k: str(v) for k, v in py.data["model"].items() if k != "seeds"} == \
        {k: str(v) for k, v in cli["model"].items() if k != "seeds"}
    assert py.data["model"]["seeds"] == cli["model"]["seeds"] == [0, 1]


def test_the_report_from_python_matches_the_command(scene, ff, tmp_path, capsys):
    from fibrilfit import api
    look = ["--render-engine", "workbench", "--render-size", "64x36"]
    assert ff.cli.main(["report", *FILES, "--linker", "8", "--layers", "4", "--restarts", "2",
                        "--max-linker", "12", "--workers", "2", "--quiet", *look,
                        "--out", str(tmp_path / "cli")]) == 0
    cli = json.loads((tmp_path / "cli" / "report.json").read_text())
    py = api.report(fibril=FIBRIL, domain=DOMAIN, linker=8, layers=4, restarts=2,
                    max_linker=12, workers=2, quiet=True, render_engine="workbench",
                    render_size="64x36", out=str(tmp_path / "py"))
    assert (py.answer, py.minimal_linker) == (cli["answer"], cli["minimal_linker"]["linker"]) \
        == ("fits", 2)
    assert py.p_fit["fits"] == cli["p_fit"]["fits"] == 2
    assert py.bracket == cli["bracket"]
    assert py.data["sources"] == cli["sources"]
    assert py.data["model"] == cli["model"]
    assert (tmp_path / "py" / "report.html").is_file()
    # the API's reproduce line is a command that runs: it names every value given
    assert py.data["command"][:2] == ["fibrilfit", "report"]
    assert "--restarts" in py.data["command"] and "--max-linker" in py.data["command"]


def test_a_bad_value_from_python_is_the_command_lines_one_line(ff, capsys):
    from fibrilfit import api
    from fibrilfit.plans import PlanError
    with pytest.raises(PlanError, match=r"^--restarts: must be at least 1 \(got 0\)$") as err:
        api.report(linker=8, restarts=0)
    assert err.value.field == "restarts"
    assert ff.cli.main(["report", "--linker", "8", "--restarts", "0"]) == 2
    assert capsys.readouterr().err.strip() == f"fibrilfit: error: {err.value}"
    with pytest.raises(PlanError, match=r"^--colour: not an option of report$"):
        api.report(colour="red")
