"""Exit codes and the usage error, shared by every command (cli/, sweep/, search/, ...).

Plain Python with no package imports, so any command module can import it without importing
cli/commands.py (which imports the commands).
"""

EXIT_OK, EXIT_INTERSECTION, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130
EXIT_OUTPUT_FAILED = 3  # the run completed but a --pdb/--render output could not be written
EXIT_FAILED = 4  # an unexpected error (a bug or a broken Blender): one line on stderr


class UsageError(Exception):
    """Bad command-line input: printed as one line, exit code 2."""
