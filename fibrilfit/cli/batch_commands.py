"""`sweep` and `minimal-linker`: the commands whose work is in sweep/ and search/, handed the
options and the values measured from structure files."""
from __future__ import annotations

from ..structure.from_files import say_warnings
from .structure_files import params_and_structure
from .values import params_from


def command_sweep(args) -> int:
    """The grid's values over the structure files' (sweep/command.py reads args.structure_values)."""
    from ..sweep import command, grid
    args.structure_values = params_and_structure(args, grid.specs_from(args))
    return command.run_sweep(args)


def command_minimal_linker(args) -> int:
    from ..search import command
    explicit = params_from(args)
    values, block = params_and_structure(args, explicit)
    say_warnings(block)
    if "linker" not in explicit:  # a fibril file's tail length: the very thing the map searches
        values.pop("linker", None)
    return command.run_minimal(args, values)
