#!/usr/bin/env bash
# One machine: `revdist stress --family all` cut into M shards of the same seeded
# stream, run by GNU parallel across the cores, then merged exactly
# (`revdist stress --merge`). The merged JSON equals one unsharded run (times aside).
# usage: scripts/stress_parallel.sh N SEED [SHARDS (default nproc)] [OUT_DIR (default stress_shards)] [stress options...]
#   e.g. scripts/stress_parallel.sh 1000 1 2 /tmp/shards --exact-every 50
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:?N cases per family}
seed=${2:?seed}
m=${3:-$(nproc)}
out=${4:-stress_shards}
shift $(($# < 4 ? $# : 4))
rd=${REVDIST:-./build/cli/revdist}
mkdir -p "$out"
rm -f "$out"/shard_*.json
# Each shard writes a temporary file and renames it when done: no half-written shard is ever merged.
seq 1 "$m" | parallel --halt now,fail=1 -j "$m" \
  "$rd stress --family all --n $n --seed $seed --shard {}/$m --json $* > $out/shard_{}.json.tmp && mv $out/shard_{}.json.tmp $out/shard_{}.json"
"$rd" stress --merge "$out"/shard_*.json --json > "$out/merged.json.tmp" && mv "$out/merged.json.tmp" "$out/merged.json"
"$rd" stress --merge "$out"/shard_*.json
