#pragma once
// Execution under `mpirun -np K cdem campaign ...`: rank 0 is the master, handing out runs one at
// a time to whichever worker asks (so fast and slow runs balance themselves) and gathering the
// records; ranks 1..K-1 are workers. The master also runs jobs itself, one at a time in a second
// thread, so K ranks run K jobs at once. Every run is still a child process of its rank. Tasks
// and records travel as JSON, so workers need no access to the campaign file; run directories
// must be on a file system the ranks share (or at the same path on every node).
#include <filesystem>

#include "campaign/campaign_queue.hpp"

namespace cdem::calib {

// True when this process was started by an MPI launcher (Open MPI, PMIx or PMI environments).
// Only then is MPI initialised: a plain `cdem campaign` never touches the MPI runtime.
bool launched_by_mpi();

// MPI_Init_thread on construction, MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
};

// Rank 0: serves the queue to the workers (and to its own job thread) until it is empty and every
// worker has been told to stop. With an empty queue it only stops the workers, which is how a
// master that failed to read the campaign releases them.
void mpi_master(const MpiSession& session, RunQueue& queue, const std::filesystem::path& self);

// Ranks > 0: ask, run, report, until told to stop. A campaign-level failure on a worker (not a
// failing job) aborts the whole MPI job rather than leaving the master waiting.
void mpi_worker(const std::filesystem::path& self);

}  // namespace cdem::calib
