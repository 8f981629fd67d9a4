"""One list of classes to register, joined from every module that defines some."""
import bpy

from . import operators, panels, properties

CLASSES = (*properties.CLASSES, *operators.CLASSES, *panels.CLASSES)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    properties.attach()


def unregister():
    properties.detach()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
