#pragma once
// Where a filter's scene comes from. VTK's Python wrapping and ParaView's server-manager XML
// can carry strings but not a Scene, so a scene can be given as JSON text or as a scene file's
// name, as well as made in C++.
#include "Scene.h"

#include <optional>
#include <string>

namespace shadelab
{
/// A scene as read, or why it could not be (the command line's message).
struct SceneReading
{
  std::optional<Scene> scene;
  std::string problem;
};

class SceneSource
{
public:
  /// A scene made in C++. Forgets a file name or JSON text given before.
  void setScene(const Scene& scene);
  /// These return whether the value changed. "" means none; so does JSON text of white space
  /// alone (a text box a user emptied).
  bool setFileName(const std::string& fileName);
  bool setJson(const std::string& json);
  const std::string& fileName() const { return fileName_; }
  const std::string& json() const { return json_; }
  bool hasJson() const;

  /// The scene to use: from the JSON text if there is any, else from the named file (read
  /// now: a file edited since the last call is read as it is now), else the one set in C++,
  /// else the default light kit (as `shadelab shade` without --scene). Throws SceneFileError
  /// with the message the command line gives for the same scene; JSON text is called
  /// "SceneJson" there, and an environment map named in it is relative to the working folder
  /// (a file's are relative to the file).
  Scene scene() const;
  /// The same, with the error's message in place of the exception.
  SceneReading read() const;

private:
  std::optional<Scene> madeInCpp_;
  std::string fileName_;
  std::string json_;
};
}
