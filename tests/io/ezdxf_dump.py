#!/usr/bin/python3
"""Independent DXF reader for floorgrid's tests: prints a DXF file's model-space geometry as JSON,
read by ezdxf (Debian's python3-ezdxf), never by floorgrid's own code.

Usage: ezdxf_dump.py FILE [--explode] [--flatten DISTANCE]

Without --explode, model-space LINE, ARC and CIRCLE entities are listed as ezdxf reads them (the
writer round trip). With --explode, INSERTs are expanded by ezdxf (Insert.multi_insert() for
MINSERT grids, Insert.virtual_entities() for the block transform and OCS), polylines are split by
ezdxf into LINE and ARC pieces, SOLID/TRACE give their WCS outline, ELLIPSE and SPLINE are
flattened by ezdxf. The only rule applied here rather than by ezdxf is AutoCAD's layer-0
inheritance (ezdxf keeps layer "0" on virtual entities): a block entity on layer "0" takes the
layer of the INSERT placing it.

Output: {"version", "insunits", "extmin", "extmax", "layers", "entities": [...], "counts": {type: n},
         "counts_by_layer": {layer: {type: n}}, "annotation": {type: n} (with --explode),
         "paper_space": n (entities of the active paper space layout),
         "extent": [xmin, ymin, xmax, ymax] or null}.
Each entity: {"type", "source" (the DXF type it came from), "layer", ...} with
LINE: "start", "end"; ARC: "center", "radius", "start", "end" (WCS points), "sweep" (degrees);
CIRCLE: "center", "radius"; POINTS: "points" (a flattened curve or an outline, in order).
Coordinates are WCS x, y.
"""
import json
import math
import sys

import ezdxf
from ezdxf import bbox
from ezdxf.math import Vec3, arc_angle_span_deg

ANNOTATION = {"TEXT", "MTEXT", "ATTRIB", "ATTDEF", "DIMENSION", "ARC_DIMENSION",
              "LARGE_RADIAL_DIMENSION", "LEADER", "MULTILEADER", "MLEADER", "TOLERANCE",
              "HATCH", "POINT", "VIEWPORT"}


def xy(v):
    return [float(v[0]), float(v[1])]


class Dump:
    def __init__(self, flatten):
        self.flatten = flatten
        self.entities = []
        self.counts = {}
        self.counts_by_layer = {}
        self.geometry = []  # ezdxf entities for the extent
        self.annotation = {}  # skipped annotation by type, counted per placement

    def count(self, source, layer):
        self.counts[source] = self.counts.get(source, 0) + 1
        by_type = self.counts_by_layer.setdefault(layer, {})
        by_type[source] = by_type.get(source, 0) + 1

    def add(self, kind, source, layer, **fields):
        record = {"type": kind, "source": source, "layer": layer}
        record.update(fields)
        self.entities.append(record)

    def primitive(self, e, source, layer):
        """Adds a LINE or ARC or CIRCLE (WCS) and returns True, or returns False."""
        t = e.dxftype()
        tilted = t in ("ARC", "CIRCLE") and not Vec3(e.dxf.extrusion).isclose(Vec3(0, 0, 1)) \
            and not Vec3(e.dxf.extrusion).isclose(Vec3(0, 0, -1))
        if tilted or t in ("ELLIPSE", "SPLINE"):
            # Not a circle in WCS XY: compare ezdxf's flattened curve (projected onto XY).
            self.add("POINTS", source, layer, points=[xy(p) for p in e.flattening(self.flatten)])
        elif t == "LINE":
            self.add("LINE", source, layer, start=xy(e.dxf.start), end=xy(e.dxf.end))
        elif t == "ARC":
            ocs = e.ocs()
            self.add("ARC", source, layer, center=xy(ocs.to_wcs(e.dxf.center)),
                     radius=float(e.dxf.radius), start=xy(e.start_point), end=xy(e.end_point),
                     sweep=arc_angle_span_deg(e.dxf.start_angle, e.dxf.end_angle))
        elif t == "CIRCLE":
            self.add("CIRCLE", source, layer, center=xy(e.ocs().to_wcs(e.dxf.center)),
                     radius=float(e.dxf.radius))
        else:
            return False
        return True

    def entity(self, e, parent_layer):
        t = e.dxftype()
        layer = e.dxf.layer
        if parent_layer is not None and layer == "0":
            layer = parent_layer
        if t in ANNOTATION:
            self.annotation[t] = self.annotation.get(t, 0) + 1
            return
        if t == "INSERT":
            for attrib in e.attribs:
                self.annotation["ATTRIB"] = self.annotation.get("ATTRIB", 0) + 1
            for cell in e.multi_insert():
                for child in cell.virtual_entities():
                    self.entity(child, layer)
            return
        if t in ("LWPOLYLINE", "POLYLINE"):
            if t == "POLYLINE" and (e.is_poly_face_mesh or e.is_polygon_mesh):
                return
            self.count(t, layer)
            self.geometry.append(e)
            for piece in e.virtual_entities():
                self.primitive(piece, t, layer)
            return
        if t in ("SOLID", "TRACE"):
            self.count(t, layer)
            self.geometry.append(e)
            self.add("POINTS", t, layer, points=[xy(p) for p in e.wcs_vertices(close=True)])
            return
        if self.primitive(e, t, layer):
            self.count(t, layer)
            self.geometry.append(e)


def main(argv):
    path = argv[1]
    explode = "--explode" in argv
    flatten = float(argv[argv.index("--flatten") + 1]) if "--flatten" in argv else 1e-4
    doc = ezdxf.readfile(path)
    dump = Dump(flatten)
    for e in doc.modelspace():
        if explode:
            dump.entity(e, None)
        elif dump.primitive(e, e.dxftype(), e.dxf.layer):
            dump.count(e.dxftype(), e.dxf.layer)
            dump.geometry.append(e)
    extent = bbox.extents(dump.geometry) if dump.geometry else None
    out = {
        "version": doc.dxfversion,
        "insunits": doc.header.get("$INSUNITS"),
        "extmin": xy(doc.header.get("$EXTMIN", (0, 0, 0))),
        "extmax": xy(doc.header.get("$EXTMAX", (0, 0, 0))),
        "layers": [layer.dxf.name for layer in doc.layers],
        "entities": dump.entities,
        "counts": dump.counts,
        "counts_by_layer": dump.counts_by_layer,
        "annotation": dump.annotation,
        "paper_space": len(doc.layouts.active_layout()),
        "extent": ([extent.extmin.x, extent.extmin.y, extent.extmax.x, extent.extmax.y]
                   if extent is not None and extent.has_data else None),
    }
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv)
