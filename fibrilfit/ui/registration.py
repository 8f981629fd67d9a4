"""One list of classes to register, joined from every module that defines some, and the
command line `blender -c fibrilfit ...` (entry.command)."""
import bpy

from ..cli import entry
from . import domain_list, operators, panels, properties

CLASSES = (*domain_list.CLASSES, *properties.CLASSES, *operators.CLASSES, *panels.CLASSES)
_cli_commands = []  # handles from bpy.utils.register_cli_command, for unregister


def register():
    """Register every class, scene.fibrilfit and the command line. On an error, undo what was done and re-raise."""
    done = []
    try:
        for cls in CLASSES:
            bpy.utils.register_class(cls)
            done.append(cls)
        properties.attach()
        _cli_commands.append(bpy.utils.register_cli_command(entry.CLI_ID, entry.command))
    except BaseException:
        if hasattr(bpy.types.Scene, "fibrilfit"):
            properties.detach()
        for cls in reversed(done):
            bpy.utils.unregister_class(cls)
        raise


def unregister():
    while _cli_commands:
        bpy.utils.unregister_cli_command(_cli_commands.pop())
    properties.detach()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
