#pragma once
// A value in a JSON document together with its JSON pointer, so that every error can say
// where it is ("/lights/2/min_distance"). The scene file reader and each light type's own
// fields (lights/) read through it.
#include "NearestName.h"
#include "Vec3.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace shadelab
{
using Json = nlohmann::json;

/// A problem at a JSON pointer; turned into a SceneFileError once the file name is known.
struct JsonError
{
  std::string path;
  std::string message;
};

inline std::string shortJsonText(const Json& value)
{
  std::string text = value.dump();
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

/// A value in the document together with its JSON pointer, so every error can say where.
class JsonNode
{
public:
  JsonNode(const Json& value, std::string path)
    : value_(value)
    , path_(std::move(path))
  {
  }

  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& message) const { throw JsonError{ path_, message }; }

  /// Requires an object whose keys are all in allowed (a misspelt key is an error, not a
  /// silently ignored setting).
  void expectObject(const std::vector<const char*>& allowed) const
  {
    if (!value_.is_object())
    {
      fail("must be an object, got " + shortJsonText(value_));
    }
    for (const auto& item : value_.items())
    {
      const bool known =
        std::any_of(allowed.begin(), allowed.end(), [&](const char* key) { return item.key() == key; });
      if (!known)
      {
        std::string list;
        for (const char* key : allowed)
        {
          list += (list.empty() ? "" : ", ") + std::string(key);
        }
        const std::string meant = nearestName(item.key(), std::vector<std::string>(allowed.begin(), allowed.end()));
        JsonNode(item.value(), path_ + "/" + item.key())
          .fail(
            "unknown field; " + (meant.empty() ? "" : "did you mean \"" + meant + "\"? ") + "allowed here: " + list);
      }
    }
  }

  void expectObject(std::initializer_list<const char*> allowed) const
  {
    expectObject(std::vector<const char*>(allowed));
  }

  bool has(const char* key) const { return value_.contains(key); }

  JsonNode at(const char* key) const
  {
    if (!has(key))
    {
      JsonNode(value_, path_ + "/" + key).fail("missing");
    }
    return JsonNode(value_.at(key), path_ + "/" + key);
  }

  double number() const
  {
    if (!value_.is_number())
    {
      fail("must be a number, got " + shortJsonText(value_));
    }
    return value_.get<double>();
  }

  int wholeNumber(int low, int high) const
  {
    const double x = number();
    if (!(x >= low && x <= high && x == std::floor(x)))
    {
      fail("must be a whole number from " + std::to_string(low) + " to " + std::to_string(high));
    }
    return static_cast<int>(x);
  }

  bool boolean() const
  {
    if (!value_.is_boolean())
    {
      fail("must be true or false, got " + shortJsonText(value_));
    }
    return value_.get<bool>();
  }

  std::string text() const
  {
    if (!value_.is_string())
    {
      fail("must be a string, got " + shortJsonText(value_));
    }
    return value_.get<std::string>();
  }

  /// One of the listed strings; returns the value paired with it.
  template<typename Value>
  Value choice(std::initializer_list<std::pair<const char*, Value>> options) const
  {
    return choiceAmong(options);
  }

  /// One of the names of options (a range of (name, value) pairs); returns the value paired
  /// with it.
  template<typename Options>
  auto choiceAmong(const Options& options) const
  {
    const std::string given = text();
    std::string list;
    for (const auto& [name, value] : options)
    {
      if (given == name)
      {
        return value;
      }
      list += (list.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    }
    fail("\"" + given + "\" is not one of " + list);
  }

  /// [low, high], low < high.
  std::array<double, 2> interval() const
  {
    if (!value_.is_array() || value_.size() != 2 ||
      !std::all_of(value_.begin(), value_.end(), [](const Json& x) { return x.is_number(); }) ||
      !(value_[0].get<double>() < value_[1].get<double>()))
    {
      fail("must be [low, high] with low < high, got " + shortJsonText(value_));
    }
    return { value_[0].get<double>(), value_[1].get<double>() };
  }

  glm::dvec3 vector3(const char* expected = "an array of 3 numbers") const
  {
    if (!value_.is_array() || value_.size() != 3 ||
      !std::all_of(value_.begin(), value_.end(), [](const Json& x) { return x.is_number(); }))
    {
      fail(std::string("must be ") + expected + ", got " + shortJsonText(value_));
    }
    return { value_[0].get<double>(), value_[1].get<double>(), value_[2].get<double>() };
  }

  /// An RGB colour: [r, g, b], or one number for grey.
  Rgb rgb() const { return value_.is_number() ? Rgb(value_.get<double>()) : vector3("[r, g, b] or one number"); }

  std::size_t size() const { return value_.size(); }
  bool isArray() const { return value_.is_array(); }
  bool isString() const { return value_.is_string(); }
  bool isObject() const { return value_.is_object(); }
  JsonNode element(std::size_t i) const { return JsonNode(value_.at(i), path_ + "/" + std::to_string(i)); }

private:
  const Json& value_;
  std::string path_;
};

/// The number at key, or fallback when the key is absent.
inline double numberOr(const JsonNode& object, const char* key, double fallback)
{
  return object.has(key) ? object.at(key).number() : fallback;
}

/// The colour at key, or fallback when the key is absent.
inline Rgb rgbOr(const JsonNode& object, const char* key, const Rgb& fallback)
{
  return object.has(key) ? object.at(key).rgb() : fallback;
}
}
