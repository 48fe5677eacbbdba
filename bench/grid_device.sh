#!/usr/bin/env bash
# The grid on the CPU path and on an OpenCL device, one run, rounds alternating:
# `polyvol grid --json` wall seconds (reading the mesh and writing nothing
# included) for spheres of 100k and 1M triangles on N^3 grids; for the device
# also its kernels' and its copies' seconds (kernels/transfers) of each round.
#   BUILD=build ROUNDS=3 SIZES="128 256" DEVICE=opencl bench/grid_device.sh
# Under pocl (Debian's CPU OpenCL) these are CPU-OpenCL numbers on the same
# cores as the CPU path, not GPU numbers.
set -euo pipefail
BUILD=${BUILD:-build}
ROUNDS=${ROUNDS:-3}
SIZES=${SIZES:-"128 256"}
DEVICE=${DEVICE:-opencl}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in 100000 1000000; do "$BUILD/bench/make_mesh" "$n" 0 "$work/sphere_$n.stl" sphere >/dev/null; done
"$BUILD/polyvol" grid --cells 8 --device "$DEVICE" "$work/sphere_100000.stl" >/dev/null 2>&1  # the kernel built once
printf "%-10s %5s %-8s %s\n" triangles N device "seconds (each round)"
for n in 100000 1000000; do
  for cells in $SIZES; do
    declare -A times=([cpu]="" [$DEVICE]="")
    for _ in $(seq "$ROUNDS"); do
      for device in cpu "$DEVICE"; do
        s=$("$BUILD/polyvol" grid --cells "$cells" --device "$device" --json "$work/sphere_$n.stl" 2>/dev/null |
            python3 -c 'import json,sys; j=json.load(sys.stdin); d=j.get("device_seconds")
print(round(j["seconds"], 3) if d is None else "%.3g(%.3g/%.3g)" % (j["seconds"], d["kernels"], d["transfers"]))')
        times[$device]="${times[$device]} $s"
      done
    done
    for device in cpu "$DEVICE"; do printf "%-10s %5s %-8s %s\n" "$n" "$cells" "$device" "${times[$device]}"; done
    unset times
  done
done
