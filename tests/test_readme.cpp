// README.md documents every array in one table: each name the code can write must be there
// with its number of components.
#include "ArrayCatalog.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace
{
using namespace shadelab;

std::string readme()
{
  std::ifstream file(SHADELAB_SOURCE_DIR "/README.md");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void expectRow(const std::string& text, const TermInfo& info)
{
  const std::string row = "| `" + std::string(info.name) + "` | " + std::to_string(info.components) + " |";
  EXPECT_NE(text.find(row), std::string::npos) << "README.md has no row " << row;
}

TEST(Readme, ArrayTablesListEveryArray)
{
  const std::string text = readme();
  ASSERT_FALSE(text.empty());
  for (int t = 0; t < LightTermCount; ++t)
  {
    expectRow(text, termInfo(LightTerm(t)));
  }
  for (int t = 0; t < TotalTermCount; ++t)
  {
    expectRow(text, termInfo(TotalTerm(t)));
  }
  expectRow(text, flagsInfo);
}
}
