#pragma once
// Bitwise comparison of point arrays, for results that must not depend on threads or files.
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace shadelab::testing
{
/// Bitwise equality of two arrays of the same type and shape.
inline void expectSameBits(vtkDataArray* a, vtkDataArray* b, const std::string& name)
{
  ASSERT_NE(a, nullptr) << name;
  ASSERT_NE(b, nullptr) << name;
  ASSERT_EQ(a->GetDataType(), b->GetDataType()) << name;
  ASSERT_EQ(a->GetNumberOfValues(), b->GetNumberOfValues()) << name;
  const std::size_t bytes = a->GetNumberOfValues() * a->GetDataTypeSize();
  EXPECT_EQ(std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0), bytes), 0) << name;
}

inline void expectSamePointArrays(vtkPolyData* expected, vtkPolyData* actual)
{
  vtkPointData* want = expected->GetPointData();
  ASSERT_EQ(want->GetNumberOfArrays(), actual->GetPointData()->GetNumberOfArrays());
  for (int a = 0; a < want->GetNumberOfArrays(); ++a)
  {
    const std::string name = want->GetArrayName(a);
    expectSameBits(want->GetArray(a), actual->GetPointData()->GetArray(name.c_str()), name);
  }
}
}
