"""Per-item costs of the resource budget (:mod:`gear3d.budget`): CPU seconds and peak bytes
a counted item (a profile vertex, a triangle, a rolling position x vertex, a B-rep face...),
plus once-only costs, each with where its numbers come from.

Every estimate is counts x these costs (:func:`gear3d.budget.estimate`); a cost is the
largest of several sizes and families measured, rounded up, so that an estimate is an upper
bound within about 2x (the fuzz property of ``tests/fuzz`` holds every command to that).

>>> COSTS["write.stl"].seconds < COSTS["write.3mf"].seconds
True
"""
from __future__ import annotations

from .records import dataclass


@dataclass(frozen=True)
class Cost:
    """Per-item costs of one stage: CPU seconds and peak bytes per item, plus once-only
    costs (imports, the interpreter's share), with where the numbers come from."""
    seconds: float
    bytes: float
    fixed_seconds: float = 0.0
    fixed_bytes: float = 0.0
    source: str = ""


#: per-item costs, measured once on the reference machine (2 cores, Python 3.11, numpy 2.4,
#: manifold3d 3.5.4, shapely 2.1; each source says what was measured and when):
#: the largest of several sizes and families, rounded up, so an estimate is an upper bound
#: within about 2x
COSTS = {
    # gear3d.model.build_profile after sampling: pattern, trim (Clipper), corners, measure
    "profile": Cost(12e-6, 900.0, 0.05, 40e6, "involute z=3000 (66,000 vertices) 0.31 s, +22 MB; "
                    "triangular z=20,000 (100,000 vertices) 0.21 s, +24 MB; cycloidal 0.38 s"),
    # gear3d.buildsteps.trim_and_refine: a trimmed corner's visit (its exact crossing, its chords'
    # refinement) and, per visit, each sample of the period searched for chords near it (x3 copies)
    "profile.corners": Cost(1.5e-4, 0.0, 0.0, 0.0, "triangular z=7, 80 deg, m 3, 1e-3 (2026-11-26): 8,927 "
                            "visits of up to 3,910 samples, 3.2 s; chords_near 2.2e-8 s a sample, Newton 0.3 ms"),
    "profile.corners.near": Cost(1.5e-8, 0.0, 0.0, 0.0, "the same run: chords_near over 3 x 3,910 chords"),
    # one more pass of trim_and_refine over the whole profile (pattern, Clipper trim, new vertices)
    "profile.pass": Cost(3e-6, 0.0, 0.0, 0.0, "involute z=3000 at 0.1 um (2026-11-26): two passes over "
                         "204,000 vertices, 0.47 s: 1.2 us a vertex, x2.5"),
    # gear3d.buildsteps.sector_distance: per (point, edge) pair near tooth 0, numpy in chunks
    "profile.pairs": Cost(1e-8, 0.0, 0.0, 0.0, "moineau-stator rho=1e5, e=1: 27,800 x 55,600 pairs, 5.4 s"),
    # solids.body: the layer mesh (float64 V, int64 F, intermediates) and its measurement
    "body": Cost(1.2e-6, 260.0, 0.1, 60e6, "helical z=20..400 at 2-10 um: 0.6-0.9 us and 180-240 B "
                 "a triangle"),
    # manifold3d's polygon triangulation of the end faces (gear3d.solids.layers.end_triangles'
    # fallback: sections not star-shaped about the axis, manifold3d's extrusions): per (layer vertices)^2
    "body.caps": Cost(4e-9, 0.0, 0.0, 0.0, "triangular z=2500..10,000 (12,500-60,000 vertices a layer): "
                      "2.0-2.2e-9 s x n^2, z=20,000 (100,000): about 4e-9; involute z=1000-2000: 0.8-0.9e-9; "
                      "re-measured 2026-11-26: triangular z=2500 / 10,000 1.97 / 1.61e-9, involute z=8 / 12 "
                      "(undercut, 1,792 / 7,128 vertices) 0.93 / 0.38e-9, z=1000 0.14e-9, cycloidal z=1000 0.20e-9"),
    # gear3d.solids.caps.cap_triangles: a fan or a zipper strip, per layer vertex (linear)
    "body.caps.star": Cost(1e-6, 0.0, 0.0, 0.0, "measured 2026-11-26 (CPU, best of 3): fans of involute z=300 / "
                           "1000 at 0.1 um, triangular z=2500 / 10,000, cycloidal z=1000: 0.03-0.16 us a vertex; "
                           "zippers to a bore (involute z=1000, triangular z=10,000, cycloidal z=1000; 55,000-75,000 "
                           "vertices) and a ring z=200's rim: 0.22-0.36 us; x3 for the strip's repair passes"),
    # gear3d.exact distance: per (point, chord) pair of the brute-force window
    "measure": Cost(2e-8, 50.0, 0.0, 0.0, "moineau-stator rho=288, e=0.1 at 0.3 um: 76,000 points x 5,452 "
                    "chords in 6.2 s (15 ns a pair); involute z=6 at 10 um: 7.4 s in all; bytes: a pair of a "
                    "chunk of at most MEASURE_CHUNK (gear3d.exact.distance's 4 M): moineau-rotor z=1 at 2 um "
                    "(89 M pairs) peaked at 258 MB with 60 MB before the body (fuzz survey, 2026-11-26)"),
    # manifold3d booleans (hubs, keyways, chamfers): extrude + warp + boolean + to_mesh64
    "body.manifold": Cost(4e-6, 600.0, 0.1, 60e6, "chamfered helical z=40..200: 2.5-3.5 us, "
                          "450-550 B a triangle"),
    # exporters, per profile vertex (2D) or per triangle (3D)
    "write.json": Cost(4e-6, 400.0, 0.05, 0.0, "triangular z=4000, 20,000 vertices: 0.25 s"),
    "write.dxf": Cost(1.2e-5, 600.0, 0.05, 30e6, "measured 2026-11-26 (CPU, after the profile; arcs certified on "
                      "the exact curve): involute z=20..2000, triangular z=4000 / 20,000, cycloidal z=200 and z=1000 "
                      "rc 100, sine, cycloid disc, gerotor, Moineau: 2.4-9.8 us a vertex + 10 ms; 100,000 vertices: "
                      "0.56 s, +41 MB"),
    "write.svg": Cost(1.2e-5, 900.0, 0.05, 30e6, "measured 2026-11-26, the same 13 parts: 3.6-9.8 us a vertex; "
                      "triangular z=20,000: 0.76 s; z=100,000 (500,000 vertices): 4.9 s, 533 MB peak in all"),
    # a rack's DXF/SVG on top of write.dxf / write.svg: its whole outline is one chain (no tooth period to
    # repeat), walked and checked whole, per outline vertex
    "write.rack": Cost(3.5e-5, 2000.0, 0.0, 0.0, "measured 2026-11-26 (CPU, write_rack alone, after the "
                       "outline's start search was vectorised and segments_distance windowed): involute z=2000 / "
                       "10,000 43 / 38 us, sine z=3000 27 us, cycloidal z=2000 35 us, triangular z=10,000 37 us a "
                       "vertex, less the 12 us of write.dxf; 233 MB peak at 80,000 vertices"),
    # the sampled fallback (a reference 20x finer, shapely, up to 3 budgets): per profile vertex
    "write.dxf.sampled": Cost(1.5e-3, 4000.0, 0.1, 250e6, "measured 2026-11-26, forced: involute z=20 / 200 0.37 / "
                              "0.32 ms, triangular z=4000 0.11 ms, sine z=300 0.32 ms, cycloidal z=1000 rc 100 "
                              "1.4 ms a vertex (3 tries, 43 s); taken unforced by gears of 5 teeth or fewer (sine "
                              "z=4 at 0.1 um: 1.7-2.0 s, 238 MB peak with shapely)"),
    # --max-arc-deg below its default: per arc of at most that turning (plan.dxf_arcs)
    "write.dxf.arcs": Cost(3e-6, 450.0, 0.0, 0.0, "measured 2026-11-26 (CPU, peak RSS): involute z = 5000 / "
                           "20,000 at 1 um with --max-arc-deg 1: 1.16 / 4.64 M arcs, +2.0 / +11.4 s and 463 MB "
                           "/ 1.5 GB peak over the default's 60,000 / 240,000 (1.7-2.5 us, 320-400 B an arc)"),
    "write.png": Cost(5e-5, 3000.0, 1.0, 70e6, "profile figure, triangular z=4000 (20,000 vertices): 0.8 s "
                      "with matplotlib's import; body preview, 10,000-56,000 triangles: 0.65-0.82 s, +47-68 MB"),
    "write.stl": Cost(1.0e-6, 130.0, 0.05, 0.0, "binary STL, helical z=40..1000 (10,000-56,000 triangles): "
                      "0.4-0.8 us and about 100-130 B a triangle"),
    "write.mesh": Cost(1.0e-5, 500.0, 0.1, 10e6, "meshio OBJ/PLY/VTU, 10,000-56,000 triangles: 5-10 us a triangle"),
    "write.3mf": Cost(1.0e-5, 2000.0, 0.8, 100e6, "measured 2026-11-26 (CPU, the linear writer), helical z=40..400, "
                      "9,000-264,000 triangles: 7.9-8.1 us a triangle warm; cold 0.76 / 1.66 / 2.80 s for 14k / "
                      "125k / 264k (+0.65 s trimesh's import and first call), +103 / 252 / 440 MB"),
    "write.step": Cost(8.0e-5, 3000.0, 0.4, 60e6, "faceted STEP, 10,000-56,000 triangles: 1.0-3.3 s "
                       "(60-95 us a triangle), +65-158 MB"),
    # a B-rep STEP (gear3d.plan.brep_estimate): per surface sample measured, plus per face
    "write.brep": Cost(2.5e-4, 20000.0, 1.2, 350e6, "measured 2026-11-26 in process (CPU): spur z=400 at "
                       "0.1 / 0.001 mm, 800 faces, 4,000 / 16,000 samples: 2.9 / 6.1 s, so 2.7e-4 s a sample; "
                       "+1.2 s OpenCascade's import and first call; +296-336 MB (helical z=40, 200); a small worm "
                       "wheel's B-rep peaked at 343 MB in all (the fuzz survey: stopped under 300 MiB, 294 planned)"),
    "brep.face": Cost(1.5e-3, 50000.0, 0.0, 0.0, "measured 2026-11-26 (CPU): spur z=700 / 1000 / 1500 at 0.1 mm, "
                      "1,400 / 2,000 / 3,000 flank faces: 4.2 / 6.0 / 11.5 s (3.0-3.8 ms a face, counted 4 a tooth)"),
    # conjugate contact (gear3d.analysis.contact): per wheel-1 angle of its grid (96 a pitch)
    "contact": Cost(3e-3, 2000.0, 0.3, 20e6, "measured 2026-11-26 (CPU): involute 20/20..2000/2000 and sine "
                    "at 1e-4..0.05 mm, 234-3,301 angles: 0.3-3.3 ms an angle; bands over 0.4 pitch up to 15 ms "
                    "(involute 100/100 and 150/150 at 0.05 mm: 10.8 s for 741 and 901 angles: CONTACT_WIDE_BAND)"),
    # gear3d inspect's measurements (span over jaw directions x flank points, neck): per (vertices a tooth)^2
    "inspect": Cost(1.5e-7, 24.0, 0.05, 20e6, "measured 2026-11-26 (CPU, analysis.inspection.inspect alone): "
                    "sine z=7 / 20 at 0.1 um (2,814 / 7,410 a tooth) 1.35 / 5.46 s, involute z=20 at 0.1 um 2.17 s, "
                    "z=200 at 1 um 0.18 s, cycloidal z=30 at 0.1 um 1.38 s: 29-195 ns a (vertex a tooth)^2"),
    # a harmonic drive's plain prisms (tubes, flanges, discs: circles at the tolerance), extruded and joined
    # (manifold3d, lazily: the booleans run when the part is measured); per triangle, caps linear for circles
    "harmonic.part": Cost(1.5e-5, 600.0, 0.0, 0.0, "measured 2026-11-26 (CPU, in process): single drive m 1, "
                          "31/33 triangular at 1 um, 190,000 triangles of circles: 2.8 s in _prism and the "
                          "parts' booleans (about 15 us a triangle); the fuzz survey found 4.6 s planned at 3.8 s"),
    # pinion on rack (analysis.rack_mesh): per roll state, and per (pinion vertex x rack chord) pair of a state
    "pair.rack": Cost(2e-3, 0.0, 0.0, 60e6, "measured 2026-11-26 (CPU): involute 20 / 100 teeth, cycloidal 30, "
                      "sine 200 at 0.1-1 um: 0.2-1.1 ms a state beside its pairs"),
    "pair.rack.pairs": Cost(3.5e-8, 0.0, 0.0, 100e6, "measured 2026-11-26 (CPU): sine z=45 m=50 at 1 / 0.3 um: "
                            "370 M / 1.48 G pairs, 9.2 / 28.2 s (19-25 ns a pair); 1 M pairs a chunk"),
    # gear3d.rack's measured error: per (chord point x chord) pair of one period (rack_part._chord_error)
    "rack.chords": Cost(2e-8, 0.0, 0.0, 100e6, "measured 2026-11-26 (CPU): sine z=45 m=50 at 10 nm 195 M pairs "
                        "3.3 s, cycloidal z=30 m=50 at 1 nm 1.16 G pairs 15.8 s (14-17 ns a pair)"),
    # rolling check: per (position x vertex of both polygons), shapely
    "pair": Cost(1.2e-5, 300.0, 0.3, 30e6, "check_pair, 78 positions: involute 20/21 to 1000/1000 at "
                 "1-10 um 4.6-11 us, sine 200/210 internal 10 us a (position x vertex)"),
    # gerotor chamber areas: per (crank position x polygon vertex), shapely buffer/difference
    "chambers": Cost(2.5e-7, 400.0, 0.0, 0.0, "gerotor 30 lobes R=300: 3.9 s for 62 positions x 366,000 "
                     "polygon vertices (1.7e-7 s an item), +113 MB (300 B a polygon vertex)"),
    # gear3d.simulate_cut: per (rack position x outline point), shapely unions in chunks
    "cut": Cost(6e-6, 200.0, 0.3, 30e6, "involute z=20, 2000 positions x 200 samples x 4: 7.8 s (4.9 us)"),
    # figures (matplotlib), per profile vertex drawn
    "figure": Cost(5e-5, 3000.0, 1.2, 60e6, "annotated involute figure, 20,000 vertices: 1.1 s"),
    # a library part's stages beyond their per-item costs, imports paid (gear3d.jobs.batch.build_part)
    "library.part": Cost(0.015, 0.0, 0.0, 0.0, "measured 2026-11-26 (CPU, in a warm process): involute spurs "
                         "z = 10..39, m 0.5-2.4, width 4, STL at 10 um: 20-32 ms a part (profile 9-15 ms, body "
                         "9-15 ms, STL 2 ms) against 9-44 ms of per-item estimates; 600 such parts: 13.9 s of "
                         "worker CPU, planned 9.9 s without this, 18.9 s with it"),
    # the harmonic deformed-state check (gear3d.harmonic.deform.mesh_check): per (position x flex
    # tooth x (tooth region vertices + 10) x rigid wheel vertex), shapely intersects/intersection/distance
    "harmonic.check": Cost(4e-9, 0.0, 0.3, 60e6, "measured 2026-11-26 in process (CPU): single drives m 0.3, "
                           "z_f = 200 / 1000 triangular at 0.1 um, 200 at 0.01 um, 200 involute at 0.1 um: "
                           "72-81 ns a (tooth x rigid vertex) for 12-17 region vertices, 202 ns for 58 "
                           "(3.1-3.5 ns an item)"),
    # the set commands (gear3d.plan_sets), measured 2026-11-26 in a subprocess (CPU, ru_maxrss)
    "worm.body": Cost(1.6e-6, 280.0, 0.4, 150e6, "measured 2026-11-26 (CPU, peak RSS): worm pairs m 2, z2 = "
                      "30 / 100 / 300 at 10 / 2 / 0.5 um, 0.2-10.7 M triangles: 1.26-1.45 us and 240-250 B a "
                      "triangle (z2 = 300 at 0.5 um: 13.5 s, 2.55 GB); per estimated triangle "
                      "(plan_sets.worm_counts); small sets peak at 90-140 MB"),
    "worm.sections": Cost(5e-4, 0.0, 0.0, 0.0, "measured 2026-11-26 (CPU): worm wheels z2 = 8 / 12 / 16 at m 2, "
                          "10 um, built section by section: 6.3 / 3.4 / 2.6 s for 117 / 80 / 71 sections of 114 "
                          "vertices a tooth (3.2-4.7e-4 s per section x vertex a tooth)"),
    "worm.rolling": Cost(5e-4, 1e5, 0.4, 60e6, "measured 2026-11-26 (CPU, with and without --check): z2 = 30 "
                         "pair at 10 um 0.21 s, z2 = 300 wheel at 50 um 0.26 s (24 positions x 81 sections)"),
    "worm.rolling.zk": Cost(1.5e-3, 0.0, 1.2, 0.0, "measured 2026-11-26 (CPU, --check with ZK against ZA): "
                            "z2 = 8 m 0.05 wheel +1.28 s, z2 = 30 m 2 pair +1.21 s (found by the fuzz survey: "
                            "3.2 s for 1.3 s planned under load)"),
    "bevel.body": Cost(1.3e-7, 1000.0, 0.4, 60e6, "measured 2026-11-26 (CPU): straight bevels 20/30, 100/100, "
                       "200/200 at 10-0.1 um: per (section vertex x cap segment) 1.25e-7 s split in layers "
                       "(200/200 at 0.1 um: 12,800 x 9,970 in 16 s), 2.2e-7 unsplit (counted twice); "
                       "400-735 B per estimated triangle (+40 MB)"),
    "bevel.spiral": Cost(1.2e-5, 1500.0, 0.4, 60e6, "measured 2026-11-26 (CPU, peak RSS): spiral bevel 20/40 m 2, "
                         "35 deg, gear at 10 / 3 um, 136k / 399k triangles: 1.2 / 4.6 s (1.05e-5 s a triangle), "
                         "131 / 318 MB; per planned triangle (layers x warped vertices, plan_sets)"),
    "bevel.spiral.internal": Cost(2.0e-5, 1500.0, 0.4, 60e6, "measured 2026-11-26 (CPU, peak RSS): the internal "
                                  "mate of a spiral pair 20/30 m 2, 35 deg, shaft 150 deg at 10 / 5 / 2 um, 211k / "
                                  "391k / 924k planned triangles: 5.4 / 13.1 / 44.7 s (25 / 33 / 48 us a triangle: "
                                  "the rim cone minus the teeth, then the caps), 186 / 318 / 617 MB; per planned "
                                  "triangle x (1 + triangles / plan_sets.INTERNAL_SPIRAL_KNEE)"),
    # the direct B-rep writer's section check (gear3d.export.step_direct_text.section_crossing):
    # per chord of half the tolerance along tooth 0 and its neighbours (plan.direct_section_points)
    "brep.direct.section": Cost(1.2e-6, 210.0, 0.0, 0.0, "measured 2026-11-26 in process (CPU, tracemalloc "
                                "peak): involute z = 14 (14.5 deg, undercut) / 100 at 10 um, 8 at 30 um, 1000 at "
                                "100 um: 0.25-2.5 M chords, 0.87-1.2 us and 207-212 B a chord; the plan's count "
                                "is 1.5-2.3x the chords"),
    # the direct B-rep writer itself (gear3d.export.step_direct, no OpenCascade; plan_writes.
    # direct_brep_estimate): per profile vertex x law piece (the flank fits, the measurement)
    "brep.direct": Cost(2.5e-5, 1500.0, 0.1, 60e6, "measured 2026-11-26 in a subprocess (CPU of direct_text, "
                        "section check included; RSS over the built body): spur z = 200 at 0.1 um... 1000 at 10 "
                        "um 1.0 / 8.6 s (800 / 4,000 face runs, 18,800 / 202,000 vertices, +48 / +406 MB, the "
                        "section's chords most of it), helical z = 40 at 0.1 mm 0.49 s, herringbone z = 60 0.92 "
                        "s, chevron-arch z = 100 at 1 um 1.56 s, helical z = 30 at 30 um (10.5 M triangles) "
                        "2.64 s: 1 ms a face run + 25 us a vertex x law piece + 0.25 us a mesh triangle; the writer's "
                        "estimate 1.2-2.1x its CPU; peak RSS of spur z = 1000 at 0.1 um 213 MB (209 MiB planned at "
                        "600 B a vertex and 30 MB: 1500 B and 60 MB kept)"),
    "brep.direct.face": Cost(1e-3, 2000.0, 0.0, 0.0, "the same measurement: per face run (teeth x 4 x law "
                             "pieces, as plan.brep_estimate counts them), 1 ms"),
    "brep.direct.mesh": Cost(2.5e-7, 300.0, 0.0, 0.0, "the same measurement: the mesh body's volume and area "
                             "(the volume check) on 10.5 M triangles about 1.9 s (0.18 us a triangle); bytes: the "
                             "body held while the writer works (260 B a triangle) and the check's arrays"),
    "bevel.brep": Cost(0.16, 2e6, 1.2, 300e6, "measured 2026-11-26 (CPU, peak RSS): B-rep STEP of a 20-tooth "
                       "gear (20/40 m 2, 10 um) 3.95 s in all, of the 100/100 pair at 50 um 30 s and 492 MB: "
                       "0.12-0.15 s and about 2 MB a tooth, plus OpenCascade's import"),
    "bevel.rolling": Cost(3e-3, 2e5, 0.3, 30e6, "measured 2026-11-26 (CPU, with and without --check): 20/40 m 2 "
                          "at 10 um 0.27 s, 300/300 m 1 at 50 um 0.87 s and +64 MB; per tooth of the larger member "
                          "(the first sphere's roll included; 300/300 0.57 s since the copies of teeth are made near "
                          "the mesh only)"),
    "bevel.rolling.sphere": Cost(0.3, 1e6, 0.0, 0.0, "measured 2026-11-26 (CPU): each further sphere of a "
                                 "uniform-clearance pair's check (96 positions) 0.14 s (20/40 m 2: 5 spheres 0.88 s "
                                 "against 0.33 s standard) to 0.19 s (300/300 m 1: 7 spheres 1.70 s against 0.57 s); "
                                 "an internal 20/30 pair at 170 deg (9 spheres) 0.33 s a sphere at load 6"),
    "crossed.check": Cost(9e-8, 250.0, 0.9, 60e6, "measured 2026-11-26 in process (CPU, ru_maxrss): crossed "
                          "helical checks 12/14 m 1 (faces 6 / 30 mm), 40/60 m 2 (20), 20/30 at 30 deg (10), 100/100 "
                          "m 0.5 (40): 0.68-6.4 s for 3.5 M-141 M flank points (46-110 ns a point beyond 0.5 s); "
                          "177-306 MB for 1.1-2.0 M points held at once (analysis.crossed_roll.work_count); as "
                          "processes after the Newton steps' flank guard: 200/300 m 1 (30 mm) 3.16 s for 3.19 s "
                          "planned at 7e-8, 1000/1000 m 0.5 2.42 for 2.85: 9e-8 and 0.9 s kept for a loaded machine"),
    "facegear.plan": Cost(2.5e-4, 0.0, 0.4, 40e6, "measured 2026-11-26 (CPU): z2 = 60, z0 = 20 at 0.1 um: 177 "
                          "sections x 93 vertices, about 4 s beyond the body (2.4e-4 s an item); the limits' scan "
                          "0.3 s"),
    "facegear.body": Cost(3e-6, 650.0, 0.0, 150e6, "measured 2026-11-26 (CPU): z2 = 300 / 1000 at 1 um, 1.26 / "
                          "4.2 M triangles: 3.6 / 11.7 s (2.8 us a triangle, plan included); 260 B a triangle "
                          "charged by the builder; small gears peak at 50-220 MB; per planned triangle (with "
                          "plan_sets.face_shaper_factor) peak RSS: z2/z0 = 1000/100 at 5 um 1.31 GB (577 B), "
                          "1000/200 pair 0.85 GB (524 B), 300/150 at 1 um 1.48 GB (380 B): 650 B kept"),
}
