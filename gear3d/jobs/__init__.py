"""Scenes and part libraries: TOML templates -> stage graph -> files.

* :mod:`.template` -- load and validate scene / library TOML files (data only, no eval);
* :mod:`.specs` -- what they return: frozen ``Scene`` / ``Library`` of ``PartSpec``,
  ``PairSpec`` and ``AssemblySpec`` values;
* :mod:`.graph` -- the stage graph: profile@T -> body@T -> outputs, only what is needed,
  identical stages computed once;
* :mod:`.scene` -- :func:`build_scene` (parts, pairs, assemblies, outputs, scene report);
* :mod:`.batch` -- :func:`run_library` (sweeps, process pool or Dask, manifest, resume).
"""
from .template import TemplateError, load_library, load_scene  # noqa: F401

__all__ = ["TemplateError", "load_scene", "load_library", "build_scene", "run_library"]


def __getattr__(name):
    if name == "build_scene":
        from .scene import build_scene
        return build_scene
    if name == "run_library":
        from .batch import run_library
        return run_library
    raise AttributeError(f"module 'gear3d.jobs' has no attribute {name!r}")
