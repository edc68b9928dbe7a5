"""Brute-force cutting simulation (seed 001's own method): blank minus many rack positions.

Deliberately independent of the envelope engine: it uses only the rack *outline* (dense
samples of its elements' points, no normals, no contact condition) and shapely/GEOS
polygon booleans (the engine trims with Clipper2). Slow; used as the oracle in tests and
as the baseline line in benchmarks.
"""
from __future__ import annotations

import math

import numpy as np

from .. import budget
from ..errors import GearError, check_bool, check_number
from ..racks import Corner, Rack

#: rack positions united at a time (bounds the memory of the union)
CHUNK = 250


def rack_outline(rack: Rack, periods: int, samples: int = 200) -> np.ndarray:
    """Rack boundary (u, v) mm over ``2*periods+1`` periods, from point samples only."""
    one = []
    for el in rack.elements:
        if isinstance(el, Corner):
            one.append(np.array([[el.u, el.v]]))
            continue
        t = np.linspace(0, 1, samples)
        u, v, _, _ = el.uv(t)
        one.append(np.stack([u, v], axis=1))
    one = np.concatenate(one)
    out = [one + [k * rack.pitch, 0.0] for k in range(-periods, periods + 1)]
    return np.concatenate(out)


def simulate_cut(rack: Rack, teeth: int, module: float, shift_coeff: float = 0.0,
                 internal: bool = False, positions: int = 2000, rolls: float | None = None,
                 samples: int = 200, window: float | None = None):
    """Gear region (shapely geometry, mm) left by a rack rolled on the pitch circle.

    Compare only the neighbourhood of tooth 0. A straight rack inside a ring cuts through the
    far teeth, so rings are cut by a local rack segment (``window``). A brute-force method,
    independent of the envelope engine: the tests and the benchmark check the engine with it.

    Parameters
    ----------
    rack : Rack
        The cutter (:func:`gear3d.racks.involute_rack` and the other basic racks), mm.
    teeth : int
        Teeth of the gear cut.
    module : float
        Module m, mm.
    shift_coeff : float, optional
        Profile shift x (the rack's datum sits x m out; default 0).
    internal : bool, optional
        Cut a ring gear (default False).
    positions : int, optional
        Rack positions (default 2000; fewer positions leave larger scallops).
    rolls : float, optional
        Travel, in pitches, each way (default: enough to finish tooth 0 and its neighbours).
    samples : int, optional
        Points per rack tooth outline (default 200).
    window : float, optional
        Pitches of rack kept around the pitch point (default: all; 0.75 for rings).

    Returns
    -------
    region : shapely.Polygon
        What is left of the blank, mm.
    blank_radius : float
        The blank's radius, mm.

    Raises
    ------
    GearError
        A parameter out of its range (one line: name, value, range), or a cut over the budget.

    Examples
    --------
    >>> import gear3d, math, shapely
    >>> from gear3d.racks import involute_rack
    >>> region, blank = gear3d.simulate_cut(involute_rack(1.0, 20.0), teeth=20, module=1.0,
    ...                                     positions=80, samples=60)
    >>> blank                                                        # r + 2 m: the uncut blank
    12.0
    >>> wedge = shapely.Polygon([(0, 0), (20, -3), (20, 3)])        # around tooth 0
    >>> xy = shapely.get_coordinates(region.intersection(wedge))
    >>> round(max(math.hypot(x, y) for x, y in xy), 2)              # the tip circle, r + m
    11.0
    """
    import shapely
    teeth, module, shift_coeff, internal, positions, samples, rolls, window = _checked(
        rack, teeth, module, shift_coeff, internal, positions, samples, rolls, window)
    budget.charge(budget.estimate("cut", float(positions) * samples * 4, 0.0,
                                  f"{positions:,} rack positions x {samples:,} outline points"), "positions", positions)
    r = module * teeth / 2
    xm = shift_coeff * module
    if rolls is None:
        rolls = _default_rolls(rack, teeth, r, xm, internal)
    per = int(math.ceil(rolls)) + 2
    uv = rack_outline(rack, per, samples)
    if window is None and internal:
        window = 0.75
    ds = np.linspace(-rolls * rack.pitch, rolls * rack.pitch, positions)
    cut = _swept(rack, uv, ds, r, xm, module, internal, window)
    if internal:
        outer = r - xm + rack.addendum + 2 * module
        blank = shapely.Point(0, 0).buffer(outer, quad_segs=2048)
    else:
        outer = r + xm + rack.dedendum + module
        blank = shapely.Point(0, 0).buffer(outer, quad_segs=2048)
    return blank.difference(cut), outer


def _checked(rack, teeth, module, shift_coeff, internal, positions, samples, rolls, window):
    """:func:`simulate_cut`'s arguments, checked (one line naming a bad one)."""
    if not isinstance(rack, Rack):
        raise GearError("rack", type(rack).__name__, "a basic rack (gear3d.racks.involute_rack(...) and others)")
    teeth = check_number("teeth", teeth, 1, 100_000, integer=True)
    module = check_number("module", module, 0, 1000, lo_open=True, unit="mm")
    shift_coeff = check_number("shift_coeff", shift_coeff, -3, 3, unit="x m")
    internal = check_bool("internal", internal)
    positions = check_number("positions", positions, 2, 200_000, integer=True)
    samples = check_number("samples", samples, 4, 100_000, integer=True)
    if rolls is not None:
        rolls = check_number("rolls", rolls, 0, 1000, lo_open=True, unit="pitches")
    if window is not None:
        window = check_number("window", window, 0, 1000, lo_open=True, unit="pitches")
    return teeth, module, shift_coeff, internal, positions, samples, rolls, window


def _default_rolls(rack, teeth, r, xm, internal):
    """Travel (pitches each way) that finishes tooth 0 and its neighbours."""
    # tooth 0 (angle within +-pi/z) is within the rack's reach only while
    # rho cos(theta) >= r + xm - h_tool for some rho <= blank radius: a geometric bound
    blank_r = r + xm + rack.dedendum if not internal else r - xm + rack.addendum
    inner = (r + xm - rack.addendum) if not internal else (r - xm - rack.dedendum)
    c = max(min(inner / blank_r, 1.0), -1.0) if not internal else 1.0
    theta = math.acos(c) + math.pi / teeth
    rolls = max(theta * r / rack.pitch, 1.0) + 0.25
    if internal:
        rolls = 1.6
    return rolls


def _swept(rack, uv, ds, r, xm, module, internal, window):
    """The union (shapely) of the rack outline ``uv`` placed at the travels ``ds`` (mm)."""
    import shapely
    sigma = -1.0 if internal else 1.0
    # rack body behind its root line; a ring's rack also covers the centre
    back = -(r + 2 * module) if internal else -(rack.dedendum + 3 * module)
    # the union is taken in chunks of rack positions: GEOS then never holds more than
    # one chunk's polygons (thousands of dense rack outlines at once took gigabytes)
    positions = len(ds)
    cut = None
    for c0 in range(0, positions, CHUNK):
        polys = []
        for d in ds[c0:c0 + CHUNK]:
            seg = uv if window is None else uv[np.abs(uv[:, 0] + d) <= window * rack.pitch]
            poly_uv = np.vstack([seg, [[seg[-1, 0], back], [seg[0, 0], back]]])
            X = r - sigma * (poly_uv[:, 1] - xm)
            Y = poly_uv[:, 0] + d
            phi = -d / r
            c, s = math.cos(phi), math.sin(phi)
            polys.append(shapely.Polygon(np.stack([c * X - s * Y, s * X + c * Y], axis=1)))
        part = shapely.union_all(shapely.make_valid(np.array(polys, dtype=object)))
        cut = part if cut is None else shapely.union(cut, part)
    return cut


def compare_tooth(region, loop: np.ndarray, pitch_angle: float, window: float = 0.45,
                  rmax: float | None = None):
    """Two-sided max distance (mm) between the brute-force boundary and ``loop`` near tooth 0.

    Only boundary points within ``window`` pitches of angle 0 (and inside ``rmax``) count.
    """
    import shapely
    from ..model import loops_distance
    bnd = shapely.get_coordinates(region.boundary)
    def sel(p):
        a = np.arctan2(p[:, 1], p[:, 0])
        m = np.abs(a) < window * pitch_angle
        if rmax is not None:
            m &= np.hypot(p[:, 0], p[:, 1]) < rmax
        return p[m]
    b = sel(bnd)
    l = sel(np.asarray(loop))
    # densify the engine loop's chords so both directions compare curves, not vertices
    d1 = loops_distance([loop], b).max()
    ring = shapely.LinearRing(bnd)
    d2 = shapely.distance(shapely.points(l), region.boundary).max()
    del ring
    return float(max(d1, d2))
