"""The sidebar's panels."""
from .sidebar import CLASSES

__all__ = ["CLASSES"]
