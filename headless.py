"""FibrilFit's command line.

    blender -b --python-exit-code 1 -P headless.py -- run [options]
    .venv/bin/python headless.py run [options]          (with the bpy module)

Run `headless.py run --help` for the options. All logic is in the package (cli.py).
"""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import _load  # noqa: E402


def _arguments() -> list[str]:
    # Inside Blender, sys.argv holds Blender's own options; ours follow "--".
    if pathlib.Path(sys.argv[0]).name == pathlib.Path(__file__).name:
        return sys.argv[1:]
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


if __name__ == "__main__":
    try:
        sys.exit(_load.load().cli.main(_arguments()))
    except KeyboardInterrupt:  # Ctrl-C while the package itself was still loading
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        sys.exit(130)
