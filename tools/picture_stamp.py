"""Every picture under docs/ carries a stamp: PNG text chunks naming the MODEL_VERSION of the code
that made it, what made it, the commit and the date (tests/unit/test_pictures.py fails a picture
whose stamp is missing or older than the code's MODEL_VERSION). Pixels are not touched.

    python tools/picture_stamp.py PATH "what made it"      # stamp with this checkout's version
    python tools/picture_stamp.py --read PATH

Standard library and Pillow only (the unit tests read stamps with it).
"""
from __future__ import annotations

import datetime
import pathlib
import re
import subprocess
import sys

from PIL import Image, PngImagePlugin

ROOT = pathlib.Path(__file__).resolve().parents[1]
PREFIX = "fibrilfit:"
KEYS = ("model_version", "made_by", "commit", "date")


def model_version() -> int:
    text = (ROOT / "fibrilfit" / "model" / "version.py").read_text(encoding="utf-8")
    return int(re.search(r"^MODEL_VERSION = (\d+)", text, re.M).group(1))


def commit() -> str:
    return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                          text=True).stdout.strip() or "?"


def read(path: pathlib.Path) -> dict[str, str]:
    """The picture's stamp ({} when it has none)."""
    with Image.open(path) as im:
        text = dict(getattr(im, "text", {}) or {})
    return {k[len(PREFIX):]: v for k, v in text.items() if k.startswith(PREFIX)}


def stamp(path: pathlib.Path, made_by: str, version: int | None = None,
          made_at: str | None = None) -> dict[str, str]:
    """Write the stamp into the PNG's text chunks (its other chunks and pixels kept)."""
    path = pathlib.Path(path)
    with Image.open(path) as im:
        im.load()
        info = PngImagePlugin.PngInfo()
        for k, v in (getattr(im, "text", {}) or {}).items():
            if not k.startswith(PREFIX):
                info.add_text(k, v)
        values = {"model_version": str(model_version() if version is None else version),
                  "made_by": made_by, "commit": made_at or commit(),
                  "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")}
        for k in KEYS:
            info.add_text(PREFIX + k, values[k])
        extra = {k: im.info[k] for k in ("dpi",) if k in im.info}
        im.save(path, pnginfo=info, **extra)
    return values


if __name__ == "__main__":
    if sys.argv[1:2] == ["--read"]:
        for p in sys.argv[2:]:
            print(p, read(pathlib.Path(p)))
    elif len(sys.argv) == 3:
        print(stamp(pathlib.Path(sys.argv[1]), sys.argv[2]))
    else:
        sys.exit(__doc__)
