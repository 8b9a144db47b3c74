#include "mpi_processes.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <vector>

#ifdef RADIOSITY_HAS_MPI
#include <mpi.h>
#endif

namespace rad::cli {

namespace {

int worldRank = 0, worldCount = 1;
uint64_t communicated = 0;
double summing = 0.0;  // seconds in sums: sending, receiving and waiting for the others

#ifdef RADIOSITY_HAS_MPI
bool startedByLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name)) return true;
  return false;
}

// The arrays summed along a binary tree of a fixed shape (rank r + s into rank r for s = 1, 2,
// 4, ..., r a multiple of 2s), then the sum broadcast from rank 0: log2(ranks) steps instead of
// ranks - 1 at rank 0, and the same sum, bit for bit, for a given number of ranks whatever their
// timing (MPI_Allreduce leaves the order to the implementation). Sent in chunks of at most
// 2^28 floats (a count is an int).
void sumInFixedTree(std::span<float> values) {
  const auto start = std::chrono::steady_clock::now();
  constexpr size_t kChunk = size_t(1) << 28;
  std::vector<float> incoming;
  for (size_t at = 0; at < values.size(); at += kChunk) {
    const std::span<float> chunk = values.subspan(at, std::min(kChunk, values.size() - at));
    const int n = int(chunk.size());
    const uint64_t bytes = chunk.size() * sizeof(float);
    for (int step = 1; step < worldCount; step *= 2) {
      if (worldRank % (2 * step) == step) {
        MPI_Send(chunk.data(), n, MPI_FLOAT, worldRank - step, 0, MPI_COMM_WORLD);
        communicated += bytes;
        break;
      }
      if (worldRank % (2 * step) == 0 && worldRank + step < worldCount) {
        incoming.resize(chunk.size());
        MPI_Recv(incoming.data(), n, MPI_FLOAT, worldRank + step, 0, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        for (size_t i = 0; i < chunk.size(); ++i) chunk[i] += incoming[i];
        communicated += bytes;
      }
    }
    MPI_Bcast(chunk.data(), n, MPI_FLOAT, 0, MPI_COMM_WORLD);
    communicated += bytes;
  }
  summing += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Integers summed by MPI_Allreduce, whose order does not matter for them; in chunks of at most
// 2^28 (a count is an int). Counted as sent to the tree's root and back.
void sumIntegersInPlace(std::span<int64_t> values) {
  const auto start = std::chrono::steady_clock::now();
  constexpr size_t kChunk = size_t(1) << 28;
  for (size_t at = 0; at < values.size(); at += kChunk) {
    const std::span<int64_t> chunk = values.subspan(at, std::min(kChunk, values.size() - at));
    MPI_Allreduce(MPI_IN_PLACE, chunk.data(), int(chunk.size()), MPI_INT64_T, MPI_SUM,
                  MPI_COMM_WORLD);
    communicated += 2 * chunk.size() * sizeof(int64_t);
  }
  summing += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every rank's bytes, concatenated in rank order, in every rank (a rank's part at most 2 GB: an
// int count).
std::vector<char> gatherInRankOrder(std::span<const char> bytes) {
  const auto start = std::chrono::steady_clock::now();
  const int mine = int(bytes.size());
  std::vector<int> counts(static_cast<size_t>(worldCount), 0);
  std::vector<int> offsets(static_cast<size_t>(worldCount), 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<char> all(size_t(offsets.back()) + size_t(counts.back()));
  MPI_Allgatherv(bytes.data(), mine, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR,
                 MPI_COMM_WORLD);
  communicated += all.size();
  summing += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return all;
}
#endif

}  // namespace

void MpiProcesses::start(int& argc, char**& argv) {
#ifdef RADIOSITY_HAS_MPI
  if (!startedByLauncher()) return;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &worldRank);
  MPI_Comm_size(MPI_COMM_WORLD, &worldCount);
#else
  (void)argc;
  (void)argv;
#endif
}

void MpiProcesses::finish(int status) {
#ifdef RADIOSITY_HAS_MPI
  int started = 0;
  MPI_Initialized(&started);
  if (!started) return;
  if (status != 0) MPI_Abort(MPI_COMM_WORLD, status);
  MPI_Finalize();
#else
  (void)status;
#endif
}

ProcessShare MpiProcesses::share() {
  ProcessShare share;
  share.rank = worldRank;
  share.count = worldCount;
#ifdef RADIOSITY_HAS_MPI
  if (worldCount > 1) {
    share.sumAll = sumInFixedTree;
    share.sumIntegers = sumIntegersInPlace;
    share.gatherAll = gatherInRankOrder;
  }
#endif
  return share;
}

int MpiProcesses::rank() {
  return worldRank;
}

int MpiProcesses::count() {
  return worldCount;
}

uint64_t MpiProcesses::bytesCommunicated() {
  return communicated;
}

double MpiProcesses::secondsSumming() {
  return summing;
}

std::vector<double> MpiProcesses::gather(double seconds) {
  std::vector<double> all(size_t(worldCount), seconds);
#ifdef RADIOSITY_HAS_MPI
  if (worldCount > 1)
    MPI_Gather(&seconds, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
#endif
  if (worldRank != 0) all.assign(1, seconds);
  return all;
}

}  // namespace rad::cli
