#!/usr/bin/env bash
# Points per minute of one sweep on the local executor and on a private
# single-node Slurm cluster (scripts/slurm-test-cluster.sh) at several
# packings (points per array task); the overhead per task. docs/cluster.md
# quotes its output.
#   scripts/cluster-bench.sh [BUILD_DIR] [PACKINGS...]   (default: build 1 4 16)
# Needs root (the cluster's daemons). Wall times: repeat on a quiet machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
shift || true
packings=("$@")
[ ${#packings[@]} -gt 0 ] || packings=(1 4 16)
exe="$(cd "$build" && pwd)/imapsim"
[ -x "$exe" ] || { echo "cluster-bench: no $exe (build first)" >&2; exit 2; }
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=DISABLE
work="$(mktemp -d /tmp/imapsim-cluster-bench-XXXXXX)"
trap 'bash scripts/slurm-test-cluster.sh stop "$work/cluster" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
cpus="$(nproc)"
# 48 small points of the bare machine (32x16 ROI, D 1..24, 8 and 16 PEs).
sweep=(sweep --model core --roi-size 32x16 --D 1..24 --pes 8,16)
points=48

now() { date +%s.%N; }
report() {  # label seconds [tasks]
  awk -v l="$1" -v s="$2" -v n="$points" -v t="${3:-0}" -v c="$cpus" -v loc="${4:-0}" 'BEGIN {
    printf "%-28s %7.1f s  %6.1f points/min", l, s, 60 * n / s;
    if (t > 0) printf "  %3d tasks  overhead %.2f s per task (x %d CPUs)", t, (s - loc) * c / t, c;
    printf "\n" }'
}

t0=$(now); "$exe" "${sweep[@]}" -j "$cpus" > "$work/local.out"; t1=$(now)
local_s=$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')
echo "sweep of $points points (${sweep[*]}), $cpus CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
report "local -j $cpus" "$local_s"

bash scripts/slurm-test-cluster.sh start "$work/cluster" > "$work/cluster.out"
export SLURM_CONF="$work/cluster/slurm.conf"
# Slurm's own cost: an array of empty tasks, one per point.
t0=$(now)
job=$(sbatch --parsable --array=0-$((points - 1)) --output=/dev/null --wrap=true)
while [ -n "$(squeue --noheader --jobs="$job" --states=PENDING,RUNNING,COMPLETING,CONFIGURING 2>/dev/null)" ]; do
  sleep 0.05
done
t1=$(now)
awk -v s="$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" -v n="$points" -v c="$cpus" 'BEGIN {
  printf "%-28s %7.1f s  %d empty tasks: %.2f s per task (x %d CPUs)\n", "slurm, empty array", s, n, s * c / n, c }'
for p in "${packings[@]}"; do
  t0=$(now)
  "$exe" "${sweep[@]}" --executor slurm --points-per-task "$p" --poll 0.2 \
    --run-dir "$work/run-$p" > "$work/slurm-$p.out"
  t1=$(now)
  tasks=$(( (points + p - 1) / p ))
  report "slurm, $p point(s) per task" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" "$tasks" "$local_s"
done
# Local again, to bracket the Slurm runs (the machine's load changes).
t0=$(now); "$exe" "${sweep[@]}" -j "$cpus" > "$work/local2.out"; t1=$(now)
report "local -j $cpus (again)" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')"
echo "load at the end $(cut -d' ' -f1-3 /proc/loadavg)"
