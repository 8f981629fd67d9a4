"""The command line: one parser and dispatcher (`commands`) for headless.py and
`blender -c fibrilfit` (`entry`). Importing it never imports bpy."""
from .commands import build_parser, main

__all__ = ["build_parser", "main"]
