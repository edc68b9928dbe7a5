"""One parameter table per family: every parameter declared once.

A :class:`Param` states a parameter's name, type, unit, range, default, help and the
parameters it excludes. The tables drive

* the builders' validation (``FAMILY_PARAMS[family]`` through :meth:`Param.check`; a
  builder adds only the limits that depend on other parameters, e.g. a tip radius outside
  the root circle),
* the CLI flags of ``gear3d profile|body|check pair`` (:mod:`gear3d.commands.profile`;
  ``gear3d profile FAMILY --help`` shows that family's flags with their units, defaults
  and ranges),
* the TOML schema of templates (:mod:`gear3d.jobs.template`),
* the web form of ``gear3d serve`` (:mod:`gear3d.web.schema`),
* the reference pages ``docs/parameters.md`` and ``docs/templates.md``
  (``python -m gear3d.docsgen --markdown > docs/parameters.md``,
  ``python -m gear3d.docsgen --templates > docs/templates.md``; :mod:`gear3d.docsgen`).

Names: a TOML key (and a Python keyword) is the parameter's name; its CLI flag is the same
name with ``-`` for ``_`` (``helix_angle_deg`` <-> ``--helix-angle-deg``). Older flag
spellings (``--helix-angle``, ``--pressure-angle``, ...) stay as aliases and print a
one-line deprecation note on stderr.

Sizes are transverse by default (``module``, ``pressure_angle_deg``); ``normal_module``,
``normal_pressure_angle_deg`` (helical gears, BOSL2's convention) and ``diametral_pitch``
(1/inch) are alternatives (:mod:`gear3d.conventions`), excluded against each other here.

One module a topic: :mod:`~gear3d.params.param` (the :class:`Param` type),
:mod:`~gear3d.params.tolerance` (the tolerance facts), :mod:`~gear3d.params.families` (the
family tables), :mod:`~gear3d.params.bodies` (body and pair), :mod:`~gear3d.params.sets` (worm
and bevel sets), :mod:`~gear3d.params.exporters` (the exporters' options),
:mod:`~gear3d.params.reference` (the reference page). Every name is
importable from ``gear3d.params``.

This package imports nothing heavy (no numpy): the CLI builds its parser from it.
"""
from __future__ import annotations

from .param import Param, declare, union
from .tolerance import (DEFAULT_TOLERANCE, MAX_TOLERANCE_SHARE, MAX_TOLERANCE_TEXT, MESH_TOLERANCE,
                        MIN_TOLERANCE, max_tolerance)
from .families import (ADD, CONV_HELIX, CONVENTION_FAMILIES, CONVENTIONS, DED, DIAMETRAL_PITCH,
                       FAMILY_PARAMS, INTERNAL, MODULE, NORMAL_MODULE, NORMAL_PRESSURE, NOT_TABULATED,
                       PRESSURE, RIM, TEETH, TIP, TOLERANCE, all_params, by_name, check_excludes,
                       check_family, family_table)
from .bodies import BODY, BODY_KINDS, BODY_PARAMS, PAIR, PAIR_PARAMS, check_body
from .sets import (BEVEL_FORMS, BEVEL_PARAMS, CROSSED_PARAMS, FACE_GEAR_PARAMS, PLANETARY, PLANETARY_FAMILIES,
                   PLANETARY_PARAMS, SPACINGS, WORM_PARAMS)
from .exporters import DXF_PARAMS, EXPORT_PARAMS, STEP_PARAMS, SVG_PARAMS, THREEMF_PARAMS
from .reference import markdown, md_rows

__all__ = ["Param", "declare", "union", "DEFAULT_TOLERANCE", "MAX_TOLERANCE_SHARE", "MAX_TOLERANCE_TEXT",
           "MESH_TOLERANCE", "MIN_TOLERANCE", "max_tolerance", "ADD", "CONV_HELIX", "CONVENTION_FAMILIES",
           "CONVENTIONS", "DED", "DIAMETRAL_PITCH", "FAMILY_PARAMS", "INTERNAL", "MODULE", "NORMAL_MODULE",
           "NORMAL_PRESSURE", "NOT_TABULATED", "PRESSURE", "RIM", "TEETH", "TIP", "TOLERANCE", "all_params",
           "by_name", "check_excludes", "check_family", "family_table", "BODY", "BODY_KINDS", "BODY_PARAMS",
           "PAIR", "PAIR_PARAMS", "check_body", "BEVEL_FORMS", "BEVEL_PARAMS", "CROSSED_PARAMS", "FACE_GEAR_PARAMS", "PLANETARY", "PLANETARY_FAMILIES", "PLANETARY_PARAMS",
           "SPACINGS", "WORM_PARAMS", "DXF_PARAMS", "EXPORT_PARAMS", "STEP_PARAMS",
           "SVG_PARAMS", "THREEMF_PARAMS", "markdown", "md_rows"]
