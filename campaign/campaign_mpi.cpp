#include "campaign/campaign_mpi.hpp"

#include <chrono>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <thread>

#include <mpi.h>

namespace cdem::calib {

namespace {

// Worker -> master: "give me a run" carrying the previous run's record (empty the first time).
constexpr int kTagRequest = 1;
// Master -> worker: a task as JSON, or the order to stop.
constexpr int kTagTask = 2;
constexpr int kTagStop = 3;

void send_text(const std::string& text, int to, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

std::string receive_text(int from, int tag, MPI_Status& status) {
  MPI_Probe(from, tag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return text;
}

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession() {
  // Only the main thread calls MPI; the master's job thread only forks and waits.
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

void mpi_master(const MpiSession& session, RunQueue& queue, const std::filesystem::path& self) {
  std::exception_ptr local_error;
  std::jthread local([&] {
    try {
      while (auto task = queue.next()) queue.finish(execute_run(*task, self));
    } catch (...) {
      local_error = std::current_exception();
    }
  });

  int working = session.size() - 1;
  while (working > 0) {
    int pending = 0;
    MPI_Status status;
    // Polling with a sleep instead of a blocking receive: Open MPI busy-waits in MPI_Recv,
    // which would take a core from the jobs running on this node.
    MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &pending, &status);
    if (!pending) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    const std::string report = receive_text(status.MPI_SOURCE, kTagRequest, status);
    if (!report.empty()) queue.finish(record_from_json(nlohmann::json::parse(report)));
    if (auto task = queue.next()) {
      send_text(to_json(*task).dump(), status.MPI_SOURCE, kTagTask);
    } else {
      send_text("", status.MPI_SOURCE, kTagStop);
      --working;
    }
  }
  local.join();
  if (local_error) std::rethrow_exception(local_error);
}

void mpi_worker(const std::filesystem::path& self) {
  try {
    std::string report;
    for (;;) {
      send_text(report, 0, kTagRequest);
      MPI_Status status;
      const std::string task = receive_text(0, MPI_ANY_TAG, status);
      if (status.MPI_TAG == kTagStop) return;
      report = to_json(execute_run(task_from_json(nlohmann::json::parse(task)), self)).dump();
    }
  } catch (const std::exception& e) {
    std::cerr << "cdem campaign: worker failed: " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 4);
  }
}

}  // namespace cdem::calib
