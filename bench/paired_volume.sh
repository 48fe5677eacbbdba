#!/bin/bash
# Whole-process paired rounds of two polyvol binaries (OLD, NEW) and the naive
# mmap loop on one binary STL: `polyvol volume --volume-only FILE` and the
# table (`polyvol volume FILE`), each tool once per round, at each ISA
# (POLYVOL_MAX_ISA); prints "ISA TOOL WHAT SECONDS..." per line, then medians.
#   OLD=old/build/polyvol NEW=build/polyvol NAIVE=build/bench/naive_stl_volume \
#   ROUNDS=5 ISAS="avx512 avx2" bench/paired_volume.sh sphere8M.stl
set -euo pipefail
file=${1:?usage: paired_volume.sh FILE.stl}
: "${OLD:?OLD=path to the old polyvol}" "${NEW:=build/polyvol}" "${NAIVE:=build/bench/naive_stl_volume}"
: "${ROUNDS:=5}" "${ISAS:=avx512 avx2}"
seconds() { local s e; s=$(date +%s.%N); "$@" > /dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc; }
out=$(for isa in $ISAS; do
  for _ in $(seq "$ROUNDS"); do
    echo "$isa naive volume-only $(seconds "$NAIVE" "$file")"
    for tool in old new; do
      bin=$OLD; [ $tool = new ] && bin=$NEW
      echo "$isa $tool volume-only $(POLYVOL_MAX_ISA=$isa seconds "$bin" volume --volume-only "$file")"
      echo "$isa $tool table $(POLYVOL_MAX_ISA=$isa seconds "$bin" volume "$file")"
    done
  done
done)
echo "$out" | awk '{k=$1" "$2" "$3; a[k]=a[k]" "$4} END{for (k in a) print k ":" a[k]}' | sort
echo "$out" | awk '{print $1" "$2" "$3}' | sort -u | while read -r isa tool what; do
  values=$(echo "$out" | awk -v k="$isa $tool $what" '$1" "$2" "$3 == k {print $4}' | sort -n)
  n=$(echo "$values" | wc -l)
  echo "$isa $tool $what median $(echo "$values" | sed -n "$(( (n + 1) / 2 ))p")"
done
