#pragma once
// How the reading process hands its mesh to the parent through the result file (a memfd; see
// IsolatedWork.h) without a format to encode and decode: each array's bytes as they are in
// memory, at a page boundary, after a table of what they are. The parent maps the pages
// (mmap) and wraps them as VTK arrays, so that a mesh of hundreds of megabytes changes
// process without being parsed or copied. Field data's string arrays (part names, a scene's
// JSON) go as their values' lengths and bytes. A mesh with another array whose bytes are not
// one plain block (strings in point or cell data, bits, VTK's other memory layouts) goes as
// VTK XML instead.
#include "vtkDataSet.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shadelab::app
{
/// Writes the mesh to the file at path (empty). Throws std::runtime_error.
void handOverMesh(vtkPolyData* mesh, const std::string& path);

/// The mesh handOverMesh wrote to path. Throws std::runtime_error if what it finds there is
/// not such a mesh (the parent does not trust the reading process).
vtkSmartPointer<vtkPolyData> takeOverMesh(const std::string& path);

/// Any dataset: polydata as handOverMesh does, others (unstructured, image, structured,
/// rectilinear grids) as VTK XML.
void handOverDataSet(vtkDataSet* data, const std::string& path);
vtkSmartPointer<vtkDataSet> takeOverDataSet(const std::string& path);
}
