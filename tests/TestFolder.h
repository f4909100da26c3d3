#pragma once
// A folder of the test's own, for tests that write files: made before it, removed after it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace shadelab::testing
{
class TestFolder : public ::testing::Test
{
protected:
  void SetUp() override
  {
    // The process id too: two test runs at once (two clones, or the sanitizer build's beside
    // the plain one) must not share a folder.
    folder = std::filesystem::temp_directory_path() /
      ("shadelab_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
        std::to_string(::getpid()));
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
  }
  void TearDown() override { std::filesystem::remove_all(folder); }

  /// Writes content to the file `name` in the folder; returns its path.
  std::string file(const std::string& name, const std::string& content)
  {
    const std::string path = (folder / name).string();
    std::ofstream(path) << content;
    return path;
  }

  std::filesystem::path folder;
};
}
