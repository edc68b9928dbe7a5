"""DXF arc-spline fit vs a plain polyline at the same tolerance.

For 20-tooth, module-1 involute and sine gears at 10, 1 and 0.1 um: segments written
(arcs + lines), polyline vertices of the profile at the same tolerance, the ratio, the
measured max error of the DXF read back (DXF -> exact and exact -> DXF) and the time.
Prints a Markdown table and writes out/bench/dxf.md.

"meas. unc." is the error of the reference that Profile.exact_distance measures against.
"""
from __future__ import annotations

import os
import tempfile
import time

import gear3d
from gear3d.export.dxf import write_dxf


def main():
    rows = []
    for fam in ("involute", "sine"):
        for tol_um in (10.0, 1.0, 0.1):
            tol = tol_um * 1e-3
            p = gear3d.profile(fam, teeth=20, module=1.0, tolerance=tol)
            with tempfile.TemporaryDirectory() as d:
                t = time.perf_counter()
                r = write_dxf(p, os.path.join(d, "g.dxf"))
                dt = time.perf_counter() - t
            rows.append((fam, tol_um, r["arcs"], r["lines"], r["segments"], r["polyline_vertices"],
                         r["polyline_vertices"] / r["segments"], r["max_error"] * 1e3,
                         r["max_error_curve_to_dxf"] * 1e3, r["measurement_uncertainty"] * 1e3, dt))
    head = ("| family | tol (um) | arcs | lines | DXF segments | polyline vertices | ratio | "
            "max err DXF->exact (um) | max err exact->DXF (um) | meas. unc. (um) | time (s) |")
    lines = [head, "|" + "---|" * 11]
    for r in rows:
        lines.append(f"| {r[0]} | {r[1]:g} | {r[2]} | {r[3]} | {r[4]} | {r[5]} | {r[6]:.1f}x | "
                     f"{r[7]:.3g} | {r[8]:.3g} | {r[9]:.2g} | {r[10]:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    os.makedirs("out/bench", exist_ok=True)
    with open("out/bench/dxf.md", "w") as f:
        f.write("# DXF: arc-spline segments vs polyline vertices (20 teeth, m = 1)\n\n" + text)


if __name__ == "__main__":
    main()
