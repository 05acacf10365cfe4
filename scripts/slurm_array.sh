#!/bin/bash
# One Slurm array task runs one shard of a floornav batch: task K of an array 1-N runs
# `floornav batch ARGS... --shard K/N` into out/sweep/shard-K. Submit it from the repository (or
# wherever ARGS' paths are relative to) with the batch's arguments after the script, as in the
# README:
#   sbatch --array=1-16 --cpus-per-task=8 scripts/slurm_array.sh TEMPLATE.yaml --scen FILE.scen
# and join the shards with `floornav merge out/sweep/shard-* --out out/sweep/all`.
# The array must be 1-N with no gaps (N comes from SLURM_ARRAY_TASK_COUNT); `floornav` must be on
# the PATH that sbatch passes on.
#SBATCH --job-name=floornav-shard
#SBATCH --array=1-4
#SBATCH --cpus-per-task=1
set -euo pipefail
: "${SLURM_ARRAY_TASK_ID:?submit with sbatch --array=1-N}"
exec floornav batch "$@" --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}" \
  --jobs "${SLURM_CPUS_PER_TASK:-1}" --no-timing --out "out/sweep/shard-${SLURM_ARRAY_TASK_ID}"
