"""The ParaView plugin on a mesh split over MPI processes, in three steps run by .ci/paraview:

  pvpython (or /usr/bin/python3) paraview_split_check.py pieces MESH.ply|obj|vtp PIECES.pvtp COUNT
      the mesh in COUNT pieces with global point and cell ids (each one's index in the mesh);
  mpiexec -np N pvbatch paraview_split_check.py shade PLUGIN PIECES.pvtp SCENE SHADED.pvtp [default]
      Local Reflectance on the pieces, each process shading those it reads, written as a .pvtp:
      every array of the scene in float64, or with "default" the default arrays in float32;
  pvpython paraview_split_check.py check SHADED.pvtp REFERENCE.vtp N
      ParaView opens the .pvtp (N pieces), and at every point every array of the command line's
      output for the whole mesh (REFERENCE.vtp) equals the pieces' at that point, bit for bit.
"""
import os
import re
import sys

import numpy as np

step = sys.argv[1]

if step == "pieces":
    from vtkmodules.vtkCommonCore import VTK_ID_TYPE
    from vtkmodules.vtkFiltersParallel import vtkExtractPolyDataPiece
    from vtkmodules.vtkFiltersProgrammable import vtkProgrammableFilter
    from vtkmodules.vtkIOParallelXML import vtkXMLPPolyDataWriter
    from vtkmodules.vtkIOGeometry import vtkOBJReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.util.numpy_support import numpy_to_vtk

    mesh_file, pieces_file, count = sys.argv[2], sys.argv[3], int(sys.argv[4])
    readers = {".ply": vtkPLYReader, ".obj": vtkOBJReader, ".vtp": vtkXMLPolyDataReader}
    extension = os.path.splitext(mesh_file)[1].lower()
    if extension not in readers:
        sys.exit(f"{mesh_file}: cannot cut it into pieces: give a .ply, .obj or .vtp mesh")
    reader = readers[extension]()
    reader.SetFileName(mesh_file)
    reader.Update()
    mesh = reader.GetOutput()
    if mesh.GetNumberOfPolys() + mesh.GetNumberOfStrips() == 0:
        sys.exit(f"{mesh_file}: no polygons read from it: is it a mesh?")
    for data, size in ((mesh.GetPointData(), mesh.GetNumberOfPoints()), (mesh.GetCellData(), mesh.GetNumberOfCells())):
        ids = numpy_to_vtk(np.arange(size, dtype=np.int64), deep=1, array_type=VTK_ID_TYPE)
        ids.SetName("GlobalIds")
        data.AddArray(ids)
    extract = vtkExtractPolyDataPiece()  # drops the global ids attribute, not an array
    extract.SetInputData(mesh)
    extract.CreateGhostCellsOff()
    mark = vtkProgrammableFilter()
    mark.SetInputConnection(extract.GetOutputPort())

    def mark_global_ids():
        piece = mark.GetPolyDataOutput()
        piece.ShallowCopy(mark.GetPolyDataInput())
        piece.GetPointData().SetActiveGlobalIds("GlobalIds")
        piece.GetCellData().SetActiveGlobalIds("GlobalIds")

    mark.SetExecuteMethod(mark_global_ids)
    writer = vtkXMLPPolyDataWriter()
    writer.SetInputConnection(mark.GetOutputPort())
    writer.SetFileName(pieces_file)
    writer.SetNumberOfPieces(count)
    writer.SetStartPiece(0)
    writer.SetEndPiece(count - 1)
    writer.SetDataModeToBinary()  # inline: Debian's ParaView reads no raw appended data (docs/packaging.md)
    if writer.Write() != 1:
        sys.exit("could not write " + pieces_file)
    print(f"wrote {count} pieces of {mesh.GetNumberOfPoints()} points to {pieces_file}")

elif step == "shade":
    from paraview.simple import LoadPlugin, OpenDataFile, SaveData
    from vtkmodules.vtkParallelCore import vtkMultiProcessController

    plugin, pieces_file, scene, shaded_file = sys.argv[2:6]
    every_array = sys.argv[6:] != ["default"]
    LoadPlugin(plugin, remote=False, ns=globals())
    pieces = OpenDataFile(pieces_file)  # each process reads its share of the pieces
    shade = LocalReflectance(Input=pieces)  # noqa: F821 (the plugin's, in globals)
    shade.SceneFileName = scene
    if every_array:
        shade.UpdatePipelineInformation()
        shade.ArraySelection = shade.ArraySelection.Available
        shade.OutputPrecision = "float64"
    SaveData(shaded_file, proxy=shade, DataMode="Binary")
    processes = vtkMultiProcessController.GetGlobalController().GetNumberOfProcesses()
    print(f"shaded {pieces_file} on {processes} processes into {shaded_file}")

elif step == "check":
    from paraview.simple import OpenDataFile, servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy

    shaded_file, reference_file, processes = sys.argv[2], sys.argv[3], int(sys.argv[4])

    def point_arrays(file):
        data = servermanager.Fetch(OpenDataFile(file)).GetPointData()
        return {data.GetArrayName(a): vtk_to_numpy(data.GetArray(a)) for a in range(data.GetNumberOfArrays())}

    with open(shaded_file) as text:
        pieces = len(re.findall(r"<Piece ", text.read()))
    shaded, reference = point_arrays(shaded_file), point_arrays(reference_file)
    ids = shaded["GlobalIds"]
    failed = [f"{pieces} pieces in {shaded_file} for {processes} processes"] if pieces != processes else []
    for name, values in sorted(reference.items()):
        if name not in shaded:
            failed.append(f"no array '{name}'")
        elif shaded[name].dtype != values.dtype or not np.array_equal(shaded[name], values[ids], equal_nan=True):
            failed.append(f"'{name}' differs")
    covered = len(np.unique(ids)) == len(next(iter(reference.values())))
    if not covered:
        failed.append("the pieces do not hold every point of the mesh")
    print(f"{processes} processes: {len(reference)} arrays at {len(ids)} points of {pieces} pieces: " +
          ("bit for bit" if not failed else "FAILED: " + "; ".join(failed)))
    sys.exit(1 if failed else 0)
else:
    sys.exit(__doc__)
