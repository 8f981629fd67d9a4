"""The sidebar's operators: thin wrappers over the functions headless runs call."""
from . import build, check, simulate

CLASSES = (*build.CLASSES, *simulate.CLASSES, *check.CLASSES)
