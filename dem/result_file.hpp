#pragma once
// The result file of a lab test (HDF5, schema in docs/result_file.md): histories, every crack,
// the genesis and lab figures, the input text and seed, and optional snapshots of the discs
// with an XDMF file beside it so ParaView can open them. A biaxial series keeps each
// confinement's records in a group of its own (/confinement_K) and the Mohr-Coulomb envelope
// at the root. Written to a temporary name and
// renamed when complete: a failed run leaves no result file behind.
#include <filesystem>
#include <memory>
#include <string>

#include "core/atomic_output.hpp"
#include "dem/biaxial_test.hpp"
#include "dem/lab_test.hpp"

namespace H5 {
class H5File;
}

namespace cdem::dem {

class ResultFile {
 public:
  // Opens the temporary file. The XDMF file (same name, extension .xmf) is written at
  // commit() when snapshots were taken.
  ResultFile(std::filesystem::path target, const LabTestInput& input);
  ~ResultFile();  // without commit(): closes and removes the temporary file
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;

  // Biaxial series: the records that follow (snapshots, then the run at commit) belong to
  // confinement k, group /confinement_k.
  void begin_confinement(std::size_t k, double sigma3);
  // Appends a snapshot of the discs (position, velocity, intact bonds per disc) taken at loading
  // step `step` and loading time `time` (s).
  void snapshot(const World& world, long step, double time);
  // Writes the histories, cracks and figures, closes the file and renames it into place.
  void commit(const LabTestResult& result);
  // The same for a biaxial series: one group per confinement, the envelope in /summary.
  void commit(const BiaxialSeries& series);

  std::filesystem::path xdmf_path() const;

 private:
  AtomicOutput out_;
  std::unique_ptr<H5::H5File> file_;
  void finish();

  std::string group_ = "/";  // where the snapshots of the run in hand go
  struct SnapshotIndex {
    std::string group;
    std::size_t index;  // within the group
    long step;
    double time;
    std::size_t discs;
  };
  std::vector<SnapshotIndex> snapshots_;
  std::vector<double> scratch_;
  std::vector<std::int32_t> bond_count_;
};

}  // namespace cdem::dem
