"""``report.html``: a scene's results as a page you can look at, written beside its files.

For each part: a rendered preview (PNG under ``previews/``: the shaded body when the part
has one, else its filled outline with the pitch circle), its measured error (the largest of
its profile's, body's and files' measured errors, mm), the tolerance of each output, and links
to its files. Pairs add their rolling check (interference, penetration, contact ratio) and a
preview of the placed bodies; assemblies their parts. Every link is relative and the page
holds its own style, so it opens straight from the folder (``file://``), with no server.

Example::

    from gear3d.jobs import load_scene, build_scene
    from gear3d.jobs.htmlreport import write_report_html
    rep = build_scene(load_scene("templates/showcase.toml"), "out/showcase")
    write_report_html(rep, "out/showcase")       # -> "out/showcase/report.html"
"""
from __future__ import annotations

import html
import os

from ..filesafe import atomic_path
from .graph import first_upstream

PREVIEWS = "previews"
_STYLE = """body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse;width:100%}td,th{border-bottom:1px solid #ddd;padding:.4em;vertical-align:top;text-align:left}
th{background:#f4f4f4}img{width:220px;height:auto;background:#fff;border:1px solid #eee}
.ok{color:#176d2c}.bad{color:#b00020;font-weight:bold}code{background:#f4f4f4;padding:0 .2em}
.num{font-variant-numeric:tabular-nums;white-space:nowrap}"""


def outline_png(profile, path) -> str:
    """A quick preview of a profile: its loops filled (holes left white) and the pitch
    circle dashed, in mm, as PNG at ``path``."""
    import matplotlib
    import numpy as np
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(4, 4), dpi=80)
    loops = list(profile.loops)
    for i, lp in enumerate(loops):
        q = np.vstack([lp, lp[:1]])
        ax.fill(q[:, 0], q[:, 1], color="#4a78a8" if i == 0 else "white", zorder=1 + (i > 0))
        ax.plot(q[:, 0], q[:, 1], color="#1f3550", lw=0.6, zorder=3)
    r = getattr(profile, "pitch_radius", None)
    if r:
        t = np.linspace(0, 2 * np.pi, 361)
        ax.plot(r * np.cos(t), r * np.sin(t), "--", color="#2a9d3a", lw=0.6, zorder=4)
    ax.set_aspect("equal")
    ax.set_xlabel("mm")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def _preview(obj, path):
    """A preview PNG of a profile, a body or a list of bodies; None when there is nothing
    to draw."""
    from ..figures import mesh_preview
    from ..solids import Body
    if obj is None:
        return None
    if isinstance(obj, (list, tuple)) or isinstance(obj, Body):
        mesh_preview(obj, path)
        import matplotlib.pyplot as plt
        plt.close("all")
        return path
    if hasattr(obj, "loops"):
        return outline_png(obj, path)
    return None


def measured(d: dict, info: dict):
    """The measured error (mm) behind one output ``info`` of a part, pair or assembly entry
    ``d`` of a scene report: the file's own (DXF/SVG read back), else its body's or its
    profile's at the output's tolerance (a pair: its placed bodies'); None for a report."""
    if info.get("max_error") is not None:
        return info["max_error"]
    tol = info.get("tolerance")
    if tol is None:
        return None
    for grp in ("bodies", "profiles"):
        hit = d.get(grp, {}).get(f"{tol:g}")
        if hit and hit.get("max_error") is not None:
            return hit["max_error"]
    stem = str(info.get("file", "")).rsplit(".", 1)[0]
    for name, part in (d.get("parts") or {}).items():       # an assembly's part files
        if stem.endswith("_" + name) and part.get("profile_max_error") is not None:
            return part["profile_max_error"]
    return d.get("max_error")


def _within(d: dict) -> bool:
    """Every measured output of ``d`` within its tolerance."""
    return all(e <= o["tolerance"] for o in d["outputs"].values()
               if (e := measured(d, o)) is not None and o.get("tolerance") is not None)


def _max_error(d) -> float | None:
    errs = [e for o in d.get("outputs", {}).values() if (e := measured(d, o)) is not None]
    return max(errs) if errs else None


def _files(d: dict) -> str:
    items = []
    for o in d["outputs"].values():
        f = o.get("file")
        if not f:
            continue
        size, tol, err = o.get("bytes"), o.get("tolerance"), measured(d, o)
        bits = [f"{size / 1024:.0f} KiB" if size else ""]
        if err is not None:
            bits.append(f"measured {err:.3g} mm")
        if tol is not None:
            bits.append(f"tolerance {tol:g} mm")
        extra = ", ".join(b for b in bits if b)
        items.append(f'<a href="{html.escape(f)}">{html.escape(f)}</a> <small>({html.escape(extra)})</small>')
    return "<br>".join(items)


def _tolerances(outputs: dict) -> str:
    tols = sorted({o["tolerance"] for o in outputs.values() if o.get("tolerance") is not None})
    return ", ".join(f"{t:g}" for t in tols) or "-"


def _fmt_mm(v) -> str:
    return "-" if v is None else f"{v:.3g}"


def _img(rel) -> str:
    return f'<img src="{html.escape(rel)}" alt="preview">' if rel else ""


def _part_rows(report, g, owners, out_dir) -> list:
    rows = []
    for name, d in report["parts"].items():
        keys = owners["parts"].get(name, {})
        obj = None
        for key in keys.values():
            obj = first_upstream(g, key, "body") or obj
        if obj is None:
            for key in keys.values():
                obj = first_upstream(g, key, "profile") or obj
        rel = _save(obj, out_dir, name)
        rows.append(f"<tr><td>{_img(rel)}</td><td><b>{html.escape(name)}</b></td>"
                    f'<td class="num {"ok" if _within(d) else "bad"}">{_fmt_mm(_max_error(d))}</td>'
                    f'<td class="num">{_tolerances(d["outputs"])}</td><td>{_files(d)}</td></tr>')
    return rows


def _save(obj, out_dir, name):
    if obj is None:
        return None
    os.makedirs(os.path.join(out_dir, PREVIEWS), exist_ok=True)
    rel = f"{PREVIEWS}/{name}.png"
    with atomic_path(os.path.join(out_dir, rel), "preview") as tmp:
        done = _preview(obj, tmp)
    if not done:
        os.remove(os.path.join(out_dir, rel))
    return rel if done else None


def _pair_rows(report, g, owners, out_dir) -> list:
    rows = []
    for name, d in report["pairs"].items():
        placed = None
        for key in owners["pairs"].get(name, {}).values():
            placed = placed or first_upstream(g, key, "place")
        rel = _save(placed, out_dir, name)
        c = d.get("check") or {}
        if c:
            bad = c.get("interference")
            check = (f'<span class="{"bad" if bad else "ok"}">{"INTERFERENCE" if bad else "no interference"}</span>'
                     f"; max penetration {_fmt_mm(c.get('max_penetration'))} mm; contact ratio "
                     f"{c['contact_ratio']:.3f}" if c.get("contact_ratio") is not None else "")
            check += f"; tolerance {c.get('tolerance', 0):g} mm"
        else:
            check = "-"
        rows.append(f"<tr><td>{_img(rel)}</td><td><b>{html.escape(name)}</b></td><td>{check}</td>"
                    f'<td>{_files(d)}</td></tr>')
    return rows


def _assembly_rows(report, g, owners, out_dir) -> list:
    rows = []
    for name, d in report["assemblies"].items():
        built = None
        for key in owners["assemblies"].get(name, {}).values():
            built = built or first_upstream(g, key, "harmonic")
        rel = _save(list(built[1]) if built else None, out_dir, name)
        ratio = d.get("ratio")
        rows.append(f"<tr><td>{_img(rel)}</td><td><b>{html.escape(name)}</b></td>"
                    f"<td>{'ratio ' + format(ratio, '.4g') if ratio is not None else '-'}</td>"
                    f'<td>{_files(d)}</td></tr>')
    return rows


def write_report_html(report: dict, out_dir, path: str = "report.html") -> str:
    """Write ``out_dir/report.html`` (and its ``previews/*.png``) for a scene report returned
    by :func:`gear3d.jobs.scene.build_scene` (it carries the stage graph and the owners of
    each output). Returns the page's path."""
    g, owners = report["graph"], report["owners"]
    head = (f"<h1>{html.escape(report['scene'])}</h1><p>From <code>{html.escape(report['file'])}</code>. "
            f"Largest measured error: <b>{_fmt_mm(report.get('max_error'))} mm</b>; every file is within "
            "its tolerance or it is not written. Measured error: the largest distance to the exact "
            "geometry, mm. Full numbers: "
            f'<a href="{html.escape(report["scene"])}.report.json">{html.escape(report["scene"])}.report.json</a>.</p>')
    parts = _part_rows(report, g, owners, out_dir)
    pairs = _pair_rows(report, g, owners, out_dir)
    asms = _assembly_rows(report, g, owners, out_dir)
    body = [head]
    if parts:
        body += ["<h2>Parts</h2><table><tr><th>preview</th><th>part</th><th>largest measured error (mm)</th>"
                 "<th>tolerance (mm)</th><th>files</th></tr>", *parts, "</table>"]
    if pairs:
        body += ["<h2>Pairs</h2><table><tr><th>preview</th><th>pair</th><th>rolling check</th>"
                 "<th>files</th></tr>", *pairs, "</table>"]
    if asms:
        body += ["<h2>Assemblies</h2><table><tr><th>preview</th><th>assembly</th><th></th>"
                 "<th>files</th></tr>", *asms, "</table>"]
    page = ("<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(report['scene'])}: gear3d report</title><style>{_STYLE}</style></head>"
            "<body>" + "\n".join(body) + "</body></html>\n")
    out = os.path.join(out_dir, path)
    with atomic_path(out, "report") as tmp, open(tmp, "w", encoding="utf-8") as fh:
        fh.write(page)
    return out
