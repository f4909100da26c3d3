#pragma once
// Reads a scene (lights, material, viewer) from a JSON file. The schema is in
// docs/guide/scene-files.md.
#include "Scene.h"

#include <stdexcept>
#include <string>

namespace shadelab
{
/// A scene that cannot be used. what() is one line: "<file>: <JSON pointer>: <what is wrong>",
/// or "<file>: <what is wrong>" when the problem is not at one place.
class SceneFileError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

Scene readSceneFile(const std::string& fileName);

/// The same from text; sourceName stands for the file in messages.
Scene parseScene(const std::string& text, const std::string& sourceName);

class JsonNode;
/// Interreflection's "bounces": a whole number from 0 to Interreflection::maxBounces, or "auto"
/// (as many as a tolerance needs).
void readBounces(const JsonNode& node, Interreflection& interreflection);
}
