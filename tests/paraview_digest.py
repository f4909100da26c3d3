"""Digests of the point arrays of mesh files, to check that ParaView reads what ShadeLab wrote.

  /usr/bin/python3 tests/paraview_digest.py reference FILE... > reference.json
      reads the files with VTK 9.1 (python3-vtk9) and prints their digests;
  pvpython tests/paraview_digest.py check reference.json FILE...
      opens the files as ParaView does (paraview.simple.OpenDataFile) and exits 1 unless every
      digest matches.

A digest is, per point array: components, tuples, and per component the range and the sum.
"""
import json
import math
import sys


def digest(mesh):
    arrays = {}
    point_data = mesh.GetPointData()
    for a in range(point_data.GetNumberOfArrays()):
        array = point_data.GetArray(a)
        components = array.GetNumberOfComponents()
        tuples = array.GetNumberOfTuples()
        sums = [math.fsum(array.GetComponent(i, c) for i in range(tuples)) for c in range(components)]
        arrays[array.GetName()] = {
            "components": components,
            "tuples": tuples,
            "ranges": [list(array.GetRange(c)) for c in range(components)],
            "sums": sums,
        }
    return {"points": mesh.GetNumberOfPoints(), "arrays": arrays}


def read_with_vtk(path):
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader() if path.endswith(".vtp") else vtkPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def read_with_paraview(path):
    from paraview import servermanager
    from paraview.simple import OpenDataFile
    source = OpenDataFile(path)
    if source is None:
        raise RuntimeError("ParaView has no reader for " + path)
    source.UpdatePipeline()
    return servermanager.Fetch(source)


def main():
    if sys.argv[1] == "reference":
        json.dump({path: digest(read_with_vtk(path)) for path in sys.argv[2:]}, sys.stdout, indent=1)
        return 0
    with open(sys.argv[2]) as file:
        reference = json.load(file)
    failures = 0
    for path in sys.argv[3:]:
        seen = digest(read_with_paraview(path))
        same = seen == reference[path]
        failures += not same
        print(("same" if same else "DIFFERENT"), path, len(seen["arrays"]), "arrays,", seen["points"], "points")
    print(f"{len(sys.argv) - 3 - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
