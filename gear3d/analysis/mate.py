"""Moved to :mod:`gear3d.profiles.mate` (a profile builder, next to the families).

Kept only while ``gear3d/commands/check.py`` still imports it from here; delete this
file once that import reads ``from ..profiles.mate import mate``.
"""
from ..profiles.mate import mate, tool_elements

__all__ = ["mate", "tool_elements"]
