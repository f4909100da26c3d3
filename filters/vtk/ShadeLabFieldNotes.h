#pragma once
// What a filter did, in words, as a string array of the output's field data: ParaView shows it
// in its Information panel, and it travels with the file.
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <string>
#include <vector>

namespace shadelab
{
constexpr const char* normalsNoteName = "shadelab_normals";
constexpr const char* visibilityNoteName = "shadelab_visibility";
constexpr const char* interreflectionNoteName = "shadelab_interreflection";
constexpr const char* methodsNoteName = "shadelab_methods";

/// Adds the lines as the field-data string array `name`, in place of one of that name.
inline void addFieldNote(vtkDataObject* data, const char* name, const std::vector<std::string>& lines)
{
  auto note = vtkSmartPointer<vtkStringArray>::New();
  note->SetName(name);
  for (const std::string& line : lines)
  {
    note->InsertNextValue(line);
  }
  data->GetFieldData()->AddArray(note);
}
}
