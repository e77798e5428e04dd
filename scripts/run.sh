#!/usr/bin/env bash
# The README's first command: install, build, and run the main job on the
# bundled cases: the biarc trees (with their certified audit), the distance of
# every query of every model case, and the circle layer (fast vs certified).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
rd=./build/cli/revdist
echo "== revdist fit cases/models/paper_pairs.json --eps 1e-5 --audit"
$rd fit cases/models/paper_pairs.json --eps 1e-5 --audit
for f in cases/models/*.json cases/distance/*.json; do
  echo "== revdist distance $f"
  $rd distance "$f"
done
for f in cases/circles/coaxial.json cases/circles/villarceau.json cases/circles/meridian.json; do
  echo "== revdist circles $f --engine both"
  $rd circles "$f" --engine both
done
