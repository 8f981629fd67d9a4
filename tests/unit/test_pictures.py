"""Pictures that cannot go stale: every PNG under docs/ carries a stamp (tools/picture_stamp.py:
the MODEL_VERSION of the code that made it, what made it, the commit, the date). A picture a user
page shows must be of the code's own MODEL_VERSION (`make pictures` makes the model's pictures
again; `make test-blender ACCEPT_SCREENS=1` the real Blender's screens); a picture only a dated
notebook page shows is a record of its day and keeps the version it was made at, which its
stamp names. Every picture is shown by some page, and every picture `make pictures` makes is one
the docs show."""
import importlib.util
import json
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


picture_stamp = load("picture_stamp")
IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+\.png)")
PNGS = sorted(DOCS.rglob("*.png"))


def pages_showing() -> dict[pathlib.Path, set[str]]:
    """Each picture under docs/ -> the pages (docs-relative; README.md) that show it."""
    shown: dict[pathlib.Path, set[str]] = {}
    pages = [(p, p.parent) for p in DOCS.rglob("*.md")] + [(ROOT / "README.md", ROOT)]
    for page, base in pages:
        for target in IMAGE.findall(page.read_text(encoding="utf-8")):
            path = (base / target).resolve()
            name = "README.md" if page.name == "README.md" and base == ROOT else \
                page.relative_to(DOCS).as_posix()
            shown.setdefault(path, set()).add(name)
    return shown


SHOWN = pages_showing()


def notebook_only(png: pathlib.Path) -> bool:
    pages = SHOWN.get(png.resolve(), set())
    return bool(pages) and all(p.startswith("notebook/") for p in pages)


@pytest.mark.parametrize("png", PNGS, ids=[p.relative_to(DOCS).as_posix() for p in PNGS])
def test_a_picture_is_of_the_codes_model_version(png):
    stamp = picture_stamp.read(png)
    name = png.relative_to(DOCS).as_posix()
    assert stamp.get("model_version", "").isdigit(), (
        f"docs/{name} has no MODEL_VERSION stamp: make it with `make pictures` (or stamp it with "
        "tools/picture_stamp.py once it is made by the current code)")
    assert stamp.get("made_by"), name
    assert png.resolve() in SHOWN, f"docs/{name} is shown by no page: remove it"
    if notebook_only(png):
        return  # a dated record: it keeps the version it was made at, which its stamp says
    current = picture_stamp.model_version()
    assert int(stamp["model_version"]) == current, (
        f"docs/{name} was made at MODEL_VERSION {stamp['model_version']}, the code is at "
        f"{current}: `make pictures` (or `make test-blender ACCEPT_SCREENS=1` for the screens)")


RUNS = sorted((DOCS / "data" / "pictures").glob("*.json"))


@pytest.mark.parametrize("path", RUNS, ids=[p.name for p in RUNS])
def test_a_pictures_run_is_of_the_codes_model_version(path):
    """docs/data/pictures/: the runs behind the model's plots (written by `make pictures` beside
    the pictures), which captions point at: of the code's MODEL_VERSION, as the pictures are."""
    run = json.loads(path.read_text(encoding="utf-8"))
    assert run.get("commit") and run.get("date"), path.name
    assert int(run["model_version"]) == picture_stamp.model_version(), (
        f"docs/data/pictures/{path.name} is of MODEL_VERSION {run['model_version']}: "
        "`make pictures` makes it again with its picture")


def test_make_pictures_makes_only_pictures_the_docs_show():
    pictures = load("pictures")
    for name in pictures.PICTURES:
        assert (DOCS / name).resolve() in SHOWN, name
    assert "pictures:" in (ROOT / "Makefile").read_text(encoding="utf-8")


def test_the_stamp_is_read_back_and_an_old_one_fails(tmp_path):
    from PIL import Image
    png = tmp_path / "x.png"
    Image.new("RGB", (4, 4), "white").save(png)
    assert picture_stamp.read(png) == {}
    picture_stamp.stamp(png, "a test", version=picture_stamp.model_version() - 1, made_at="abc1234")
    stamp = picture_stamp.read(png)
    assert stamp["made_by"] == "a test" and stamp["commit"] == "abc1234"
    assert int(stamp["model_version"]) < picture_stamp.model_version()
    with Image.open(png) as im:
        assert im.getpixel((0, 0)) == (255, 255, 255)  # pixels untouched
