#!/usr/bin/env bash
# The default test run (labels `unit` and `bad_input`): what CI runs. Long runs have their own
# labels:
#   ctest --test-dir build -L validation     (long physics validation)
set -euo pipefail
cd "$(dirname "$0")/.."
ctest --test-dir build -L 'unit|bad_input' --output-on-failure -j 2
