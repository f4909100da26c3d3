#pragma once
// A mesh split over processes in files: each process's piece of a mesh read whole, the
// pieces a .pvtp names, and the pieces written as one .pvtp (docs/guide/mpi.md).
#include "MeshFiles.h"

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>

class vtkMultiProcessController;

namespace shadelab::app
{
/// Piece `piece` of `pieces` of mesh (vtkExtractPolyDataPiece: runs of cells in their order,
/// with ghostLevels layers of ghost cells around it), every array and the field data passed
/// through, and global point and cell ids added where the mesh has none (each point's and
/// cell's index in mesh), with which the filters put the whole mesh back together
/// (ShadeLabWholeMesh.h).
vtkSmartPointer<vtkPolyData> meshPiece(vtkPolyData* mesh, int piece, int pieces, int ghostLevels);

/// VTK's reader of a .pvtp, whose pieces' readers report their errors as its own, naming the
/// piece (VTK 9.1's takes a piece it cannot parse for an empty one, and says nothing itself).
vtkSmartPointer<vtkAlgorithm> pvtpReader(const std::string& fileName);

/// How many bytes the pieces that a .pvtp names hold together. Throws UserError, naming the
/// .pvtp, where one is missing or is not a regular file.
std::uintmax_t pieceFileBytes(const std::string& fileName);

/// Why a .pvtp and its pieces cannot be written at fileName ("" where they can), found without
/// writing: a name its summary cannot hold or with a dot before its extension, a folder in its
/// place, or a folder of its pieces' name that holds anything but an earlier run's pieces.
/// fileName ends in .pvtp (in any case).
std::string pvtpPlaceProblem(const std::string& fileName);

/// Writes every process's piece of a mesh as one .pvtp (a collective call): the summary file,
/// and beside it a folder named after it with a .vtp per process (VTK's layout, which
/// ParaView opens as one mesh). Everything is written into a folder of its own first and moved
/// into place once every process has written its piece, so that a failed run leaves neither a
/// partial file nor a mix of old and new pieces. Throws UserError on every process alike.
void writePieces(vtkPolyData* piece, const std::string& fileName, vtkMultiProcessController* processes,
  Compression compression, VtpLayout layout);
}
