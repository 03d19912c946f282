#pragma once
// The result file of a lab test (HDF5, schema in docs/result_file.md): histories, every crack,
// the genesis and lab figures, the input text and seed, and optional snapshots of the discs
// with an XDMF file beside it so ParaView can open them. A biaxial series keeps each
// confinement's records in a group of its own (/confinement_K) and the Mohr-Coulomb envelope
// at the root. Written to a temporary name and
// renamed when complete: a failed run leaves no result file behind.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"
#include "lab/biaxial_test.hpp"
#include "lab/lab_test.hpp"

namespace H5 {
class H5File;
class Group;
}  // namespace H5

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

class ResultFile {
 public:
  // Opens the temporary file. The XDMF files (docs/result_file.md: NAME.xmf for the discs,
  // NAME_bonds.xmf for the bond network, NAME_cracks.xmf for the crack log) are written at
  // commit() when snapshots were taken (a biaxial series: the discs only).
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

  // The XDMF companions of a result file `target`: discs, bonds, cracks, smooth joints.
  static std::array<std::filesystem::path, 4> xdmf_paths(const std::filesystem::path& target);
  // The result file `target` and its companions, named after the option that gave it (`flag`,
  // "-o" or "output") for the output checks: all outputs of the command that writes them.
  static std::vector<NamedPath> outputs(const std::string& flag,
                                        const std::filesystem::path& target);

 private:
  AtomicOutput out_;
  std::unique_ptr<H5::H5File> file_;
  std::vector<JointSet> joint_sets_;  // [[test.joints]] as given
  void finish();

  std::string group_ = "/";  // where the snapshots of the run in hand go
  struct SnapshotIndex {
    std::string group;
    std::size_t index;  // within the group
    long step;
    double time;
    std::size_t discs;
    std::size_t bonds;   // of the bond network
    std::size_t joints;  // smooth joints
  };
  std::vector<SnapshotIndex> snapshots_;
  std::vector<double> scratch_;
  std::vector<std::int32_t> bond_count_;
  // The bond network of the run in hand: the pairs bonded at its first snapshot (sorted keys),
  // and per bond the mode (1 tension, 2 shear; 0 none) and loading time (s; -1 none) of its
  // latest failure, read from the crack log as it grows.
  std::string bond_group_;
  std::vector<std::uint64_t> bond_keys_;
  std::vector<std::int32_t> bond_mode_;
  std::vector<double> bond_time_;
  std::size_t cracks_seen_ = 0;
  std::size_t crack_count_ = 0;  // cracks of a single test, for its XDMF
  void snapshot_bonds(H5::Group& root, H5::Group& g, const World& world, double time);
  // The smooth joints at a snapshot: their pairs and sets at the run's first snapshot (in
  // `root`), their state at each.
  void snapshot_joints(H5::Group& root, H5::Group& g, const World& world, double time, bool first);
  std::string xdmf_joints(const std::string& h5) const;
};

}  // namespace cdem::lab
