"""The web form in words: every field of every family's form has a label a person reads
("Number of teeth", not ``teeth``), short enough not to be cut off, a tooltip source (help and
range) and a group (size, tooth form, body, print compensation, pair, accuracy)."""
from __future__ import annotations

from gear3d.web.schema import GROUPS, LABELS, SET_LABELS, families, form_schema


def test_every_field_has_a_label_and_a_group():
    for fam in families():
        sch = form_schema(fam)
        assert sch["groups"] == list(GROUPS)
        for sec in ("profile", "body", "pair"):
            for f in sch[sec]:
                assert f["name"] in LABELS, (fam, f["name"])          # written, not derived
                written = SET_LABELS.get(fam, {}).get(f["name"], LABELS[f["name"]])     # a set's own words first
                assert f["label"] == written and f["label"][0].isupper() and len(f["label"]) <= 26
                assert f["group"] in GROUPS, (fam, f)
                assert f["help"], (fam, f["name"])


def test_groups_follow_the_parameter_kind():
    sch = form_schema("involute")
    g = {f["name"]: f["group"] for sec in ("profile", "body") for f in sch[sec]}
    assert g["teeth"] == g["module"] == "size"
    assert g["pressure_angle_deg"] == g["shift_coeff"] == "tooth form"
    assert g["bore"] == g["width"] == "body"
    assert g["xy_offset"] == g["elephant_foot"] == "print compensation"
    assert {f["label"] for f in sch["profile"]} >= {"Number of teeth", "Module", "Pressure angle"}
