#!/usr/bin/env bash
# The stability suite (label `stability`, docs/stability.md): hard cases of issue 6 run as real
# lab tests on small specimens. A few minutes on 2 cores; run after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
ctest --test-dir build -L stability --output-on-failure -j 2
