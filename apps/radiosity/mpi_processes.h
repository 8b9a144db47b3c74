#pragma once
// `mpirun -np N radiosity ...`: one run split among N processes (MPI ranks). Each method takes
// its share of the work through process_share.h (the voxel method a block of the direction pairs
// and of the first shot, the patch method rows of form factors and Jacobi's sweeps, the path
// tracer every N-th tile) and the shares are added in a fixed order; rank 0 alone writes outputs
// and speaks. Built without MPI, or started without mpirun, the tool runs as one process.

#include <radiosity/process_share.h>

#include <cstdint>
#include <vector>

namespace rad::cli {

class MpiProcesses {
 public:
  /// Starts MPI when this process was started by mpirun (the launcher's rank variables are
  /// set) and the tool was built with MPI; otherwise the run is one process.
  static void start(int& argc, char**& argv);
  /// Ends MPI after a run that exited with `status`: finalized after success, the whole job
  /// aborted with it otherwise (a rank that fails takes the others with it).
  static void finish(int status);
  /// This process's share of a split run (rank 0 of 1 alone).
  static ProcessShare share();
  static bool split() { return count() > 1; }
  static int rank();
  static int count();
  /// Bytes this process sent and received in sums so far.
  static uint64_t bytesCommunicated();
  /// Seconds this process spent in sums (sending, receiving, waiting for the others).
  static double secondsSumming();
  /// Every process's `seconds`, in rank order, at rank 0 (the others get theirs alone). Called by
  /// every process.
  static std::vector<double> gather(double seconds);
};

}  // namespace rad::cli
