#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 60), two at a time, from
# its seeds (fuzz/seeds/<target>) and the regressions (tests/data/regressions),
# with its dictionary; new inputs go to BUILD/fuzz-corpus/<target>. A crash,
# leak, hang (-timeout=1 s; 10 s for pipeline and grid) or allocation over 2 GB stops that target and
# fails the run; its input is left in BUILD/fuzz-artifacts/. Prints one line
# per target: executions, coverage, seconds. With RUNS set, a target also
# stops after that many executions.
#   [RUNS=N] fuzz/run.sh [BUILD=build-fuzz] [SECONDS=60] [TARGET...]
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-fuzz}
seconds=${2:-60}
shift $(( $# > 2 ? 2 : $# ))
targets=("$@")
RUNS=${RUNS:-}
[ ${#targets[@]} -eq 0 ] && targets=(stl obj off ply 3mf amf gzip archive gltf chain qhull polygons pipeline grid vtu polymesh grdecl)
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"

dict_of() {
  case $1 in
    stl) echo fuzz/dict/stl.dict ;; obj) echo fuzz/dict/obj.dict ;; off) echo fuzz/dict/off.dict ;;
    ply) echo fuzz/dict/ply.dict ;; 3mf|amf|vtu) echo fuzz/dict/xml.dict ;; chain|qhull|polygons) echo fuzz/dict/chain.dict ;; grdecl) echo fuzz/dict/grdecl.dict ;;
    *) echo "" ;;
  esac
}

run_one() {
  local t=$1 dict
  dict=$(dict_of "$t")
  mkdir -p "$build/fuzz-corpus/$t"
  local start=$SECONDS
  # A hang is more than 1 s on one input; the exact geometry of the whole
  # path (GMP under ASan and coverage instrumentation, 10-200x slower than a
  # Release build) gets 10 s, its slow inputs replayed by ctest instead.
  # Their inputs stay within 4 KB (the regressions would raise libFuzzer's
  # max_len to 20 KB, and their cost grows with the mesh).
  local timeout=1 extra=""
  case $t in pipeline|grid) timeout=10 extra="-max_len=4096" ;; esac
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" ${RUNS:+-runs=$RUNS} -timeout=$timeout $extra -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t-" ${dict:+-dict=$dict} \
    "$build/fuzz-corpus/$t" "fuzz/seeds/$t" tests/data/regressions >"$build/fuzz-logs/$t.log" 2>&1
  local rc=$?
  local runs cov
  runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$build/fuzz-logs/$t.log" | tail -1 | grep -o '[0-9]*$')
  cov=$(grep -o 'cov: [0-9]*' "$build/fuzz-logs/$t.log" | tail -1 | grep -o '[0-9]*$')
  printf '%-9s %s  executions %10s  coverage %6s  %ss\n' "$t" "$([ $rc = 0 ] && echo ok || echo FAILED)" \
    "${runs:-?}" "${cov:-?}" "$((SECONDS - start))"
  return $rc
}
export -f run_one dict_of
export build seconds RUNS
printf '%s\n' "${targets[@]}" | xargs -P 2 -I{} bash -c 'run_one {}'
status=$?
if [ $status -ne 0 ]; then
  echo "fuzz: a target failed; its log is in $build/fuzz-logs, its input in $build/fuzz-artifacts"
  exit 1
fi
