"""The one error of the structure reader: bad input, printed as one line (exit 2 on the CLI)."""


class StructureError(ValueError):
    """A structure file that cannot be measured. `option` names the input (e.g. '--fibril')."""

    def __init__(self, option: str, message: str):
        super().__init__(f"{option}: {message}")
        self.option = option
