#pragma once
// demcal-dem batch over MPI ranks (mpirun -np N demcal-dem batch ...).
//
// Rank 0 hands out the design points one at a time and writes the one result
// file; ranks 1..N-1 run them, each point in a child process so that a crash
// costs that point only (recorded as failed, as in a local batch). Rank 0
// stores every result as it arrives, so a rank or a job that dies loses only
// the points that were running, and a rerun resumes. Specimens are packed
// first, one per rank at a time, into each rank's cache folder.
#include "demcal/jobs/batch.hpp"

namespace demcal::jobs {

// True when this build has MPI and the process was started by an MPI
// launcher (mpirun, srun); checked from the launcher's environment, before
// MPI is initialised.
bool started_by_mpi_launcher();

// Initialises MPI for its lifetime (finalises at the end).
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

// Call on every rank (size >= 2). Rank 0 returns the batch summary; the
// other ranks return an empty one. A setup error (bad scene, design, ...)
// is thrown on rank 0 only; the other ranks then return, and must exit with
// status 0 (rank 0's exit carries the failure), so the launcher does not
// abort the job before rank 0 has said why.
BatchSummary run_batch_mpi(const BatchOptions& options, const MpiSession& mpi);

}  // namespace demcal::jobs
