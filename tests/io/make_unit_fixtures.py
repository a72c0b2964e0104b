#!/usr/bin/python3
"""Writes the DXF drawings floorgrid's unit tests read (tests/io/dxf_units_test.cpp), with ezdxf
(Debian's python3-ezdxf), never with floorgrid's own writer. Each reproduces a kind of real file
on which guessing the units from the overall extent and a few door arcs went wrong.

Usage: make_unit_fixtures.py OUTPUT_FOLDER

Every drawing is a building drawn in metres and then scaled to its drawing unit: double-line
walls (exterior and interior thickness), rooms along corridors, door swings (a quarter arc about
the hinge with a straight leaf, on layer DOORS). Files:
  cm_header_four_doors.dxf      $INSUNITS cm, a 95 x 59 m building in cm whose only door arcs are
                                four 36-unit swings (an inch door block inserted unscaled): cm
  storeys_side_by_side_m.dxf    $INSUNITS m, four 130 x 40 m storeys side by side (565 m): m
  storeys_side_by_side_none.dxf the same without $INSUNITS: m, with a warning
  campus_unitless_m.dxf         no $INSUNITS, a 340 x 206 m campus in metres at georeferenced
                                coordinates, with a survey marker left at the origin: m, warning
  unitless_mm_doors.dxf         no $INSUNITS, a 30 x 20 m building in mm with 900 mm doors: mm
  header_lies_mm_inches.dxf     $INSUNITS mm, a 22 x 14.5 m house drawn in inches with 10 door
                                swings and feet-inch dimensions (as house_floorplan_r2004): in
  header_lies_cm_inches.dxf     $INSUNITS cm, a 60 x 30 m building drawn in inches (a plausible
                                23.6 x 11.8 m in cm) with 36-inch doors in every room: in
"""
import os
import sys

import ezdxf

INCH = 0.0254


class Drawing:
    """A building drawing in metres, written in drawing units (`scale` units per metre)."""

    def __init__(self, insunits, scale, offset=(0.0, 0.0)):
        self.doc = ezdxf.new("R2010", setup=True)
        if insunits is None:
            del self.doc.header["$INSUNITS"]
        else:
            self.doc.header["$INSUNITS"] = insunits
        self.msp = self.doc.modelspace()
        self.scale = scale
        self.offset = offset
        for layer in ("WALLS", "DOORS", "DIMS"):
            self.doc.layers.add(layer)

    def p(self, x, y):
        return ((x + self.offset[0]) * self.scale, (y + self.offset[1]) * self.scale)

    def line(self, a, b, layer="WALLS"):
        self.msp.add_line(self.p(*a), self.p(*b), dxfattribs={"layer": layer})

    def rect(self, x0, y0, x1, y1):
        self.msp.add_lwpolyline([self.p(x0, y0), self.p(x1, y0), self.p(x1, y1), self.p(x0, y1)],
                                close=True, dxfattribs={"layer": "WALLS"})

    def wall(self, a, b, thickness):
        """A straight wall along the x or y axis between a and b, as its two faces."""
        h = thickness / 2.0
        if a[1] == b[1]:
            self.line((a[0], a[1] - h), (b[0], b[1] - h))
            self.line((a[0], a[1] + h), (b[0], b[1] + h))
        else:
            self.line((a[0] - h, a[1]), (b[0] - h, b[1]))
            self.line((a[0] + h, a[1]), (b[0] + h, b[1]))

    def door(self, hinge, radius_units, start_deg):
        """A door swing: a quarter arc of `radius_units` drawing units about the hinge from
        `start_deg`, and the open leaf along its end."""
        import math
        c = self.p(*hinge)
        self.msp.add_arc(c, radius_units, start_deg, start_deg + 90.0,
                         dxfattribs={"layer": "DOORS"})
        end = math.radians(start_deg + 90.0)
        self.msp.add_line(c, (c[0] + radius_units * math.cos(end),
                              c[1] + radius_units * math.sin(end)), dxfattribs={"layer": "DOORS"})

    def building(self, x0, y0, width, depth, exterior=0.3, interior=0.12, room=6.0,
                 corridor=2.4, door=0.9, doors=True):
        """Exterior walls, a corridor along the middle, rooms of `room` m on both sides, and a
        door (radius `door` m) from the corridor into every room when `doors`."""
        self.rect(x0, y0, x0 + width, y0 + depth)
        self.rect(x0 + exterior, y0 + exterior, x0 + width - exterior, y0 + depth - exterior)
        mid = y0 + depth / 2.0
        low, high = mid - corridor / 2.0, mid + corridor / 2.0
        inner_x0, inner_x1 = x0 + exterior, x0 + width - exterior
        self.wall((inner_x0, low), (inner_x1, low), interior)
        self.wall((inner_x0, high), (inner_x1, high), interior)
        x = inner_x0 + room
        while x < inner_x1 - 1.0:
            self.wall((x, y0 + exterior), (x, low - interior / 2.0), interior)
            self.wall((x, high + interior / 2.0), (x, y0 + depth - exterior), interior)
            if doors:
                r = door * self.scale
                self.door((x - interior / 2.0 - 0.1, low - interior / 2.0), r, 180.0)
                self.door((x - interior / 2.0 - 0.1, high + interior / 2.0), r, 90.0)
            x += room

    def dimension(self, a, b, text=None):
        """A horizontal or vertical dimension from a to b (metres), with `text` overriding the
        measured value when given; rendered by ezdxf into its block."""
        horizontal = a[1] == b[1]
        base = (a[0], a[1] - 1.0) if horizontal else (a[0] - 1.0, a[1])
        dim = self.msp.add_linear_dim(base=self.p(*base), p1=self.p(*a), p2=self.p(*b),
                                      angle=0 if horizontal else 90, text=text or "<>",
                                      dimstyle="EZDXF", dxfattribs={"layer": "DIMS"})
        dim.render()

    def save(self, folder, name):
        self.doc.saveas(os.path.join(folder, name))


def feet_inches(metres):
    inches = round(metres / INCH)
    return "%d'-%d\"" % (inches // 12, inches % 12)


def main(folder):
    os.makedirs(folder, exist_ok=True)

    # A cm drawing whose only quarter arcs are four 36-unit door swings: 0.36 m in cm, 0.91 m
    # if they were inches. The walls (30 and 12 cm) and rooms (6 m) are a building's in cm.
    d = Drawing(5, 100.0)
    d.building(0.0, 0.0, 95.0, 59.0, doors=False)
    for i in range(4):
        d.door((10.0 + 12.0 * i, 28.3), 36.0, 180.0)
    d.save(folder, "cm_header_four_doors.dxf")

    # Four storeys of 130 x 40 m side by side, 15 m apart: 565 m in all, in metres.
    for insunits, name in ((6, "storeys_side_by_side_m.dxf"), (None,
                                                               "storeys_side_by_side_none.dxf")):
        d = Drawing(insunits, 1.0)
        for storey in range(4):
            d.building(145.0 * storey, 0.0, 130.0, 40.0, room=6.5, door=0.9)
        d.save(folder, name)

    # A campus of five buildings over 340 x 206 m in metres, placed at UTM-like coordinates as
    # shared coordinates place a Revit model, with the survey marker left at the origin.
    d = Drawing(None, 1.0, offset=(455000.0, 5650000.0))
    for x0, y0, w, h in ((0.0, 0.0, 120.0, 36.0), (150.0, 0.0, 190.0, 44.0),
                         (0.0, 80.0, 90.0, 30.0), (120.0, 90.0, 110.0, 40.0),
                         (250.0, 150.0, 90.0, 56.0)):
        d.building(x0, y0, w, h, exterior=0.35, interior=0.15, room=7.5, corridor=2.8, door=1.0)
    d.msp.add_circle((0.0, 0.0), 1.0)
    d.msp.add_line((-2.0, 0.0), (2.0, 0.0))
    d.msp.add_line((0.0, -2.0), (0.0, 2.0))
    d.save(folder, "campus_unitless_m.dxf")

    # A 30 x 20 m building in millimetres with 900 mm doors, 200 and 100 mm walls, no header.
    d = Drawing(None, 1000.0)
    d.building(0.0, 0.0, 30.0, 20.0, exterior=0.2, interior=0.1, room=5.0, corridor=1.8, door=0.9)
    d.save(folder, "unitless_mm_doors.dxf")

    # A house drawn in inches under a header saying mm: 12 door swings of 30-36 inches, 6-inch
    # exterior and 4.5-inch interior walls, and feet-inch dimensions (overrides, and measured
    # values with an inch mark appended by the dimension style).
    d = Drawing(4, 1.0 / INCH)
    style = d.doc.dimstyles.get("EZDXF")
    style.dxf.dimpost = "<>\""  # the measured value in inches, with an inch mark
    style.dxf.dimlfac = 1.0  # ezdxf's style measures 1:100 drawings in cm
    style.dxf.dimdec = 0
    d.building(0.0, 0.0, 22.0, 14.5, exterior=6 * INCH, interior=4.5 * INCH, room=3.6,
               corridor=1.2, door=0.9)
    for x in (3.6, 7.2, 10.8):
        d.dimension((x - 3.6, 0.0), (x, 0.0), feet_inches(3.6))
        d.dimension((0.0, x - 3.6), (0.0, x))
    d.save(folder, "header_lies_mm_inches.dxf")

    # A building drawn in inches under a header saying cm, where cm gives a plausible size: the
    # many door swings, walls and rooms must outweigh the header.
    d = Drawing(5, 1.0 / INCH)
    d.building(0.0, 0.0, 60.0, 30.0, exterior=8 * INCH, interior=4.5 * INCH, room=5.0,
               corridor=1.8, door=36 * INCH)
    d.save(folder, "header_lies_cm_inches.dxf")


if __name__ == "__main__":
    main(sys.argv[1])
