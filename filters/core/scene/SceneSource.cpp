#include "SceneSource.h"

#include "DefaultLightKit.h"
#include "SceneFile.h"

namespace shadelab
{
void SceneSource::setScene(const Scene& scene)
{
  madeInCpp_ = scene;
  fileName_.clear();
  json_.clear();
}

bool SceneSource::setFileName(const std::string& fileName)
{
  const bool changed = fileName != fileName_;
  fileName_ = fileName;
  return changed;
}

bool SceneSource::setJson(const std::string& json)
{
  const bool changed = json != json_;
  json_ = json;
  return changed;
}

bool SceneSource::hasJson() const
{
  return json_.find_first_not_of(" \t\r\n") != std::string::npos;
}

Scene SceneSource::scene() const
{
  if (hasJson())
  {
    return parseScene(json_, "SceneJson");
  }
  if (!fileName_.empty())
  {
    return readSceneFile(fileName_);
  }
  return madeInCpp_ ? *madeInCpp_ : defaultLightKit();
}

SceneReading SceneSource::read() const
{
  try
  {
    return { scene(), "" };
  }
  catch (const std::exception& error) // a scene file or JSON text that cannot be used
  {
    return { std::nullopt, error.what() };
  }
}
}
