"""The decorated fibril's envelope: radial distances of the domain centres from the fibril axis."""
import json
import math

import numpy as np
import pytest
from helpers import run_cli

from fibrilfit.model import params as P
from fibrilfit.model.chain import chain_x
from fibrilfit import pipeline
from fibrilfit.analysis.envelope import envelope
from fibrilfit.exits import UsageError
from fibrilfit.exports import envelope_plot


def test_hand_placed_ring():
    """Domains on a ring of 50 Å, at any angle and height: every r is 50."""
    angles = np.linspace(0, 2 * math.pi, 20, endpoint=False)
    centres = np.c_[50 * np.cos(angles), 50 * np.sin(angles), 4.8 * np.arange(20)]
    env = envelope(centres, radius=15)
    assert (env["r_median"], env["r95"], env["r_max"], env["n"]) == (50, 50, 50, 20)
    assert env["outer_diameter"] == 2 * (50 + 15)


def test_hand_placed_spread():
    """r = 1..100 Å along a line through the axis: median 50.5, and the 95th percentile by
    linear interpolation 1 + 0.95 * 99 = 95.05; a 3-4-5 triangle gives r = 5; z is ignored."""
    centres = [(r * (-1) ** r, 0, 7 * r) for r in range(1, 101)]
    env = envelope(centres, radius=10)
    assert (env["r_median"], env["r95"], env["r_max"]) == (50.5, 95.05, 100)
    assert env["outer_diameter"] == pytest.approx(2 * (95.05 + 10))
    assert envelope([(3, 4, 100)], 1)["r95"] == 5
    assert envelope(np.zeros((0, 3)), 1) == {"r_median": None, "r95": None, "r_max": None,
                                             "outer_diameter": None, "n": 0}


@pytest.mark.parametrize("twist, linker", [(0.034, 6), (-0.124, 9)])
def test_built_model_envelope_is_the_geometry(scene, twist, linker):
    """Before the bake every globule sits where the build put it, at chain_x[-1] from the axis
    whatever the layer's turn; the check reports exactly that."""
    p = P.make_params(layers=10, linker=linker, twist=twist, score_layers=2)
    model = pipeline.build(p, scene)
    env = pipeline.check(model, scene)["envelope"]
    r = chain_x(p)[-1]  # anchor 21.75 + 3.5 (linker - 1) + 1.75 + R
    assert r == 21.75 + 3.5 * (linker - 1) + 1.75 + 15
    assert env["n"] == 6  # the scored layers only
    assert env["r_median"] == pytest.approx(r, abs=1e-3)
    assert env["r95"] == pytest.approx(r, abs=1e-3)
    assert env["outer_diameter"] == pytest.approx(2 * (r + 15), abs=2e-3)


def test_every_result_has_the_envelope_of_its_scored_layers(scene):
    r = pipeline.run_model(P.make_params(layers=6, linker=4, frames=40, seed=1), scene)
    centres = np.asarray(r["globule_centres"])
    radii = np.hypot(centres[:, 0], centres[:, 1])
    assert r["envelope"]["n"] == 6
    assert r["envelope"]["r_median"] == pytest.approx(np.median(radii), abs=1e-3)
    assert r["envelope"]["r95"] <= r["envelope"]["r_max"] == pytest.approx(radii.max(), abs=1e-3)


def test_envelope_plot_written(tmp_path):
    png, out = tmp_path / "env.png", tmp_path / "r.json"
    cp = run_cli("run", "--layers", "5", "--linker", "4", "--frames", "30", "--envelope-plot",
                 str(png), "--json", str(out))
    assert cp.returncode == 0, cp.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = json.loads(out.read_text())
    assert r["envelope_plot"] == {"path": str(png)}
    assert f"outer diameter {r['envelope']['outer_diameter']:.0f} Å" in cp.stdout


def test_envelope_plot_refused_without_matplotlib_or_a_check(monkeypatch, tmp_path):
    cp = run_cli("run", "--stop-after", "build", "--envelope-plot", str(tmp_path / "e.png"))
    assert cp.returncode == 2 and "--envelope-plot: needs the check" in cp.stderr
    monkeypatch.setattr(envelope_plot.importlib.util, "find_spec", lambda name: None)
    with pytest.raises(UsageError, match="^--envelope-plot needs the Python package "
                                         "matplotlib, which this Python .* pip install "
                                         "matplotlib$"):
        envelope_plot.available()


