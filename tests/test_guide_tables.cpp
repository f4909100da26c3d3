// docs/guide/arrays.md documents the arrays in four tables, totals, per-light terms, ambient
// occlusion and interreflection; each must list exactly the arrays the code writes, with their
// number of components.
#include "ArrayCatalog.h"
#include "ShBands.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

namespace
{
using namespace shadelab;
using Rows = std::map<std::string, int>; // name -> components

std::string arraysPage()
{
  std::ifstream file(shadelab::testing::sourcePath("docs/guide/arrays.md"));
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The rows "| `name` | components | ..." of the table that follows the line starting with
/// heading.
Rows tableAfter(const std::string& text, const std::string& heading)
{
  std::istringstream lines(text.substr(text.find("\n" + heading) + 1));
  std::string line;
  std::getline(lines, line); // the heading
  Rows rows;
  bool inTable = false;
  while (std::getline(lines, line))
  {
    if (line.rfind("|", 0) != 0)
    {
      if (inTable)
      {
        break;
      }
      continue;
    }
    inTable = true;
    if (line.rfind("| `", 0) == 0)
    {
      const std::size_t nameEnd = line.find('`', 3);
      rows[line.substr(3, nameEnd - 3)] = std::stoi(line.substr(line.find('|', nameEnd) + 1));
    }
  }
  return rows;
}

TEST(Guide, ArrayTablesListExactlyTheArraysWritten)
{
  const std::string text = arraysPage();
  Rows totals, perLight;
  for (int t = 0; t < TotalTermCount; ++t)
  {
    totals[termInfo(TotalTerm(t)).name] = termInfo(TotalTerm(t)).components;
  }
  totals[flagsInfo.name] = flagsInfo.components;
  for (int t = 0; t < LightTermCount; ++t)
  {
    // A transfer vector's count depends on its light's order: the table says "9, 16 or 25",
    // whose first number is order 2's.
    const int components = termInfo(LightTerm(t)).components;
    perLight[termInfo(LightTerm(t)).name] = components > 0 ? components : shCount(2);
  }
  Rows occlusion;
  for (int t = 0; t < OcclusionTermCount; ++t)
  {
    occlusion[termInfo(OcclusionTerm(t)).name] = termInfo(OcclusionTerm(t)).components;
  }
  EXPECT_EQ(tableAfter(text, "Totals (RGB"), totals);
  EXPECT_EQ(tableAfter(text, "Per light, named"), perLight);
  EXPECT_EQ(tableAfter(text, "Ambient occlusion, with the scene's"), occlusion);
  Rows interreflection;
  for (int t = 0; t < InterreflectionTermCount; ++t)
  {
    interreflection[termInfo(InterreflectionTerm(t)).name] = termInfo(InterreflectionTerm(t)).components;
  }
  interreflection[indirectBounceArrayName("", 1).substr(0, indirectBounceArrayName("", 1).size() - 1) + "<n>"] = 3;
  interreflection[indirectTransferArrayName("", "<light>")] = 3 * shCount(2); // "27, 48 or 75", as above
  EXPECT_EQ(tableAfter(text, "Interreflection, with the scene's"), interreflection);
}
}
