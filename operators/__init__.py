"""The sidebar's operators: thin wrappers over the functions headless runs call."""
from . import build, check, export, simulate, structures

CLASSES = (*build.CLASSES, *simulate.CLASSES, *check.CLASSES, *export.CLASSES,
           *structures.CLASSES)
