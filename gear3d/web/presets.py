"""Designs the web page offers as presets: the source papers' designs and an ordinary pair.

A preset fills the page's form: ``family``, then the profile's parameters by name, the body's
(``b.NAME`` in a query) and the pair's (``pair.NAME``), as the texts a person would type. A
field a preset leaves out keeps its default. The numbers are the papers' own:

* **Harmonic drive, seed 002 Table 2** (first engagement): the flexspline's outer teeth,
  m = 0.3 mm, z2 = 200, addendum h_a = 0.2625 mm (0.875 m), dedendum h_f = 0.3375 mm
  (1.125 m), tooth half-angle 28 deg 36' 31", tooth thickness on the pitch circle
  s_d = 0.4123 mm (0.4375 p); face width b2 = 12 mm; bore d = 58.125 mm (the flexible
  wall s = 0.6 mm under the root circle d_f2 = 59.325 mm). The 202-tooth rigid ring meshes
  with the deflected flexspline (w0 = 0.3 mm), which a rigid pair check does not model:
  ``gear3d harmonic`` builds the drive; the preset leaves the pair empty.
* **Chevron-arch EC pair, seed 003**: the paper states the geometry (tooth circles of radius
  rho on helices of radius epsilon, an arch of radius R joining the chevron's helices) but no
  numbers; the preset takes the project's template ``templates/chevron-ec-pair.toml``:
  epsilon = 1.5 mm, rho = 5 mm, a 2-tooth pinion with a 20-tooth wheel, face width 20 mm,
  helix 30 deg, the arch at its default radius. The wheel is a second preset (its own
  family), its twist the pinion's mate (opposite hand, same helix angle and arch radius,
  which ``gear3d.solids.body.mate_body`` builds).
* **Internal sine pair, seed 001 Fig. 15**: Z = 20 in Z' = 21, m = 1 mm, c_h = 0.5, the
  paper's choice for a teeth difference of one ("the interference disappears"). The page's
  ring switch makes the pair internal (wheel 1 the 20-tooth pinion, wheel 2 the ring), and
  the previewed gear the 20-tooth ring of that tooth form.
* **Involute 20/40**: module 1 mm, 20 deg, standard proportions, 10 mm wide with a 5 mm bore.

Example::

    >>> from gear3d.web.presets import preset, preset_query
    >>> preset("seed002-harmonic")["profile"]["teeth"]
    '200'
    >>> preset_query(preset("involute-20-40"))
    'family=involute&teeth=20&module=1&b.width=10&b.bore=5&pair.mate_teeth=40'
"""
from __future__ import annotations

from urllib.parse import urlencode

from ..errors import GearError

#: the presets, in the order the page lists them (texts as typed in the form)
PRESETS = (
    {"name": "involute-20-40", "label": "Involute 20/40 pair",
     "description": "an ordinary pair: 20 and 40 teeth, module 1 mm, 20 deg, 10 mm wide",
     "family": "involute",
     "profile": {"teeth": "20", "module": "1"},
     "body": {"width": "10", "bore": "5"},
     "pair": {"mate_teeth": "40"}},
    {"name": "seed002-harmonic", "label": "Harmonic drive flexspline (Table 2)",
     "description": "the double harmonic transmission's Table 2: the flexspline's 200 outer teeth, "
                    "m 0.3 mm, 12 mm wide, 0.6 mm wall; its 202-tooth ring meshes deflected (gear3d harmonic)",
     "family": "triangular",
     "profile": {"teeth": "200", "module": "0.3", "addendum_coeff": "0.875", "dedendum_coeff": "1.125",
                 "half_angle_deg": "28.608611", "thickness_coeff": "0.4375"},
     "body": {"width": "12", "bore": "58.125"},
     "pair": {}},
    {"name": "seed003-ec-pinion", "label": "Chevron-arch EC pinion",
     "description": "the chevron-arch transmitter's gearing: 2-tooth eccentric-cycloidal pinion "
                    "(tooth circle 5 mm at 1.5 mm) for a 20-tooth wheel, chevron-arch teeth, 20 mm wide, "
                    "helix 30 deg",
     "family": "ec-pinion",
     "profile": {"teeth": "2", "mate_teeth": "20", "eccentricity": "1.5", "tooth_radius": "5"},
     "body": {"kind": "chevron-arch", "width": "20", "helix_angle_deg": "30", "bore": "4"},
     "pair": {}},
    {"name": "seed003-ec-wheel", "label": "Chevron-arch EC wheel",
     "description": "the 20-tooth EC wheel of the pinion above (equidistant of the "
                    "epitrochoid), its chevron-arch twist the pinion's mate (left hand)",
     "family": "ec-wheel",
     "profile": {"teeth": "20", "mate_teeth": "2", "eccentricity": "1.5", "tooth_radius": "5"},
     "body": {"kind": "chevron-arch", "width": "20", "helix_angle_deg": "30", "hand": "left", "bore": "20"},
     "pair": {}},
    {"name": "seed001-internal-sine", "label": "Internal sine pair 20 in 21",
     "description": "the sine gear paper's Fig. 15: sine teeth Z = 20 in Z' = 21, m 1 mm, c_h = 0.5 "
                    "(no tip interference); Check pair rolls it",
     "family": "sine",
     "profile": {"teeth": "20", "module": "1", "addendum_coeff": "0.5", "internal": "true"},
     "body": {"width": "6", "rim_diameter": "30"},
     "pair": {"mate_teeth": "21"}},
)

_PREFIX = {"profile": "", "body": "b.", "pair": "pair."}


def preset(name: str) -> dict:
    """The preset called ``name`` (see :data:`PRESETS`), or ``GearError("preset", ...)``.

    Example: ``preset("involute-20-40")["pair"] == {"mate_teeth": "40"}``.
    """
    for p in PRESETS:
        if p["name"] == name:
            return p
    raise GearError("preset", name, "one of " + ", ".join(p["name"] for p in PRESETS))


def preset_items(p: dict) -> list:
    """``[(key, text), ...]`` of a preset as the page's query holds it (``family`` first,
    body keys as ``b.NAME``, pair keys as ``pair.NAME``).

    Example: ``preset_items(preset("involute-20-40"))[:2] == [("family", "involute"), ("teeth", "20")]``.
    """
    items = [("family", p["family"])]
    for sec in ("profile", "body", "pair"):
        items += [(_PREFIX[sec] + k, v) for k, v in p[sec].items()]
    return items


def preset_query(p: dict) -> str:
    """A preset as the query (or URL fragment) the page writes: ``family=...&teeth=...``."""
    return urlencode(preset_items(p))


def presets() -> list:
    """The presets as the page reads them: ``[{name, label, description, family, query}]``."""
    return [{"name": p["name"], "label": p["label"], "description": p["description"],
             "family": p["family"], "query": preset_query(p)} for p in PRESETS]
