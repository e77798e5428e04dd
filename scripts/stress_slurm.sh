#!/usr/bin/env bash
#SBATCH --job-name=revdist-stress
#SBATCH --cpus-per-task=1
#SBATCH --time=12:00:00
#SBATCH --output=stress_shards/slurm_%A_%a.log
# A cluster audit (issue 7): each task of a Slurm job array runs one shard of
# the same seeded stream; `revdist stress --merge` combines them exactly.
# 10^8 cases = 33 families x N=3030304 cases each, e.g. in 1000 tasks:
#   mkdir -p stress_shards
#   jid=$(N=3030304 SEED=1 sbatch --parsable --array=1-1000 scripts/stress_slurm.sh)
#   sbatch --dependency=afterok:$jid --wrap "build/cli/revdist stress --merge stress_shards/shard_*.json --json > stress_shards/merged.json"
# Environment: N (cases per family), SEED, OUT (directory, default stress_shards),
# REVDIST (the binary), STRESS_ARGS (more stress options, e.g. "--exact-every 1000").
set -euo pipefail
: "${N:=10000}" "${SEED:=1}" "${OUT:=stress_shards}" "${STRESS_ARGS:=}"
m=${SLURM_ARRAY_TASK_COUNT:?submit with sbatch --array=1-M}
k=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))
mkdir -p "$OUT"
# shellcheck disable=SC2086
"${REVDIST:-build/cli/revdist}" stress --family all --n "$N" --seed "$SEED" --shard "$k/$m" --json $STRESS_ARGS \
  > "$OUT/shard_$k.json.tmp"
mv "$OUT/shard_$k.json.tmp" "$OUT/shard_$k.json"  # whole or not at all
