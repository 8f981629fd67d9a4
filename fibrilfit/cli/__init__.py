"""The command line: one parser (`parser`) and dispatcher (`commands`) for headless.py and
`blender -c fibrilfit` (`entry`, imported by name where it is needed: it calls down into this
package, never the other way). Importing it never imports bpy."""
from .commands import main
from .parser import build_parser

__all__ = ["build_parser", "main"]
