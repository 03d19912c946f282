#pragma once
// Output files are written to a temporary name beside the target and renamed into place only
// when complete, so an interrupted or failed run never leaves a file that looks valid.
//
// The temporary name is "<target>.tmp<PID>". Every live temporary file is registered so that
// SIGINT, SIGTERM and SIGHUP remove it before the process dies of the signal
// (install_output_cleanup_on_signals); after a SIGKILL, the next AtomicOutput of the same target
// removes the temporary files whose process is gone.
//
// A command with several outputs (result, XDMF, summary, pictures) opens an OutputTransaction
// naming them: their AtomicOutputs then hand their finished temporary files to the transaction,
// which renames all of them at its commit() (with those signals blocked), so the outputs of one
// command appear all together or not at all.
#include <filesystem>
#include <string>
#include <vector>

namespace cdem {

class AtomicOutput {
 public:
  // Creates the target's folder if needed and clears stale temporary files of the target.
  explicit AtomicOutput(std::filesystem::path target);
  ~AtomicOutput();  // removes the temporary file unless commit() was called
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  // Where to write now.
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  // Renames the temporary file onto the target, or, when the target is an output of the open
  // OutputTransaction, hands the file to it.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  int slot_ = -1;  // in the signal-cleanup registry
  bool committed_ = false;
};

// The outputs of one command, renamed together. At most one is open at a time.
class OutputTransaction {
 public:
  explicit OutputTransaction(const std::vector<std::filesystem::path>& outputs);
  ~OutputTransaction();  // without commit(): removes every temporary file handed over
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // Renames every finished output into place.
  void commit();

 private:
  friend class AtomicOutput;
  struct Pending {
    std::filesystem::path temp, target;
    int slot;
  };
  bool holds(const std::filesystem::path& target) const;
  std::vector<std::filesystem::path> outputs_;  // absolute, normalised
  std::vector<Pending> pending_;
};

// A scratch path (a file, or a directory emptied of its registered files) that the cleanup
// signals remove too, for the life of the object; removing it otherwise is the owner's job.
class RemovedOnSignal {
 public:
  explicit RemovedOnSignal(const std::filesystem::path& path);
  ~RemovedOnSignal();
  RemovedOnSignal(const RemovedOnSignal&) = delete;
  RemovedOnSignal& operator=(const RemovedOnSignal&) = delete;

 private:
  int slot_;
};

// SIGINT, SIGTERM and SIGHUP remove every registered temporary file (then the registered
// directories), then end the process with the signal's default action (exit status 128 + signal
// in a shell). SIGXFSZ is ignored, so that a write beyond the file-size limit is an error cdem
// reports (exit 3) rather than a crash.
void install_output_cleanup_on_signals();

// The temporary name of `target` for process `pid`, and whether `name` is the temporary name of
// a file called `target_name` (then *pid is set).
std::filesystem::path temporary_name(const std::filesystem::path& target, long pid);
bool is_temporary_name(const std::string& name, const std::string& target_name, long* pid);

// Writes `text` to `target` atomically.
void write_text_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace cdem
