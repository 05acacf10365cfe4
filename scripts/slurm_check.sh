#!/usr/bin/env bash
# The README's Slurm job array, run for real on a one-node Slurm cluster on this machine, and its
# merged result compared with the same batch run in one go: results.jsonl, aggregate.json and
# sweep.json must be equal byte for byte.
#
#   scripts/slurm_check.sh [BUILD_DIR]      (as root; default BUILD_DIR: build)
#
# Installs Debian's slurmctld, slurmd and slurm-client when missing. The cluster lives in a
# temporary folder (configuration, state, spool, logs) with no munge (auth/none) and its own ports;
# both daemons are stopped when the script ends, however it ends. The recipe is not copied: it is
# the README's code block that submits scripts/slurm_array.sh, taken from README.md and run as it
# stands in a work folder that sees the repository's scripts/, scenarios/ and tests/.
# Any failure: exit status 1 and a last line "slurm_check: FAILED: <reason>".
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$repo/build}" 2>/dev/null && pwd) || build=${1:-$repo/build}
started=$SECONDS

fail() {
  echo "slurm_check: FAILED: $*" >&2
  exit 1
}
[ -x "$build/floornav" ] || fail "no floornav executable in $build (build it first)"
[ "$(id -u)" -eq 0 ] || fail "run as root (slurmd starts the jobs as the submitting user)"

# --- Slurm, from Debian ---------------------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
  ! command -v sbatch >/dev/null; then
  echo "slurm_check: installing slurmctld slurmd slurm-client"
  apt-get update -qq || fail "apt-get update failed"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    slurmctld slurmd slurm-client >/dev/null || fail "apt-get install of Slurm failed"
fi

# --- a one-node cluster on localhost --------------------------------------------------------
tmp=$(mktemp -d /tmp/floornav-slurm.XXXXXX)
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ "$status" -eq 0 ]; then rm -rf "$tmp"; else echo "slurm_check: files kept in $tmp" >&2; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

show_logs() {
  for f in "$tmp"/slurmctld.log "$tmp"/slurmd.log "$tmp"/work/slurm-*.out; do
    [ -f "$f" ] || continue
    echo "----- $f (last 40 lines)" >&2
    tail -n 40 "$f" >&2
  done
}

host=$(hostname -s)
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/work"
cat >"$tmp/slurm.conf" <<EOF
ClusterName=floornavcheck
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/none
CredType=cred/none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdParameters=config_overrides
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MailProg=/bin/true
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=check Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$tmp/slurm.conf

slurmctld -D -c -f "$SLURM_CONF" >"$tmp/slurmctld.stderr" 2>&1 &
pids+=($!)
slurmd -D -N "$host" -f "$SLURM_CONF" >"$tmp/slurmd.stderr" 2>&1 &
pids+=($!)

deadline=$((SECONDS + 60))
until [ "$(sinfo -h -N -o '%t' 2>/dev/null | head -n 1)" = idle ]; do
  for pid in "${pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || {
      cat "$tmp"/*.stderr >&2
      show_logs
      fail "a Slurm daemon exited during start-up (logs above)"
    }
  done
  if [ "$SECONDS" -ge "$deadline" ]; then
    sinfo -N >&2 || true
    show_logs
    fail "the node did not become idle within 60 s (logs above)"
  fi
  sleep 1
done
echo "slurm_check: one-node cluster up ($host, 2 CPUs) after $((SECONDS - started)) s"

# --- the README's recipe --------------------------------------------------------------------
# The fenced block of README.md that submits scripts/slurm_array.sh (indentation removed).
awk '
  /^[ \t]*```/ { if (inside) { if (keep) { printf "%s", block; exit } inside = 0; next }
                 inside = 1; block = ""; keep = 0; next }
  inside { line = $0; sub(/^[ \t]+/, "", line); block = block line "\n"
           if (line ~ /sbatch/ && line ~ /scripts\/slurm_array\.sh/) keep = 1 }
' "$repo/README.md" >"$tmp/recipe.sh"
[ -s "$tmp/recipe.sh" ] || fail "README.md has no code block that submits scripts/slurm_array.sh"
echo "slurm_check: running the README's recipe:"
sed 's/^/  /' "$tmp/recipe.sh"

# The batch arguments of the recipe: what follows scripts/slurm_array.sh in its sbatch command.
joined=$(sed -e ':a' -e '/\\$/N; s/\\\n//; ta' "$tmp/recipe.sh" | grep 'scripts/slurm_array\.sh')
batch_args=${joined#*scripts/slurm_array.sh}
batch_args=${batch_args%)*}
eval "set -- $batch_args"
[ "$#" -gt 0 ] || fail "the recipe passes no batch arguments to scripts/slurm_array.sh"

ln -s "$repo/scripts" "$repo/scenarios" "$repo/tests" "$tmp/work/"
export PATH="$build:$PATH"
(cd "$tmp/work" && bash -euo pipefail "$tmp/recipe.sh") >"$tmp/submit.log" 2>&1 || {
  cat "$tmp/submit.log" >&2
  show_logs
  fail "the README's recipe failed to submit (output above)"
}

deadline=$((SECONDS + 300))
while [ -n "$(squeue -h -o '%i' 2>/dev/null)" ]; do
  if squeue -h -o '%r' 2>/dev/null | grep -q DependencyNeverSatisfied; then
    squeue >&2 || true
    show_logs
    fail "an array task failed, so the merge job can never start (logs above)"
  fi
  if [ "$SECONDS" -ge "$deadline" ]; then
    squeue >&2 || true
    show_logs
    fail "the jobs did not finish within 300 s"
  fi
  sleep 2
done
# No accounting database: the finished jobs' states come from slurmctld (kept MinJobAge s).
states=$(scontrol -o show job 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort | uniq -c)
if [ -z "$states" ] || echo "$states" | grep -v -q 'JobState=COMPLETED'; then
  echo "$states" >&2
  show_logs
  fail "not every job of the recipe completed (states above)"
fi
echo "slurm_check: jobs finished after $((SECONDS - started)) s:" $states
[ -f "$tmp/work/out/sweep/all/results.jsonl" ] ||
  fail "the recipe's merge wrote no out/sweep/all/results.jsonl"

# --- the same batch in one go, and the comparison -------------------------------------------
(cd "$tmp/work" && floornav batch "$@" --no-timing --out "$tmp/whole") >"$tmp/whole.log" 2>&1 || {
  cat "$tmp/whole.log" >&2
  fail "the unsharded batch failed (output above)"
}
for f in results.jsonl aggregate.json sweep.json; do
  cmp -s "$tmp/work/out/sweep/all/$f" "$tmp/whole/$f" || {
    diff "$tmp/work/out/sweep/all/$f" "$tmp/whole/$f" | head -n 20 >&2 || true
    fail "merged $f differs from the unsharded batch's"
  }
done
shards=$(ls -d "$tmp"/work/out/sweep/shard-* | wc -l)
lines=$(wc -l <"$tmp/whole/results.jsonl")
echo "slurm_check: OK: $shards shards merged equal one batch ($lines cases; results.jsonl," \
  "aggregate.json, sweep.json byte for byte) in $((SECONDS - started)) s"
