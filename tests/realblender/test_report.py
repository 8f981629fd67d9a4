"""The report in the real Blender 4.3.2 from the installed zip (issue #33): `blender -b -c
fibrilfit report` gives the bpy module's report.json numbers for the same seeds, with its
pictures (matplotlib from the zip's wheels); its render carries the legend and the scale bar
(pixels checked); and the page, opened in a real browser (Debian's Chromium, headless, no
network), renders with every image loaded. The screenshot stays in out/realblender/ (the docs
show the real command's page, docs/report_6cu7.png, made by `make pictures`)."""
import shutil

import numpy as np
import pytest

from realblender.helpers import OUT, chroot, inside, module, quote, read_json

# the session (or the two reports) runs in the first test's set-up: minutes under a loaded
# machine, beyond the suite's 300 s per test (pyproject's timeout)
pytestmark = pytest.mark.timeout(1200)

# Small and fast (as tests/blender/test_report.py's FAST, but Cycles: no OpenGL in the chroot):
# 12 Å domains on 3 layers, 2 restarts, the walk up to 4 residues.
ARGS = ["report", "--layers", "3", "--grow-frames", "20", "--hold-frames", "20",
        "--regrow-cycles", "0", "--globule-diameter", "12", "--linker", "3", "--restarts", "2",
        "--max-linker", "4", "--workers", "2", "--render-size", "480x270",
        "--render-samples", "4", "--quiet"]


@pytest.fixture(scope="module")
def reports(installed):
    real, ref = OUT / "report-blender", OUT / "report-module"
    cp = chroot(f"rm -rf {inside(real)} && blender -b -c fibrilfit {quote(ARGS)} "
                f"--out {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    shutil.rmtree(ref, ignore_errors=True)
    cp_ref = module([*ARGS, "--out", str(ref)])
    assert cp_ref.returncode == 0, cp_ref.stderr[-2000:]
    return {"real": real, "ref": ref, "real_doc": read_json(real / "report.json"),
            "ref_doc": read_json(ref / "report.json")}


def numbers(doc):
    pf, m, best = doc["p_fit"], doc["minimal_linker"], doc["best_layout"]
    return {"answer": doc["answer"], "model": doc["model"],
            "p_fit": {k: pf[k] for k in ("fits", "runs", "low", "high", "linker", "seeds",
                                         "best_seed")},
            "per_seed": [(r["seed"], r["status"], r["verdict"], r["accommodated"])
                         for r in pf["per_seed"]],
            "minimal_linker": {k: m[k] for k in ("linker", "linker_below", "p_fit",
                                                 "p_fit_below", "tried", "error")},
            "best": {k: best.get(k) for k in ("seed", "verdict", "accommodated")}}


def test_the_installed_report_gives_the_bpy_modules_numbers(reports):
    real, ref = reports["real_doc"], reports["ref_doc"]
    assert real["versions"]["blender"] == "4.3.2" and ref["versions"]["blender"] != "4.3.2"
    assert real["versions"]["matplotlib"] == "3.10.9"  # the zip's wheel
    assert numbers(real) == numbers(ref)
    # measured (bpy 4.2, 5.0, 5.2 and Blender 4.3.2): 12 Å domains on 3 layers fit at every
    # linker, 2 of 2 at linker 3, and the walk's minimum is the shortest linker, 1
    assert real["answer"] == "fits" and real["minimal_linker"]["linker"] == 1


def test_the_report_wrote_its_pictures_in_the_real_blender(reports):
    real, doc = reports["real"], reports["real_doc"]
    assert not [w for w in doc["warnings"] if "failed" in w], doc["warnings"]
    assert {"render", "envelope_plot", "bracket_plot"} <= set(doc["files"])
    for name in doc["files"].values():
        assert (real / name).is_file(), name
    page = (real / "report.html").read_text(encoding="utf-8")
    # the render, the envelope and the bracket's number line (matplotlib from the zip's wheel)
    assert page.count('src="data:image/png;base64,') == 3


def test_the_real_blenders_render_carries_legend_and_scale_bar(reports):
    from matplotlib.image import imread
    best = read_json(reports["real"] / "best_layout.json")
    legend = best["render"]["legend"]
    assert legend["drawn"] and legend["scale_bar_angstrom"] > 0, legend
    img = imread(reports["real"] / reports["real_doc"]["files"]["render"])[..., :3]
    h, w, _ = img.shape
    assert (h, w) == (270, 480)
    # the legend's box: near-white, in its corner's quarter of the picture (the background is
    # Blender's grey, the domains shaded: measured under 5 % of such pixels there without it)
    top = legend["legend_corner"].startswith("upper")
    left = legend["legend_corner"].endswith("left")
    quarter = img[:h // 2] if top else img[h // 2:]
    quarter = quarter[:, :w // 2] if left else quarter[:, w // 2:]
    light = (quarter > 0.9).all(axis=2).mean()
    assert light > 0.15, light
    # the scale bar: a row of dark pixels as long as scale_bar_angstrom at angstrom_per_pixel,
    # in the bottom third
    length = legend["scale_bar_angstrom"] / legend["angstrom_per_pixel"]
    dark = (img[2 * h // 3:] < 0.2).all(axis=2).sum(axis=1)
    assert dark.max() >= 0.9 * length, (dark.max(), length)


def test_the_page_renders_in_chromium_with_every_image(reports):
    """The page as a reader opens it: Chromium (headless, no network: every host resolves to
    nothing), a screenshot, and the page's own count of its images that loaded (a copy of the
    page with a two-line script that writes it into the title, read from --dump-dom)."""
    real = reports["real"]
    page = (real / "report.html").read_text(encoding="utf-8")
    probe = real / "report-probe.html"
    probe.write_text(page.replace("</body>", """<script>
window.addEventListener("load", () => { const im = [...document.images];
  document.title = "images " + im.filter(i => i.complete && i.naturalWidth > 0).length + "/" +
                   im.length; });</script></body>"""), encoding="utf-8")
    shot = OUT / "report-page.png"
    flags = ("--headless --no-sandbox --disable-gpu --hide-scrollbars "
             "--host-resolver-rules='MAP * ~NOTFOUND' --proxy-server=127.0.0.1:9 "
             "--virtual-time-budget=5000")
    cp = chroot(f"export HOME=/tmp/chromium-home && rm -f {inside(shot)} && "
                f"chromium {flags} --dump-dom file://{inside(probe)} && "
                f"chromium {flags} --window-size=1000,1900 --screenshot={inside(shot)} "
                f"file://{inside(real / 'report.html')}", timeout=300)
    assert cp.returncode == 0, cp.stderr[-2000:]
    assert "<title>images 3/3</title>" in cp.stdout, cp.stdout[:500]
    from matplotlib.image import imread
    img = imread(shot)[..., :3]
    assert img.shape[:2] == (1900, 1000)
    colours = len(np.unique((img[::4, ::4] * 255).astype(np.uint8).reshape(-1, 3), axis=0))
    assert colours > 200, colours  # text, tables and the two pictures, not a blank page
    # the shot stays in out/realblender/: the docs show the real command's page instead
    # (docs/report_6cu7.png, made by `make pictures` at the code's MODEL_VERSION)
