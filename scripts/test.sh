#!/usr/bin/env bash
# The README's second command: build (incrementally) and run the default test
# suite. Long stress runs carry the ctest label "stress" and are left out here;
# run them with: ctest --test-dir build -L stress
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build -LE stress --output-on-failure -j"$(nproc)" --timeout 900
