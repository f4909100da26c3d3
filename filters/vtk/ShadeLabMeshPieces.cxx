#include "ShadeLabMeshPieces.h"

#include "ShadeLabMeshExtent.h"
#include "ShadeLabPieceExchange.h"

#include "vtkAlgorithm.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <new>
#include <numeric>
#include <stdexcept>

namespace shadelab
{
namespace
{
constexpr int firstCopiesTag = 7351;
}

const char* const anotherProcessFailed = "another process failed on its piece (see its error), so this one stops too";

bool saysAnotherProcessFailed(const std::string& error)
{
  return error.find("another process") != std::string::npos;
}

MeshExtent wholeMeshExtent(vtkMultiProcessController* controller, vtkPolyData* piece)
{
  // An empty piece's box is VTK's empty range, which the others' replace.
  PointBox box = piece->GetNumberOfPoints() > 0 ? finitePointBox(piece)
                                                : PointBox{ glm::dvec3(VTK_DOUBLE_MAX), glm::dvec3(VTK_DOUBLE_MIN) };
  if (processCount(controller) > 1)
  {
    const PointBox mine = box;
    controller->AllReduce(&mine.low[0], &box.low[0], 3, vtkCommunicator::MIN_OP);
    controller->AllReduce(&mine.high[0], &box.high[0], 3, vtkCommunicator::MAX_OP);
  }
  return extentOfBox(box);
}

std::size_t distinctIdCount(vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids)
{
  std::vector<vtkIdType> all = allGather(controller, ids);
  std::sort(all.begin(), all.end());
  return static_cast<std::size_t>(std::unique(all.begin(), all.end()) - all.begin());
}

std::vector<double> valuesByDistinctId(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids, const std::vector<double>& values)
{
  if (ids.size() != values.size())
  {
    throw std::invalid_argument(
      "valuesByDistinctId: " + std::to_string(ids.size()) + " ids for " + std::to_string(values.size()) + " values");
  }
  const std::vector<vtkIdType> allIds = allGather(controller, ids);
  const std::vector<double> allValues = allGather(controller, values);
  std::vector<std::size_t> order(allIds.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return allIds[a] < allIds[b]; });
  std::vector<double> distinct;
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    if (k == 0 || allIds[order[k]] != allIds[order[k - 1]])
    {
      distinct.push_back(allValues[order[k]]);
    }
  }
  return distinct;
}

std::vector<double> valuesAtEveryPoint(vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids,
  const std::vector<double>& values, int components, vtkIdType points)
{
  const std::size_t width = static_cast<std::size_t>(components);
  if (values.size() != ids.size() * width)
  {
    throw std::invalid_argument("valuesAtEveryPoint: " + std::to_string(ids.size()) + " ids for " +
      std::to_string(values.size()) + " values of " + std::to_string(components));
  }
  const std::vector<vtkIdType> allIds = allGather(controller, ids);
  const std::vector<double> allValues = allGather(controller, values);
  std::vector<double> everyPoint;
  bool allocated = true;
  try
  {
    everyPoint.resize(static_cast<std::size_t>(points) * width);
  }
  catch (const std::bad_alloc&)
  {
    allocated = false;
  }
  if (!everyProcessHolds(controller, allocated)) // so that every process stops alike
  {
    throw std::runtime_error("out of memory for the whole mesh's values (" + std::to_string(points) + " points)");
  }
  for (std::size_t k = 0; k < allIds.size(); ++k)
  {
    std::copy_n(&allValues[k * width], width, &everyPoint[static_cast<std::size_t>(allIds[k]) * width]);
  }
  return everyPoint;
}

std::vector<bool> firstCopies(vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids)
{
  const int processes = processCount(controller);
  // Each id's first place in the piece; each id, once, in ascending order, to the process that
  // owns it (ownerOf).
  std::vector<std::size_t> byId;
  std::vector<std::vector<vtkIdType>> sent(static_cast<std::size_t>(processes));
  auto firstOfItsId = [&](std::size_t k) { return k == 0 || ids[byId[k]] != ids[byId[k - 1]]; };
  agreedStep(controller,
    [&]
    {
      byId.resize(ids.size());
      std::iota(byId.begin(), byId.end(), std::size_t(0));
      std::stable_sort(byId.begin(), byId.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
      for (std::size_t k = 0; k < byId.size(); ++k)
      {
        if (firstOfItsId(k))
        {
          sent[ownerOf(ids[byId[k]], processes)].push_back(ids[byId[k]]);
        }
      }
    });
  const std::vector<std::vector<vtkIdType>> received = swapWithEvery(controller, std::move(sent), firstCopiesTag);
  // The owner answers each process, for each id it sent, whether no earlier process sent it:
  // the ascending lists merged, ties taken in process order.
  std::vector<std::vector<unsigned char>> answers(received.size());
  agreedStep(controller,
    [&]
    {
      for (std::size_t p = 0; p < received.size(); ++p)
      {
        answers[p].resize(received[p].size());
      }
      forEachIdReceived(received,
        [&](vtkIdType, const std::vector<std::pair<std::size_t, std::size_t>>& holders)
        {
          for (const auto& [p, index] : holders)
          {
            answers[p][index] = p == holders.front().first ? 1 : 0; // the first process to hold it
          }
        });
    });
  const std::vector<std::vector<unsigned char>> answered =
    swapWithEvery(controller, std::move(answers), firstCopiesTag + 2);
  // The answers come in the order the ids went: walked again, each owner's in turn.
  std::vector<bool> first;
  agreedStep(controller,
    [&]
    {
      std::vector<std::size_t> next(answered.size(), 0);
      first.assign(ids.size(), false);
      for (std::size_t k = 0; k < byId.size(); ++k)
      {
        if (firstOfItsId(k))
        {
          const std::size_t owner = ownerOf(ids[byId[k]], processes);
          first[byId[k]] = next[owner] < answered[owner].size() && answered[owner][next[owner]++] != 0;
        }
      }
    });
  return first;
}

vtkIdType wholePointCount(vtkMultiProcessController* controller, const std::vector<vtkIdType>& pieceIds)
{
  const vtkIdType largest = pieceIds.empty() ? -1 : *std::max_element(pieceIds.begin(), pieceIds.end());
  const std::vector<vtkIdType> all = allGather(controller, std::vector<vtkIdType>{ largest });
  return *std::max_element(all.begin(), all.end()) + 1;
}

std::string firstText(vtkMultiProcessController* controller, const std::string& text)
{
  std::vector<vtkIdType> lengths;
  const std::vector<char> all = allGather(controller, std::vector<char>(text.begin(), text.end()), &lengths);
  const auto first = std::find_if(lengths.begin(), lengths.end(), [](vtkIdType length) { return length > 0; });
  if (first == lengths.end())
  {
    return "";
  }
  const vtkIdType start = std::accumulate(lengths.begin(), first, vtkIdType(0));
  return std::string(all.begin() + start, all.begin() + start + *first);
}

int agreedOutcome(vtkMultiProcessController* controller, vtkAlgorithm* filter, vtkPolyData* output, bool succeeded)
{
  const std::vector<int> all = allGather(controller, std::vector<int>{ succeeded ? 1 : 0 });
  if (std::find(all.begin(), all.end(), 0) == all.end())
  {
    return 1;
  }
  if (succeeded)
  {
    output->Initialize();
    vtkErrorWithObjectMacro(filter, << anotherProcessFailed);
  }
  return 0;
}

bool everyProcessHolds(vtkMultiProcessController* controller, bool mine)
{
  int held = mine ? 1 : 0;
  if (processCount(controller) > 1)
  {
    const int local = held;
    controller->AllReduce(&local, &held, 1, vtkCommunicator::MIN_OP);
  }
  return held == 1;
}
}
