"""One list of classes to register, joined from every module that defines some."""
import bpy

from . import operators, panels, properties

CLASSES = (*properties.CLASSES, *operators.CLASSES, *panels.CLASSES)


def register():
    """Register every class, then scene.fibrilfit. On an error, undo what was done and re-raise."""
    done = []
    try:
        for cls in CLASSES:
            bpy.utils.register_class(cls)
            done.append(cls)
        properties.attach()
    except BaseException:
        for cls in reversed(done):
            bpy.utils.unregister_class(cls)
        raise


def unregister():
    properties.detach()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
