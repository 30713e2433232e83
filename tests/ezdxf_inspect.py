"""Reads a DXF with ezdxf (the independent reader of the tests) and prints what it found as
JSON, for tests/dxf_writer.rs to compare with the drawing it wrote.

usage: python ezdxf_inspect.py FILE.dxf"""
import json
import sys
from collections import Counter

from ezdxf import recover

doc, _ = recover.readfile(sys.argv[1])
msp = doc.modelspace()


def xy(v):
    return [v[0], v[1]]


out = {
    "version": doc.dxfversion,
    "header": {k: doc.header.get(k) for k in ("$DIMTXT", "$DIMASZ", "$LTSCALE", "$INSUNITS", "$MEASUREMENT",
                                              "$TEXTSTYLE", "$DIMTXSTY")},
    "styles": {s.dxf.name: s.dxf.font for s in doc.styles},
    "extmin": xy(doc.header["$EXTMIN"]),
    "extmax": xy(doc.header["$EXTMAX"]),
    "limmin": xy(doc.header["$LIMMIN"]),
    "limmax": xy(doc.header["$LIMMAX"]),
    "counts": dict(Counter(e.dxftype() for e in msp)),
    "layers": {l.dxf.name: [l.dxf.color, l.dxf.linetype] for l in doc.layers},
    "linetypes": {},
    "polylines": [],
    "texts": [],
    "dimensions": [],
    "entities": [],
}
for lt in doc.linetypes:
    pattern = lt.pattern_tags.tags
    values = [t.value for t in pattern]
    out["linetypes"][lt.dxf.name] = values  # [73 count, 40 total, 49 lengths...]

for e in msp:
    rec = {"type": e.dxftype(), "layer": e.dxf.layer, "color": e.dxf.get("color", 256),
           "linetype": e.dxf.get("linetype", "BYLAYER")}
    out["entities"].append(rec)
    if e.dxftype() == "POLYLINE":
        out["polylines"].append({
            "layer": e.dxf.layer,
            "closed": e.is_closed,
            "vertex_layers": [v.dxf.layer for v in e.vertices],
            "points": [xy(v.dxf.location) for v in e.vertices],
            "widths": [[v.dxf.get("start_width", 0.0), v.dxf.get("end_width", 0.0)] for v in e.vertices],
        })
    elif e.dxftype() == "TEXT":
        halign, valign = e.dxf.get("halign", 0), e.dxf.get("valign", 0)
        align = e.dxf.get("align_point")
        out["texts"].append({
            "text": e.dxf.text,
            "plain": e.plain_text(),
            "halign": halign,
            "valign": valign,
            "insert": xy(e.dxf.insert),
            "align_point": xy(align) if align is not None else None,
            "placement": xy(e.get_placement()[1]),
            "rotation": e.dxf.get("rotation", 0.0),
            "height": e.dxf.height,
            "width": e.dxf.get("width", 1.0),
            "style": e.dxf.get("style", "Standard"),
        })
    elif e.dxftype() == "DIMENSION":
        name = e.dxf.geometry
        block = doc.blocks.get(name)
        out["dimensions"].append({
            "dimtype": e.dimtype,
            "measurement": e.get_measurement(),
            "text": e.dxf.text,
            "block": name,
            "block_content": dict(Counter(b.dxftype() for b in block)) if block is not None else None,
            "block_texts": [b.dxf.text for b in block if b.dxftype() == "TEXT"] if block is not None else [],
        })
print(json.dumps(out))
