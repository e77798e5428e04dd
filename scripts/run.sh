#!/usr/bin/env bash
# The README's first command: install, build, and run the main job on the bundled cases.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
for f in cases/circles/*.json; do
  echo "== revdist circles $f --engine both"
  ./build/cli/revdist circles "$f" --engine both
done
