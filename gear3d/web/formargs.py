"""A form -> the keywords the CLI would pass for the same flags.

The form's texts are read by the CLI's own flag types (their range checks included) into an
``argparse.Namespace`` of the CLI's own parser, and the CLI's own helpers turn it into
keywords (``family_params``, ``body_params``, ``pair_profiles``). So the page builds exactly
what ``gear3d profile`` / ``gear3d body`` / ``gear3d check pair`` build, defaults included
(the tolerance the CLI picks for a mesh output, say), and a download has the CLI's bytes.

A refused text raises ``GearError(name, value, allowed)`` with the CLI's own range.
"""
from __future__ import annotations

import argparse
import inspect

from ..errors import GearError
from .schema import cli_parsers, is_flag, number_kind

_TRUE, _FALSE = ("1", "true", "on", "yes"), ("0", "false", "off", "no")


def _shown(text: str):
    """The value as a GearError shows it: a number when the text is one, else the text."""
    from ..cliargs import plain_int, plain_number
    for cast in (plain_int, plain_number):
        v = cast(text)
        if v is not None:
            return v
    return text


def typed(action, name: str, text: str):
    """``text`` read as the CLI reads it for ``action`` (its type and choices), or GearError."""
    if is_flag(action):
        v = text.lower()
        if v in _TRUE or v in _FALSE:
            return v in _TRUE
        raise GearError(name, text, "true or false")
    if action.choices and text not in action.choices:
        raise GearError(name, text, "one of " + ", ".join(map(str, action.choices)))
    conv = action.type or str
    if conv in (int, float):               # plain ASCII numbers only (1_0 is not 10), as the CLI reads them
        from ..cliargs import plain_int, plain_number
        v = plain_int(text) if conv is int else plain_number(text)
        if v is None:
            raise GearError(name, _shown(text), "an integer" if conv is int else "a number")
        return v
    try:
        return conv(text)
    except argparse.ArgumentTypeError as e:
        msg = str(e)
        allowed = msg.split("is not allowed: ", 1)[1] if "is not allowed: " in msg else msg
        raise GearError(name, _shown(text), allowed) from None
    except (TypeError, ValueError):
        kind = number_kind(action)
        raise GearError(name, _shown(text), "an integer" if kind == "int" else "a number") from None


def namespace(section: str, family: str, *parts) -> argparse.Namespace:
    """The CLI's Namespace for ``section`` ("profile", "body", "pair") with the given
    ``(section_of_fields, {name: text})`` parts set (later parts win)."""
    parser, _ = cli_parsers()[section]
    ns = parser.parse_args([family])
    by_dest = {a.dest: a for a in parser._actions}
    for sec, texts in parts:
        for name, text in texts.items():
            act = (by_dest.get("b_" + name) or by_dest.get(name)) if sec == "body" else by_dest.get(name)
            if act is None:
                raise GearError(name, text, f"a parameter of the `gear3d {section}` command")
            setattr(ns, act.dest, typed(act, name, text))
    return ns


def family_params(ns, output=None, mesh: bool = False) -> dict:
    """The CLI's ``family_params`` (its tolerance default by output, where it has one)."""
    from ..commands.profile import family_params as fp
    if len(inspect.signature(fp).parameters) > 1:
        return fp(ns, output, mesh=mesh)
    return fp(ns)


def profile_kwargs(form: dict, output=None) -> tuple:
    """(``profile()`` keywords, the Namespace) of ``gear3d profile FAMILY ... [-o output]``."""
    ns = namespace("profile", form["family"], ("profile", form["profile"]))
    return family_params(ns, output), ns


def body_kwargs(form: dict, output=None) -> tuple:
    """(``profile()`` keywords, ``body()`` keywords, the Namespace) of ``gear3d body FAMILY ...
    [-o output]``; the profile's tolerance is the body's, as the user asked (see
    :func:`profile_tolerance` for the share the CLI builds it at)."""
    from ..commands.body import body_params
    ns = namespace("body", form["family"], ("profile", form["profile"]), ("body", form["body"]))
    kw = body_params(ns)
    if "width" not in kw:
        raise GearError("width", None, "a number > 0 mm (--width)")
    return family_params(ns, output, mesh=True), kw, ns


def profile_tolerance(body_tol: float, kind: str, offset: bool) -> float:
    """The tolerance (mm) the CLI builds a body's profile at: the core's planned share of the
    body tolerance (``gear3d.solids.body.profile_tolerance``)."""
    from ..solids.body import profile_tolerance as share
    return share(body_tol, kind, offset)


def pair_kwargs(form: dict) -> tuple:
    """(wheel-1 keywords, z2, internal, mate mode) of ``gear3d check pair FAMILY ...``."""
    from ..commands.check import pair_profiles
    ns = namespace("pair", form["family"], ("profile", form["profile"]), ("pair", form["pair"]))
    kw, z2, internal = pair_profiles(ns)
    return kw, z2, internal, ns.mate
