"""Writes a DXF of zones for tests/io/plan_layers_io_test.cpp with ezdxf (R2010, metres):
layer ZONES: a closed LWPOLYLINE (a 4 x 3 rectangle at (1, 1)), a HATCH with a polyline path
(a triangle) and a hole, a HATCH with an edge path (line edges, a 2 x 2 square at (10, 0));
layer ROUND: a 2 x 2 closed LWPOLYLINE at (0, 20) whose right edge bulges out into a half disk
(bulge 1); layer OPEN: an open LWPOLYLINE; layer WALLS: a LINE.
Usage: make_zone_fixtures.py OUT.dxf"""
import sys

import ezdxf

doc = ezdxf.new("R2010")
doc.header["$INSUNITS"] = 6  # metres
msp = doc.modelspace()
msp.add_lwpolyline([(1, 1), (5, 1), (5, 4), (1, 4)], close=True, dxfattribs={"layer": "ZONES"})
hatch = msp.add_hatch(dxfattribs={"layer": "ZONES"})
hatch.paths.add_polyline_path([(20, 0), (26, 0), (23, 6)], is_closed=True)
hatch.paths.add_polyline_path([(22, 1), (24, 1), (23, 3)], is_closed=True)
edges = msp.add_hatch(dxfattribs={"layer": "ZONES"})
path = edges.paths.add_edge_path()
path.add_line((10, 0), (12, 0))
path.add_line((12, 0), (12, 2))
path.add_line((12, 2), (10, 2))
path.add_line((10, 2), (10, 0))
msp.add_lwpolyline([(0, 20, 0, 0, 0), (2, 20, 0, 0, 1), (2, 22, 0, 0, 0), (0, 22, 0, 0, 0)],
                   format="xyseb", close=True, dxfattribs={"layer": "ROUND"})
msp.add_lwpolyline([(0, 10), (3, 10), (3, 13)], close=False, dxfattribs={"layer": "OPEN"})
msp.add_line((0, 0), (30, 0), dxfattribs={"layer": "WALLS"})
doc.saveas(sys.argv[1])
