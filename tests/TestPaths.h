#pragma once
// Where the tests find the repository's files and the programs they run. The paths are compiled
// into one file that CMake writes (TestPaths.cpp.in), rather than defined on the command line of
// every test file, so that the test files compile to the same objects in any folder a clone is
// in, and .ci/compiler-cache finds them in its cache.
#include <string>

namespace shadelab::testing
{
/// The absolute path of a file or folder given relative to the source folder ("data/...").
std::string sourcePath(const std::string& relative);

/// The built `shadelab` command.
std::string shadelabExecutable();

/// The built `shadelab-bench`.
std::string benchExecutable();
}
