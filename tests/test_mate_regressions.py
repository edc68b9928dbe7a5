"""Mate builder regressions from the stability benchmark (issue #13): involute tools whose
mate disagreed with a 50x finer build by up to 0.46 mm.

Oracles: the 50x finer reference build (``Profile.reference_distance``), and for the tool
elements the tool's own tooth loop (every vertex must lie on the chain of elements, and
consecutive elements must join)."""
import numpy as np
import pytest

import gear3d
from gear3d.profiles.mate import mate, tool_elements

CASES = [  # tool teeth, module, mate teeth, tolerance (benchmarks/stability.py, seed 2026)
    (25, 1.456619572529181, 43, 0.015555482664568134),   # was 0.459 mm: a half tip piece lost
    (16, 0.920108804551887, 27, 0.027814474665360744),   # was 0.348 mm: the root switched mid-piece
]


@pytest.mark.parametrize("zt, m, z, tol", CASES)
def test_mate_agrees_with_finer_build(zt, m, z, tol):
    tool = gear3d.profile("involute", teeth=zt, module=m, tolerance=tol)
    p = mate(tool, z, tolerance=tol)
    assert p.report["max_error"] <= tol
    assert p.reference_distance(np.concatenate(p.loops)).max() <= tol


@pytest.mark.parametrize("zt, m, z, tol", CASES)
def test_tool_elements_cover_the_tooth_loop(zt, m, z, tol):
    tool = gear3d.profile("involute", teeth=zt, module=m, tolerance=tol)
    els = tool_elements(tool)
    t = np.linspace(0, 1, 2001)
    pts = [pn(t)[0] for pn, _ in els]
    for a, b in zip(pts[:-1], pts[1:]):           # consecutive elements join
        assert np.hypot(*(a[-1] - b[0])) <= 2 * tol
    chain = np.concatenate(pts)
    from scipy.spatial import cKDTree
    # one period of the tooth loop, tooth 0 (angles within half a pitch of +x)
    loop = tool.tooth_loop
    ang = np.arctan2(loop[:, 1], loop[:, 0])
    sel = np.abs(ang) < np.pi / zt * 0.999
    d, _ = cKDTree(chain).query(loop[sel])
    assert d.max() <= tol


def test_thin_swallowtail_is_not_kept_as_a_spike():
    """Stability benchmark, seed 2026: a 7-tooth involute whose swallowtail (flank past its
    singular point against the tip-corner trochoid) is thinner than the 29 µm chords. The
    fill kept it as a 0.1 mm spike that every chord measure passed; the builder now sees
    an outline vertex on the branch past the singular point and re-tessellates finer."""
    kw = dict(teeth=7, module=0.8967, pressure_angle_deg=20.46, shift_coeff=0.2338, tip_radius_coeff=0.2325)
    tol = 0.02915
    p = gear3d.profile("involute", tolerance=tol, **kw)
    assert p.report["max_error"] <= tol and p.report["undercut"]
    assert p.reference_distance(np.concatenate(p.loops)).max() <= tol


def test_gerotor_tip_not_cut_by_a_blank_from_sparse_samples():
    """Stability benchmark: a 4-lobe hypo gerotor's outer rotor has a long flat tip; its
    first tessellation had no sample near the tip's middle, the blank was turned at the
    extreme *sample* radius and cut the tip 0.065 mm too deep (the measured error could not
    see it: a blank cut counts as exact). The blank now starts from the exact extreme."""
    kw = dict(lobes=4, pin_circle_radius=63.12935539380795, pin_radius=8.41724738584106,
              eccentricity=3.6591028900495406, variant="hypo")
    tol = 0.004359540536442003
    p = gear3d.profile("gerotor-outer", tolerance=tol, **kw)
    fine = gear3d.profile("gerotor-outer", tolerance=tol / 20, **kw)
    assert abs(p.report["tip_radius"] - fine.report["tip_radius"]) <= tol
    assert fine.exact_distance(np.concatenate(p.loops)).max() <= tol
