#pragma once
// The summary of `cdem run` (JSON, docs/lab_tests.md "Summary"): one lab test, or the series of a
// biaxial test. Shared by the command line and the Python module so both report the same fields
// and the same numbers.
#include <nlohmann/json.hpp>

#include "lab/biaxial_test.hpp"
#include "lab/lab_test.hpp"

namespace cdem::apps {

// The summary of one run: figures in the units their field names carry (MPa, GPa, kN/m, s).
nlohmann::ordered_json summary_json(const dem::LabTestResult& r, const dem::LabTestInput& in);
// The series of a biaxial test: the envelope, then each confinement's own summary.
nlohmann::ordered_json series_json(const dem::BiaxialSeries& series, const dem::LabTestInput& in);

}  // namespace cdem::apps
