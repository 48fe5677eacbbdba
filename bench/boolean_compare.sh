#!/usr/bin/env bash
# The boolean benchmark (issues #20, #36): the intersection volume of two
# spheres (or tori) of N triangles each, the second moved by
# (0.29, 0.29, 0.29) (half the sphere's radius). Every tool reads the same
# binary STL files (float32 coordinates) and reports its in-process call
# (meshes loaded); each runs as a whole process too. The tools:
#   p  polyvol, `polyvol overlap --json` (call: its "seconds", the one-solid
#      policy's checks of each operand and the booleans)
#   i  polyvol in process (bench/peers/polyvol_boolean.cpp): call =
#      boolean_volumes on the two meshes; its policy figure is printed too
#   n  Manifold native, oneTBB backend (only when BUILD has
#      peer_manifold_boolean: -DPOLYVOL_MANIFOLD_PEER=ON, see
#      bench/peers/build_manifold.sh)
#   m  Manifold's WebAssembly build (npm manifold-3d, in Node)
#   c  CGAL's exact corefinement + volume
# Per size, ROUNDS rounds; the tools' order rotates from round to round.
# Prints per-round figures, the medians and the ratios of medians to i's call.
#   bench/boolean_compare.sh     CASES="sphere:20000 sphere:100000 sphere:500000 torus:100000" ROUNDS=5 TOOLS="p i n m c"
# Needs: BUILD (build-bench; configured here with -DPOLYVOL_CGAL_PEER=ON unless
# SKIP_BUILD=1), node + npm (manifold-3d is installed into BUILD/node on first use).
set -euo pipefail
cd "$(dirname "$0")/.."
CASES=${CASES:-"sphere:20000 sphere:100000 sphere:500000 torus:100000"}
ROUNDS=${ROUNDS:-5}
BUILD=${BUILD:-build-bench}
WORK=${WORK:-/tmp/polyvol-boolean-bench}
mkdir -p "$WORK"
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DPOLYVOL_CGAL_PEER=ON -DPOLYVOL_TESTS=OFF >/dev/null
  cmake --build "$BUILD" -j2 --target polyvol_cli make_mesh peer_cgal_boolean harness_polyvol_boolean >/dev/null
fi
TOOLS=${TOOLS:-"p i n m c"}
[ -x "$BUILD/bench/peer_manifold_boolean" ] || TOOLS=${TOOLS//n/}
read -r -a tools <<< "$TOOLS"
[[ " $TOOLS " == *" i "* ]] || { echo "TOOLS must hold i (the ratios' base)" >&2; exit 2; }
NODE_DIR="$BUILD/node"
if [[ " $TOOLS " == *" m "* ]] && [ ! -d "$NODE_DIR/node_modules/manifold-3d" ]; then
  mkdir -p "$NODE_DIR" && (cd "$NODE_DIR" && npm init -y >/dev/null && npm install --silent manifold-3d@3 >/dev/null)
fi
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(grep -o -m1 'avx512f' /proc/cpuinfo || echo 'no avx512'), load $(cut -d' ' -f1-3 /proc/loadavg); node $(node --version)"
now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
name() { case $1 in p) echo "polyvol overlap";; i) echo "polyvol in process";; n) echo "Manifold native";; m) echo "Manifold WASM";; c) echo "CGAL";; esac; }
for case in $CASES; do
  shape=${case%%:*} n=${case##*:}
  a="$WORK/${shape}_${n}_a.stl" b="$WORK/${shape}_${n}_b.stl"
  [ -f "$a" ] || "$BUILD/bench/make_mesh" "$n" 0 "$a" "$shape"
  [ -f "$b" ] || "$BUILD/bench/make_mesh" "$n" 0.28867513459481287 "$b" "$shape"  # moved 0.5
  for tool in "${tools[@]}"; do : > "$WORK/$tool.call"; : > "$WORK/$tool.proc"; done
  : > "$WORK/i.policy"
  echo "== 2 x $n triangles ($shape)"
  for r in $(seq 1 "$ROUNDS"); do
    k=${#tools[@]}
    for j in $(seq 0 $((k - 1))); do
      tool=${tools[$(((j + r) % k))]}
      t0=$(now)
      case $tool in
        p) vol=$("$BUILD/polyvol" overlap --json "$a" "$b" |
             python3 -c 'import json,sys; j=json.load(sys.stdin); print(repr(j["intersection"]), j["seconds"])');;
        i) out=$("$BUILD/bench/harness_polyvol_boolean" "$a" "$b" 3)
           vol=$(echo "$out" | awk '{print $2, $4}'); echo "$out" | awk '{print $5}' >> "$WORK/i.policy";;
        n) vol=$("$BUILD/bench/peer_manifold_boolean" "$a" "$b" 3 | awk '{print $2, $4}');;
        m) vol=$(MANIFOLD_DIR="$NODE_DIR" node bench/peers/manifold_boolean.mjs "$a" "$b" 1 |
             python3 -c 'import json,sys; j=json.load(sys.stdin); print(repr(j["volume"]), j["call_seconds"][0])');;
        c) vol=$(timeout 600 "$BUILD/bench/peer_cgal_boolean" "$a" "$b" 1 | awk '{print $2, $4}');;
      esac
      t1=$(now)
      echo "$vol" | awk '{print $2}' >> "$WORK/$tool.call"
      echo "$t1 - $t0" | bc -l >> "$WORK/$tool.proc"
      echo "  round $r $tool: volume $(echo "$vol" | awk '{print $1}'), call $(echo "$vol" | awk '{print $2}') s, process $(echo "$t1 - $t0" | bc -l | cut -c1-6) s"
    done
  done
  base=$(median < "$WORK/i.call")
  printf '  polyvol in process, policy route (make_solid x2 + solid_booleans): %.4f s\n' "$(median < "$WORK/i.policy")"
  for tool in "${tools[@]}"; do
    c=$(median < "$WORK/$tool.call"); p=$(median < "$WORK/$tool.proc")
    printf '  median %-20s call %.4f s (%.2fx polyvol in process), process %.3f s\n' "$(name "$tool"):" "$c" "$(echo "$c / $base" | bc -l)" "$p"
  done
done
