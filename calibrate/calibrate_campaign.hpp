#pragma once
// The simulator of `cdem calibrate`: every batch of a strategy becomes campaigns
// (campaign/campaign.hpp) of `cdem run` jobs, one campaign per test type and specimen, whose
// factors are the free material keys and whose explicit design holds the batch's points; the
// campaigns of a batch run side by side. So the runs go in parallel (-j), a calibration interrupted
// and started again re-uses every completed run, and a failed run is a failed outcome. Specimens
// are made first by a campaign of `cdem generate` jobs whose factor is the generator's seed.
#include <filesystem>
#include <map>

#include "calibrate/calibrate_simulator.hpp"

namespace cdem::calib {

class CampaignSimulator : public Simulator {
 public:
  // `output_dir` holds specimens/ and stages/; `jobs` as `cdem campaign -j` (0 = one per core).
  CampaignSimulator(const CalibrationInput& input, std::filesystem::path output_dir, int jobs,
                    bool verbose);

  // Generates the specimens of these seeds (those not already generated). Throws RunError when
  // a specimen cannot be generated: no calibration can go on without it.
  void make_specimens(const std::vector<std::uint64_t>& seeds);
  int specimens_generated() const { return generated_; }

  std::vector<SimulationOutcome> run(const std::string& stage,
                                     const std::vector<SimulationPoint>& points) override;

 private:
  // The specimen of input.tests[test] made with `seed`.
  std::filesystem::path specimen_file(std::size_t test, std::uint64_t seed) const;
  void generate(std::size_t test, const std::vector<std::uint64_t>& seeds);

  const CalibrationInput& input_;
  std::filesystem::path output_dir_;
  int jobs_;
  bool verbose_;
  int generated_ = 0;
  std::map<std::pair<std::size_t, std::uint64_t>, std::filesystem::path> specimens_;
};

}  // namespace cdem::calib
