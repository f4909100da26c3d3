#pragma once
// shadelab arrays --scene SCENE.json: the arrays a scene can produce, for shade's --arrays.
#include <CLI/CLI.hpp>

#include <string>

namespace shadelab::app
{
/// `arrays`'s option, read into sceneFile.
CLI::App* addArraysCommand(CLI::App& cli, std::string& sceneFile);

/// Exit code 0 done; throws UserError for a scene that cannot be read.
int runArrays(const std::string& sceneFile);
}
