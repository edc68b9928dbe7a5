"""3MF (units mm) through trimesh, post-processed for determinism and metadata.

trimesh writes the objects (one per body, named), their meshes in the body frame and one
build item per body carrying its placement (``body.transform``). gear3d then rewrites the
package deterministically: random ``p:UUID`` values become name-based UUID5s, zip entries
get a fixed date, and metadata is added: model-level ``Title``, ``Application`` and
``gear3d:parameters`` (JSON of every part's parameters and measured error), and an
object-level ``metadatagroup`` with each part's ``gear3d:parameters`` and
``gear3d:max_error_mm``.
"""
from __future__ import annotations

import io
import json
import uuid
import zipfile

import numpy as np

NS_CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
NS_PROD = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"
NS_G3D = "https://gear3d.invalid/3mf/2026"
_UUID_NS = uuid.UUID("6f1d3c1e-5a2b-4c8e-9d0f-0e3d6a7b8c9d")
FIXED_DATE = (1980, 1, 1, 0, 0, 0)


def _params(b) -> dict:
    from .json_format import clean
    rep = dict(getattr(b, "report", {}) or {})
    params = rep.get("params") or getattr(getattr(b, "profile", None), "params", None) or {}
    return clean({"params": params, "max_error_mm": rep.get("max_error"),
                  "tolerance_mm": rep.get("tolerance"), "volume_mm3": rep.get("volume")})


def write(obj, path, title: str | None = None, **opts):
    import trimesh
    from . import as_bodies, body_name
    bodies = as_bodies(obj, **opts)
    scene = trimesh.Scene()
    names, seen = [], {}
    for i, b in enumerate(bodies):
        name = body_name(b, i)
        if name in seen:                      # object names must be unique in the scene
            seen[name] += 1
            name = f"{name}-{seen[name]}"
        seen.setdefault(name, 1)
        names.append(name)
        m = trimesh.Trimesh(np.asarray(b.mesh.vertices, float), np.asarray(b.mesh.faces), process=False)
        T = getattr(b, "transform", None)
        T = np.eye(4) if T is None else np.asarray(T, float)
        scene.add_geometry(m, geom_name=name, node_name=name, transform=T)
    raw = trimesh.exchange.threemf.export_3MF(scene)
    meta = {n: _params(b) for n, b in zip(names, bodies)}
    data = _postprocess(raw, title or names[0], meta)
    with open(path, "wb") as f:
        f.write(data)
    tri = sum(len(b.mesh.faces) for b in bodies)
    return f"3mf: {len(bodies)} object(s), {tri} triangles"


def _postprocess(raw: bytes, title: str, meta: dict) -> bytes:
    from lxml import etree
    zin = zipfile.ZipFile(io.BytesIO(raw))
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w") as zout:
        for info in zin.infolist():
            data = zin.read(info.filename)
            if info.filename == "3D/3dmodel.model":
                data = _model_xml(etree.fromstring(data), title, meta)
            zi = zipfile.ZipInfo(info.filename, date_time=FIXED_DATE)
            zi.compress_type = zipfile.ZIP_DEFLATED
            zi.external_attr = 0o644 << 16
            zout.writestr(zi, data, compresslevel=6)
    return out.getvalue()


def _model_xml(root, title, meta) -> bytes:
    from lxml import etree
    from .. import __version__
    q = lambda tag: f"{{{NS_CORE}}}{tag}"
    nsmap = dict(root.nsmap)
    nsmap["gear3d"] = NS_G3D
    new = etree.Element(root.tag, attrib=dict(root.attrib), nsmap=nsmap)
    for k, v in [("Title", title), ("Application", f"gear3d {__version__}"),
                 ("gear3d:parameters", json.dumps(meta, sort_keys=True, allow_nan=False))]:
        e = etree.SubElement(new, q("metadata"), name=k)
        if k.startswith("gear3d:"):
            e.set("preserve", "1")
        e.text = v
    for child in list(root):
        new.append(child)
    # deterministic UUIDs (trimesh writes uuid4s): derived from the element's role and name
    for k, el in enumerate(new.iter()):
        key = f"{{{NS_PROD}}}UUID"
        if key in el.attrib:
            label = el.get("name") or el.get("partnumber") or el.tag
            el.set(key, str(uuid.uuid5(_UUID_NS, f"{etree.QName(el).localname}/{label}/{k}")))
    for obj in new.iter(q("object")):
        m = meta.get(obj.get("name"))
        if m is None:
            continue
        grp = etree.Element(q("metadatagroup"))
        for k, v in [("gear3d:parameters", json.dumps(m["params"], sort_keys=True)),
                     ("gear3d:max_error_mm", "" if m["max_error_mm"] is None else repr(m["max_error_mm"]))]:
            e = etree.SubElement(grp, q("metadata"), name=k, preserve="1")
            e.text = v
        obj.insert(0, grp)
    return etree.tostring(new, xml_declaration=True, encoding="UTF-8")
