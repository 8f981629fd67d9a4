"""The command line: one parser (`parser`) and dispatcher (`commands`) for headless.py and
`blender -c fibrilfit` (`entry`). Importing it never imports bpy."""
from . import entry
from .commands import main
from .parser import build_parser

__all__ = ["build_parser", "entry", "main"]
