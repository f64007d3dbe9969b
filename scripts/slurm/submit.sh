#!/usr/bin/env bash
# Runs a slender sweep on a Slurm cluster: a job array computes the shards (`--shard i/n`) into
# one store each, then a dependent job merges the stores (`slender merge`) and reruns the sweep
# on the merged store, which computes nothing and writes the report.
#
# Usage:  scripts/slurm/submit.sh SHARDS OUT_DIR SLENDER_ARGS...
# e.g.    scripts/slurm/submit.sh 25 /scratch/$USER/bend-twist-full bend-twist --preset full
#         scripts/slurm/submit.sh 8 /scratch/$USER/validate-full validate --preset full
#
# OUT_DIR must be on a file system every node sees. The binary is $SLENDER_BIN (default:
# target/release/slender of this checkout; build it first with `cargo build --release`).
# Resources per shard: edit the #SBATCH lines of shard.sbatch, or pass SBATCH_* variables.
# Rerunning this script after a failure or a time-out resumes: finished cases stay in the stores.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 SHARDS OUT_DIR SLENDER_ARGS..." >&2
  exit 2
fi
SHARDS=$1
OUT=$2
shift 2
case "$SHARDS" in
  '' | *[!0-9]* | 0) echo "SHARDS = '$SHARDS': must be an integer >= 1" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "$0")" && pwd)
SLENDER_BIN=${SLENDER_BIN:-$here/../../target/release/slender}
if [ ! -x "$SLENDER_BIN" ]; then
  echo "no slender binary at $SLENDER_BIN: run cargo build --release or set SLENDER_BIN" >&2
  exit 2
fi
SLENDER_BIN=$(cd "$(dirname "$SLENDER_BIN")" && pwd)/$(basename "$SLENDER_BIN")
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
export SHARDS OUT SLENDER_BIN

array_job=$(sbatch --parsable --export=ALL --array="0-$((SHARDS - 1))" \
  --job-name=slender-shard --output="$OUT/shard-%a.log" "$here/shard.sbatch" "$@")
merge_job=$(sbatch --parsable --export=ALL --dependency="afterok:${array_job%%;*}" \
  --job-name=slender-merge --output="$OUT/merge.log" "$here/merge.sbatch" "$@")
echo "submitted shards as job $array_job and the merge as job $merge_job; report in $OUT"
