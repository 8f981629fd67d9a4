"""The `fibrilfit` command of a pip-installed FibrilFit, and `python -m fibrilfit`.

The same command line as headless.py and `blender -c fibrilfit` (fibrilfit/cli/entry.py: the
parser, the dispatcher, one line and a non-zero exit for every failure), run by the Python that
pip installed into: `fibrilfit run ...`, `fibrilfit inspect ...` (docs/guide/install.md#pip).
"""
import sys

PROG = "fibrilfit"


def main() -> int:
    from .cli import entry
    return entry.main(sys.argv[1:], prog=PROG)


if __name__ == "__main__":
    sys.exit(main())
