#pragma once
// The shadelab command run as a user runs it, for the command-line tests: each test gets a
// folder of its own, and a run's exit code, standard output and standard error.
#include "TestFolder.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace shadelab::testing
{
namespace fs = std::filesystem;

struct Result
{
  int exitCode;
  std::string out;
  std::string err;
};

class Cli : public TestFolder
{
protected:
  static std::string slurp(const fs::path& path)
  {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// Runs shadelab with these arguments; launcher (such as xvfb-run) goes before it.
  Result shadelab(const std::string& arguments, const std::string& launcher = "")
  {
    return run(shadelab::testing::shadelabExecutable(), arguments, launcher);
  }

  /// Runs an executable with these arguments, launcher before it.
  Result run(const std::string& executable, const std::string& arguments, const std::string& launcher = "")
  {
    const fs::path out = folder / "stdout.txt", err = folder / "stderr.txt";
    const std::string command = launcher + executable + " " + arguments + " > " + out.string() + " 2> " + err.string();
    const int status = std::system(command.c_str());
    Result result{ WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err) };
    fs::remove(out);
    fs::remove(err);
    return result;
  }

  /// Runs shade with a mesh and scene, expecting failure with exactly this one-line message.
  void expectError(const std::string& arguments, const std::string& message)
  {
    const Result result = shadelab(arguments);
    EXPECT_EQ(result.exitCode, 1) << arguments;
    EXPECT_EQ(result.err, "shadelab: " + message + "\n") << arguments;
    EXPECT_EQ(result.out, "") << arguments;
  }

  std::string goodScene()
  {
    return file("scene.json", R"({ "lights": [ { "name": "sun", "type": "distant", "direction": [0, 0, -1] } ] })");
  }

  std::string goodMesh() { return shadelab::testing::sourcePath("data/meshes/bunny_zipper.ply"); }
};
}
