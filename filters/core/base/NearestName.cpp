#include "NearestName.h"

#include <algorithm>
#include <numeric>

namespace shadelab
{
std::size_t editDistance(const std::string& a, const std::string& b)
{
  // Three rows of the dynamic programme: the one before the last (for swaps), the last, this.
  std::vector<std::size_t> beforeLast(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  std::iota(last.begin(), last.end(), std::size_t(0));
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t substitution = last[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({ last[j] + 1, row[j - 1] + 1, substitution });
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
      {
        row[j] = std::min(row[j], beforeLast[j - 2] + 1);
      }
    }
    std::swap(beforeLast, last);
    std::swap(last, row);
  }
  return last[b.size()];
}

std::string nearestName(const std::string& word, const std::vector<std::string>& names)
{
  const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
  std::string nearest;
  std::size_t best = allowed + 1;
  bool tied = false;
  for (const std::string& name : names)
  {
    const std::size_t distance = editDistance(word, name);
    tied = distance == best ? true : distance < best ? false : tied;
    if (distance < best)
    {
      best = distance;
      nearest = name;
    }
  }
  return tied ? "" : nearest;
}
}
