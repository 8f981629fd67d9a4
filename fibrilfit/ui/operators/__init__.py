"""The sidebar's operators: thin wrappers over the functions headless runs call."""
from . import (build, cases, check, domains, ensemble, export, minimal, outline, report,
               simulate, structures)

CLASSES = (*build.CLASSES, *outline.CLASSES, *simulate.CLASSES, *check.CLASSES, *export.CLASSES,
           *structures.CLASSES, *domains.CLASSES, *cases.CLASSES, *report.CLASSES,
           *minimal.CLASSES, *ensemble.CLASSES)
