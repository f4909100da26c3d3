"""Writes open_box.vtp: a box of side 1 open at the front (+z), five walls of 32 x 32 quads each
split in two triangles, every wall with its own points and its normal pointing out of the box,
as a modeller exports a closed box's walls, a closed white block standing on its floor (faces of
8 x 8 quads, normals out), and a point array "paint": the albedo kd, white walls with a red left
wall and a green right one (the classic test of colour bleeding).

Run with VTK's Python: /usr/bin/python3 data/scenes/open_box/make_open_box.py
"""
import os

from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

CELLS = 32
WHITE, RED, GREEN = (0.72, 0.72, 0.72), (0.72, 0.08, 0.06), (0.10, 0.55, 0.12)

# Each wall: its origin and the ends of its two edges, ordered so that the plane's normal,
# edge 1 x edge 2, points out of the box, and its paint.
WALLS = [
    ("floor", (0, 0, 0), (1, 0, 0), (0, 0, 1), WHITE),
    ("ceiling", (0, 1, 0), (0, 1, 1), (1, 1, 0), WHITE),
    ("back", (0, 0, 0), (0, 1, 0), (1, 0, 0), WHITE),
    ("left", (0, 0, 0), (0, 0, 1), (0, 1, 0), RED),
    ("right", (1, 0, 0), (1, 1, 0), (1, 0, 1), GREEN),
]

# The block: x from 0.55 to 0.85, y from 0 to 0.45, z from 0.25 to 0.55, its faces' edges
# ordered so that their normals point out of it.
X0, X1, Y1, Z0, Z1 = 0.55, 0.85, 0.45, 0.25, 0.55
BLOCK = [
    ((X0, 0, Z0), (X1, 0, Z0), (X0, 0, Z1)),
    ((X0, Y1, Z0), (X0, Y1, Z1), (X1, Y1, Z0)),
    ((X0, 0, Z0), (X0, Y1, Z0), (X1, 0, Z0)),
    ((X0, 0, Z1), (X1, 0, Z1), (X0, Y1, Z1)),
    ((X0, 0, Z0), (X0, 0, Z1), (X0, Y1, Z0)),
    ((X1, 0, Z0), (X1, Y1, Z0), (X1, 0, Z1)),
]


def wall(origin, end1, end2, paint, cells=CELLS):
    plane = vtkPlaneSource()
    plane.SetOrigin(origin)
    plane.SetPoint1(end1)
    plane.SetPoint2(end2)
    plane.SetResolution(cells, cells)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(plane.GetOutputPort())
    triangles.Update()
    part = triangles.GetOutput()
    colours = vtkFloatArray()
    colours.SetName("paint")
    colours.SetNumberOfComponents(3)
    for _ in range(part.GetNumberOfPoints()):
        colours.InsertNextTuple3(*paint)
    part.GetPointData().AddArray(colours)
    part.GetPointData().RemoveArray("TextureCoordinates")
    return part


box = vtkAppendPolyData()
for _, origin, end1, end2, paint in WALLS:
    box.AddInputData(wall(origin, end1, end2, paint))
for origin, end1, end2 in BLOCK:
    box.AddInputData(wall(origin, end1, end2, WHITE, 8))
box.Update()
writer = vtkXMLPolyDataWriter()
writer.SetInputData(box.GetOutput())
writer.SetFileName(os.path.join(os.path.dirname(os.path.abspath(__file__)), "open_box.vtp"))
writer.SetDataModeToBinary()
writer.Write()
