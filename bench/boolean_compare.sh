#!/usr/bin/env bash
# The boolean benchmark (issue #20): the intersection volume of two spheres
# (or tori) of N triangles each, the second moved by (0.29, 0.29, 0.29)
# (half the sphere's radius), with polyvol
# (`polyvol overlap`, exact), Manifold (npm manifold-3d in Node, float32) and
# CGAL (exact corefinement + volume). Each tool reads the same binary STL
# files (float32 coordinates). Per size, ROUNDS rounds in rotating order; each
# round runs every tool once as a whole process and records its in-process
# call (meshes loaded) as the tool reports it. Prints per-round figures, the
# medians and the ratios of medians.
#   bench/boolean_compare.sh            CASES="sphere:20000 sphere:100000 sphere:500000 torus:100000" ROUNDS=5
# Needs: build-bench (cmake -DPOLYVOL_CGAL_PEER=ON, done here unless SKIP_BUILD=1), node + npm (manifold-3d is
# installed into build-bench/node on first use).
set -euo pipefail
cd "$(dirname "$0")/.."
CASES=${CASES:-"sphere:20000 sphere:100000 sphere:500000 torus:100000"}
ROUNDS=${ROUNDS:-5}
BUILD=${BUILD:-build-bench}
WORK=${WORK:-/tmp/polyvol-boolean-bench}
mkdir -p "$WORK"
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DPOLYVOL_CGAL_PEER=ON -DPOLYVOL_TESTS=OFF >/dev/null
  cmake --build "$BUILD" -j2 --target polyvol_cli make_mesh peer_cgal_boolean >/dev/null
fi
NODE_DIR="$BUILD/node"
if [ ! -d "$NODE_DIR/node_modules/manifold-3d" ]; then
  mkdir -p "$NODE_DIR" && (cd "$NODE_DIR" && npm init -y >/dev/null && npm install --silent manifold-3d@3 >/dev/null)
fi
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(grep -o -m1 'avx512f' /proc/cpuinfo || echo 'no avx512'), load $(cut -d' ' -f1-3 /proc/loadavg)"
now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
for case in $CASES; do
  shape=${case%%:*} n=${case##*:}
  a="$WORK/${shape}_${n}_a.stl" b="$WORK/${shape}_${n}_b.stl"
  [ -f "$a" ] || "$BUILD/bench/make_mesh" "$n" 0 "$a" "$shape"
  [ -f "$b" ] || "$BUILD/bench/make_mesh" "$n" 0.28867513459481287 "$b" "$shape"  # moved 0.5
  : > "$WORK/p.call"; : > "$WORK/m.call"; : > "$WORK/c.call"; : > "$WORK/p.proc"; : > "$WORK/m.proc"; : > "$WORK/c.proc"
  echo "== 2 x $n triangles ($shape)"
  for r in $(seq 1 "$ROUNDS"); do
    for tool in $(case $((r % 3)) in 0) echo p m c;; 1) echo m c p;; *) echo c p m;; esac); do
      t0=$(now)
      case $tool in
        p) out=$("$BUILD/polyvol" overlap --json "$a" "$b")
           vol=$(echo "$out" | python3 -c 'import json,sys; j=json.load(sys.stdin); print(repr(j["intersection"]), j["seconds"])');;
        m) out=$(MANIFOLD_DIR="$NODE_DIR" node bench/peers/manifold_boolean.mjs "$a" "$b" 1)
           vol=$(echo "$out" | python3 -c 'import json,sys; j=json.load(sys.stdin); print(repr(j["volume"]), j["call_seconds"][0])');;
        c) out=$(timeout 600 "$BUILD/bench/peer_cgal_boolean" "$a" "$b" 1)
           vol=$(echo "$out" | awk '{print $2, $4}');;
      esac
      t1=$(now)
      echo "$vol" | awk '{print $2}' >> "$WORK/$tool.call"
      echo "$t1 - $t0" | bc -l >> "$WORK/$tool.proc"
      echo "  round $r $tool: volume $(echo "$vol" | awk '{print $1}'), call $(echo "$vol" | awk '{print $2}') s, process $(echo "$t1 - $t0" | bc -l | cut -c1-6) s"
    done
  done
  pc=$(median < "$WORK/p.call"); mc=$(median < "$WORK/m.call"); cc=$(median < "$WORK/c.call")
  pp=$(median < "$WORK/p.proc"); mp=$(median < "$WORK/m.proc"); cp=$(median < "$WORK/c.proc")
  printf '  medians: call polyvol %.4f s, Manifold %.4f s (%.1fx), CGAL %.3f s (%.0fx); process polyvol %.3f s, Manifold %.3f s (%.1fx), CGAL %.2f s (%.0fx)\n' \
    "$pc" "$mc" "$(echo "$mc / $pc" | bc -l)" "$cc" "$(echo "$cc / $pc" | bc -l)" \
    "$pp" "$mp" "$(echo "$mp / $pp" | bc -l)" "$cp" "$(echo "$cp / $pp" | bc -l)"
done
