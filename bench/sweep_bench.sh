#!/usr/bin/env bash
# Variants per second of `ontogen sweep` over models/stochastic_tree.cell (256 variants:
# LEN 2 x SHRINK 4 x BRANCH 2 x seeds 16, 32x32 thumbnails) on 1 and 2 workers and on 2 MPI
# ranks of one worker, with the hand-written loop of Runs of 64 of those variants
# (BM_VariantsHandWritten) and the library's runVariant loop in the same run. Each figure
# is the best of 3 runs (wall time, the process's start included).
#   bash bench/sweep_bench.sh [BUILD_DIR]        (default build/)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
ontogen="$build/apps/ontogen"
bench="$build/bench/ontogen_bench"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
flags=(--define LEN=1,2 --define SHRINK=0.6:0.9:4 --define BRANCH=0.3,0.7 --seeds 1:16 --size 32x32
       --measure h=height --measure n=cells)
variants=256

best_of_3() {  # prints the fastest of 3 runs of "$@", in seconds
  local best=""
  for _ in 1 2 3; do
    rm -rf "$work/out"
    local start end
    start=$(date +%s.%N)
    "$@" --out "$work/out" >/dev/null 2>"$work/err" || { cat "$work/err" >&2; return 1; }
    end=$(date +%s.%N)
    best=$(awk -v a="$start" -v b="$end" -v best="$best" 'BEGIN { t = b - a; print (best == "" || t < best) ? t : best }')
  done
  echo "$best"
}

report() {  # label seconds
  awk -v label="$1" -v t="$2" -v n="$variants" 'BEGIN { printf "%-28s %6.3f s  %7.1f variants/s\n", label, t, n / t }'
}

report "sweep, 1 worker" "$(best_of_3 "$ontogen" sweep "$root/models/stochastic_tree.cell" "${flags[@]}" --workers 1)"
report "sweep, 2 workers" "$(best_of_3 "$ontogen" sweep "$root/models/stochastic_tree.cell" "${flags[@]}" --workers 2)"
if command -v mpirun >/dev/null; then
  as_root=()
  [[ $(id -u) -eq 0 ]] && as_root=(--allow-run-as-root)
  report "sweep, 2 MPI ranks x 1" "$(best_of_3 mpirun --oversubscribe "${as_root[@]}" -n 2 "$ontogen" sweep \
    "$root/models/stochastic_tree.cell" "${flags[@]}" --workers 1)"
else
  echo "sweep, 2 MPI ranks: mpirun is missing (openmpi-bin)"
fi
"$bench" --benchmark_filter='BM_Variants' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E 'Benchmark|median'
