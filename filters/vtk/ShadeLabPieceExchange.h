#pragma once
// What the pieces of a split mesh exchange with (ShadeLabWholeMesh.cxx, ShadeLabMeshPieces.cxx,
// ShadeLabPieceNormals.cxx): every process's values gathered, on every process or on the first
// only; lists swapped pairwise; ids sent to the process that owns them.
#include "ShadeLabMeshPieces.h"
#include "ShadeLabWholeMesh.h"

#include "vtkMultiProcessController.h"
#include "vtkType.h"

#include <functional>
#include <limits>
#include <new>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shadelab
{
inline int processCount(vtkMultiProcessController* controller)
{
  return controller ? controller->GetNumberOfProcesses() : 1;
}

inline bool isFirstProcess(vtkMultiProcessController* controller)
{
  return !controller || controller->GetLocalProcessId() == 0;
}

/// Whether this process receives what is gathered `where`.
inline bool receives(vtkMultiProcessController* controller, WholeMeshOn where)
{
  return where == WholeMeshOn::EveryProcess || isFirstProcess(controller);
}

/// Every process's `mine`, one after another in process order, on every process or on the
/// first only (the others get nothing); counts[p] is process p's size, on every process.
template<typename T>
std::vector<T> gathered(vtkMultiProcessController* controller, const std::vector<T>& mine, WholeMeshOn where,
  std::vector<vtkIdType>* counts = nullptr)
{
  const int processes = processCount(controller);
  std::vector<vtkIdType> lengths(processes, static_cast<vtkIdType>(mine.size()));
  if (processes == 1)
  {
    if (counts)
    {
      *counts = lengths;
    }
    return mine;
  }
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  controller->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> offsets(processes, 0);
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  const vtkIdType total = offsets.back() + lengths.back();
  // MPI counts are ints: every process finds the same total, and stops alike.
  if (total > std::numeric_limits<int>::max())
  {
    throw std::overflow_error("the mesh is too large to gather: " + std::to_string(total) +
      " values in one exchange, more than MPI's 2^31 - 1");
  }
  if (counts)
  {
    *counts = lengths;
  }
  std::vector<T> all;
  bool allocated = true;
  try
  {
    all.resize(receives(controller, where) ? static_cast<std::size_t>(total) : 0);
  }
  catch (const std::bad_alloc&)
  {
    allocated = false;
  }
  if (!everyProcessHolds(controller, allocated)) // so that every process stops alike
  {
    throw std::runtime_error("out of memory gathering the mesh's pieces (" + std::to_string(total) + " values)");
  }
  const int exchanged = where == WholeMeshOn::EveryProcess
    ? controller->AllGatherV(mine.data(), all.data(), length, lengths.data(), offsets.data())
    : controller->GatherV(mine.data(), all.data(), length, lengths.data(), offsets.data(), 0);
  if (exchanged == 0)
  {
    throw std::runtime_error("gathering the mesh's pieces failed (MPI's gather)");
  }
  return all;
}

template<typename T>
std::vector<T> allGather(
  vtkMultiProcessController* controller, const std::vector<T>& mine, std::vector<vtkIdType>* counts = nullptr)
{
  return gathered(controller, mine, WholeMeshOn::EveryProcess, counts);
}

/// Runs a step that holds no exchange; where it fails on any process, throws on every process:
/// its own message where it failed, anotherProcessFailed elsewhere. So no process waits in the
/// next exchange for one that has left.
template<typename Step>
void agreedStep(vtkMultiProcessController* controller, Step step)
{
  std::string failure;
  try
  {
    step();
  }
  catch (const std::exception& error)
  {
    failure = *error.what() ? error.what() : "a step of the split mesh's work failed";
  }
  if (!everyProcessHolds(controller, failure.empty()))
  {
    throw std::runtime_error(failure.empty() ? anotherProcessFailed : failure);
  }
}

/// Sends `mine` to process `other` and returns what it sent back: both call it at the same step.
/// The lower process sends first, so that two blocking sends never wait for each other; and
/// every process meets the others in the order of their ranks, so that no chain of waits closes.
template<typename T>
std::vector<T> swapWith(vtkMultiProcessController* controller, int other, const std::vector<T>& mine, int tag)
{
  const vtkIdType myLength = static_cast<vtkIdType>(mine.size());
  vtkIdType theirLength = 0;
  std::vector<T> theirs;
  bool exchanged = true;
  auto send = [&]
  {
    exchanged = exchanged && controller->Send(&myLength, 1, other, tag) != 0 &&
      (myLength == 0 || controller->Send(mine.data(), myLength, other, tag + 1) != 0);
  };
  auto receive = [&]
  {
    exchanged = exchanged && controller->Receive(&theirLength, 1, other, tag) != 0;
    theirs.resize(static_cast<std::size_t>(exchanged ? theirLength : 0));
    exchanged = exchanged && (theirs.empty() || controller->Receive(theirs.data(), theirLength, other, tag + 1) != 0);
  };
  if (controller->GetLocalProcessId() < other)
  {
    send();
    receive();
  }
  else
  {
    receive();
    send();
  }
  if (!exchanged)
  {
    throw std::runtime_error("exchanging values between two processes failed (MPI's send or receive)");
  }
  return theirs;
}

/// Calls exchange(other) for every other process, in the order swapWith needs.
template<typename Exchange>
void forEveryOtherProcess(vtkMultiProcessController* controller, Exchange exchange)
{
  if (processCount(controller) == 1)
  {
    return;
  }
  for (int other = 0; other < processCount(controller); ++other)
  {
    if (other != controller->GetLocalProcessId())
    {
      exchange(other);
    }
  }
}

/// For each process, what `sent` had for it (sent[p] for process p) and it had for this one: each
/// pair of processes swaps its lists (swapWith), and this process's own list stays (a collective
/// call).
template<typename T>
std::vector<std::vector<T>> swapWithEvery(
  vtkMultiProcessController* controller, std::vector<std::vector<T>> sent, int tag)
{
  std::vector<std::vector<T>> received(sent.size());
  const std::size_t me = static_cast<std::size_t>(controller ? controller->GetLocalProcessId() : 0);
  received[me] = std::move(sent[me]);
  forEveryOtherProcess(controller,
    [&](int other)
    {
      const std::size_t p = static_cast<std::size_t>(other);
      received[p] = swapWith(controller, other, sent[p], tag);
      std::vector<T>().swap(sent[p]); // sent: no longer held beside what comes in
    });
  return received;
}

/// The process that owns a global id in the exchanges that split the ids among the processes.
inline std::size_t ownerOf(vtkIdType id, int processes)
{
  return static_cast<std::size_t>((id % processes + processes) % processes);
}

/// Merges the ids the processes sent their owner (received[p] from process p, each id once, in
/// strictly ascending order, which the callers guarantee): calls visit(id, holders) for each id,
/// ascending, with the processes that sent it and where it is in each one's list ((process,
/// index) pairs, in process order).
template<typename Visit>
void forEachIdReceived(const std::vector<std::vector<vtkIdType>>& received, Visit visit)
{
  using Cursor = std::pair<vtkIdType, std::size_t>; // (id, process)
  std::priority_queue<Cursor, std::vector<Cursor>, std::greater<Cursor>> heads;
  std::vector<std::size_t> at(received.size(), 0);
  for (std::size_t p = 0; p < received.size(); ++p)
  {
    if (!received[p].empty())
    {
      heads.push({ received[p][0], p });
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> holders;
  while (!heads.empty())
  {
    const vtkIdType id = heads.top().first;
    holders.clear();
    while (!heads.empty() && heads.top().first == id)
    {
      const std::size_t p = heads.top().second;
      heads.pop();
      holders.emplace_back(p, at[p]);
      if (++at[p] < received[p].size())
      {
        heads.push({ received[p][at[p]], p }); // a later id: it pops after this one's holders
      }
    }
    visit(id, holders);
  }
}
}
