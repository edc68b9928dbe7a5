"""ISO 10303-21 (STEP file) text for gear3d's own STEP writers: REAL and STRING literals,
numbered entities, and the AP214 frame (product, units mm, context) around the solids.

The faceted writer (:mod:`gear3d.export.step`) and the direct B-rep writer
(:mod:`gear3d.export.step_direct`) both write through these, so both files carry the same
header and product naming, and the same input gives the same bytes (fixed timestamp).

Example::

    >>> from gear3d.export.step_part21 import real, Writer
    >>> real(1.0), real(2.5e-07)
    ('1.0', '2.5E-07')
    >>> w = Writer(); w.add("CARTESIAN_POINT('',(0.,0.,0.))"), w.lines
    (1, ["#1=CARTESIAN_POINT('',(0.,0.,0.));"])
"""
from __future__ import annotations

from .. import __version__


def real(x: float) -> str:
    """A STEP REAL: the float's shortest round-trip repr, always with a decimal point and an
    upper-case exponent (so a reader gets back exactly the same float)."""
    s = repr(float(x))
    if "e" in s:
        mant, exp = s.split("e")
        if "." not in mant:
            mant += "."
        return mant + "E" + exp
    return s if "." in s else s + "."


def string(text: str) -> str:
    """A STEP STRING literal (quotes doubled)."""
    return "'" + str(text).replace("'", "''") + "'"


class Writer:
    """Numbered entity lines: ``add(text)`` appends ``#n=text;`` and returns n."""

    def __init__(self):
        self.lines = []
        self.n = 0

    def add(self, text: str) -> int:
        self.n += 1
        self.lines.append(f"#{self.n}={text};")
        return self.n


def framed_text(add_breps, product: str, description: str) -> str:
    """A whole AP214 file (mm): the product, units and context entities around the solids
    that ``add_breps(writer)`` appends (it returns their MANIFOLD_SOLID_BREP ids); fixed
    header timestamp."""
    w = Writer()
    ac = w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')")
    w.add(f"APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{ac})")
    pc = w.add(f"PRODUCT_CONTEXT('',#{ac},'mechanical')")
    pr = w.add(f"PRODUCT({string(product)},{string(product)},'',(#{pc}))")
    w.add(f"PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{pr}))")
    pf = w.add(f"PRODUCT_DEFINITION_FORMATION('','',#{pr})")
    dc = w.add(f"PRODUCT_DEFINITION_CONTEXT('part definition',#{ac},'design')")
    pd = w.add(f"PRODUCT_DEFINITION('design','',#{pf},#{dc})")
    ps = w.add(f"PRODUCT_DEFINITION_SHAPE('','',#{pd})")
    lu = w.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))")
    au = w.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))")
    su = w.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())")
    un = w.add(f"UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{lu},'distance_accuracy_value','confusion accuracy')")
    ctx = w.add(f"(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{un}))"
                f"GLOBAL_UNIT_ASSIGNED_CONTEXT((#{lu},#{au},#{su}))REPRESENTATION_CONTEXT('',''))")
    o = w.add("CARTESIAN_POINT('',(0.,0.,0.))")
    z = w.add("DIRECTION('',(0.,0.,1.))")
    x = w.add("DIRECTION('',(1.,0.,0.))")
    world = w.add(f"AXIS2_PLACEMENT_3D('',#{o},#{z},#{x})")
    breps = add_breps(w)
    rep = w.add(f"ADVANCED_BREP_SHAPE_REPRESENTATION({string(product)},(#{world}," +
                ",".join(f"#{b}" for b in breps) + f"),#{ctx})")
    w.add(f"SHAPE_DEFINITION_REPRESENTATION(#{ps},#{rep})")
    head = ["ISO-10303-21;", "HEADER;",
            f"FILE_DESCRIPTION(({string(description)}),'2;1');",
            f"FILE_NAME({string(product)},'1970-01-01T00:00:00',('gear3d'),('gear3d'),"
            f"'gear3d {__version__}','gear3d {__version__}','');",
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));", "ENDSEC;", "DATA;"]
    return "\n".join(head + w.lines + ["ENDSEC;", "END-ISO-10303-21;", ""])
