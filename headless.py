"""FibrilFit's command line from a source checkout.

    blender -b -P headless.py -- run [options]
    .venv/bin/python headless.py run [options]          (with the bpy module)

An installed extension has the same command line as `blender -b -c fibrilfit run [options]`.
Run `headless.py run --help` for the options. All logic is in the package (cli.py, entry.py).
Written so that any Blender's Python gets as far as the version check, which says in one line
what is needed (exit 2); every other failure also exits non-zero with one line (Blender itself
would exit 0 when a -P script raises).
"""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))


def _arguments():
    # Inside Blender, sys.argv holds Blender's own options; ours follow "--".
    if pathlib.Path(sys.argv[0]).name == pathlib.Path(__file__).name:
        return sys.argv[1:]
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def main():
    import blender_check
    blender_check.exit_if_too_old()
    try:
        import _load
        entry = _load.load().entry
    except KeyboardInterrupt:  # Ctrl-C while the package itself was still loading
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        return 130
    except Exception as exc:
        print("fibrilfit: error: could not load FibrilFit: {}: {}".format(
            type(exc).__name__, exc), file=sys.stderr)
        return 4  # exits.EXIT_FAILED
    return entry.main(_arguments(), prog="headless.py")


if __name__ == "__main__":
    sys.exit(main())
