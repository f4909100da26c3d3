#include "SpecularPower.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

namespace shadelab
{
std::string powMethodName(PowMethod method)
{
  switch (method)
  {
    case PowMethod::Exact: return "std::pow";
    case PowMethod::Series: return "series pow";
    case PowMethod::Schlick: return "Schlick pow";
  }
  return "";
}

namespace
{
/// The largest |power(x) - pow(x, eta)| over x in [0, 1], x and eta as type T holds them.
/// x^eta changes fastest just below 1 for a large eta, so the grid is uniform in x and also
/// geometric in 1 - x down to 1e-9, then refined around the worst sample.
template<typename T, typename Power>
double searchLargestError(double eta, Power&& power)
{
  auto errorAt = [&](double x)
  {
    const long double exact =
      std::pow(static_cast<long double>(static_cast<T>(x)), static_cast<long double>(static_cast<T>(eta)));
    return static_cast<double>(std::abs(static_cast<long double>(power(static_cast<T>(x))) - exact));
  };
  std::vector<double> grid;
  constexpr int uniform = 4096;
  for (int k = 0; k <= uniform; ++k)
  {
    grid.push_back(double(k) / uniform);
  }
  for (double gap = 1e-9; gap < 1; gap *= 1.02)
  {
    grid.push_back(1 - gap);
  }
  std::sort(grid.begin(), grid.end());
  double largest = 0;
  std::size_t worst = 0;
  for (std::size_t k = 0; k < grid.size(); ++k)
  {
    const double error = errorAt(grid[k]);
    if (error > largest)
    {
      largest = error;
      worst = k;
    }
  }
  const double low = grid[worst == 0 ? 0 : worst - 1];
  const double high = grid[std::min(worst + 1, grid.size() - 1)];
  constexpr int refinement = 512;
  for (int k = 0; k <= refinement; ++k)
  {
    largest = std::max(largest, errorAt(low + (high - low) * k / refinement));
  }
  return largest;
}

template<typename T>
double searchLargestPowError(PowMethod method, double eta)
{
  return searchLargestError<T>(eta,
    [&](T x)
    {
      T approximation = 0;
      withPowMethod(method, T(eta), [&](auto power) { approximation = power(x); });
      return approximation;
    });
}
}

void evaluatePowers(PowMethod method, const float* x, float* y, std::size_t count, float eta)
{
  withPowMethod(method, eta,
    [&](auto power)
    {
      for (std::size_t i = 0; i < count; ++i)
      {
        y[i] = power(x[i]);
      }
    });
}

void wholePowers(const float* x, float* y, std::size_t count, unsigned eta)
{
  // Below 2^(-150 / eta) the power is below half the smallest float and rounds to 0; such an x
  // is raised to that bound first, so that no product falls among the subnormal doubles,
  // which are many times slower, and set to 0 at the end.
  const double zeroBelow = eta > 0 ? std::exp2(-150.0 / eta) : 0.0;
  // One loop over a chunk per bit of eta, rather than a loop over bits per value, so that
  // each loop vectorises.
  constexpr std::size_t chunk = 128;
  double base[chunk], power[chunk];
  for (std::size_t first = 0; first < count; first += chunk)
  {
    const std::size_t n = std::min(chunk, count - first);
    for (std::size_t k = 0; k < n; ++k)
    {
      base[k] = std::max(double(x[first + k]), zeroBelow);
      power[k] = 1.0;
    }
    for (unsigned bits = eta; bits != 0; bits >>= 1)
    {
      if (bits & 1u)
      {
        for (std::size_t k = 0; k < n; ++k)
        {
          power[k] *= base[k];
        }
      }
      if (bits > 1)
      {
        for (std::size_t k = 0; k < n; ++k)
        {
          base[k] *= base[k];
        }
      }
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      y[first + k] = double(x[first + k]) < zeroBelow ? 0.0f : float(power[k]);
    }
  }
}

double largestWholePowerError(unsigned eta)
{
  return searchLargestError<float>(eta,
    [&](float x)
    {
      float power = 0;
      wholePowers(&x, &power, 1, eta);
      return power;
    });
}

template<typename T>
double largestPowError(PowMethod method, double eta)
{
  if (!std::isfinite(eta))
  {
    return searchLargestPowError<T>(method, eta); // not a key a map can order
  }
  // The search takes milliseconds, longer than shading a million vertices: each answer is
  // kept, so a filter re-run under a tolerance pays for it once per method and shininess.
  static std::mutex mutex;
  static std::map<std::pair<PowMethod, double>, double> found;
  const std::pair<PowMethod, double> key{ method, eta };
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto known = found.find(key); known != found.end())
    {
      return known->second;
    }
  }
  const double error = searchLargestPowError<T>(method, eta);
  const std::lock_guard<std::mutex> lock(mutex);
  found.emplace(key, error);
  return error;
}

template double largestPowError<float>(PowMethod, double);
template double largestPowError<double>(PowMethod, double);
}
