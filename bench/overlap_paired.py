"""Paired rounds of `polyvol overlap --json A B` with two polyvol binaries
(before and after a change), in turn, alternating which goes first; prints
the medians of the process's wall time and of the JSON's `seconds`.

    python3 bench/overlap_paired.py OLD_POLYVOL NEW_POLYVOL A1.stl B1.stl [A2.stl B2.stl ...] [--rounds 7]

Both binaries must give the same intersection (checked)."""
import json
import statistics
import subprocess
import sys
import time


def main(argv):
    rounds = 7
    if "--rounds" in argv:
        i = argv.index("--rounds")
        rounds = int(argv[i + 1])
        del argv[i:i + 2]
    old, new, files = argv[0], argv[1], argv[2:]
    for a, b in zip(files[::2], files[1::2]):
        wall = {"old": [], "new": []}
        call = {"old": [], "new": []}
        result = {}
        for r in range(rounds):
            order = (("old", old), ("new", new)) if r % 2 == 0 else (("new", new), ("old", old))
            for name, exe in order:
                t0 = time.perf_counter()
                p = subprocess.run([exe, "overlap", "--json", a, b], capture_output=True, text=True, check=True)
                wall[name].append(time.perf_counter() - t0)
                j = json.loads(p.stdout)
                call[name].append(j["seconds"])
                result[name] = j["intersection"]
        assert result["old"] == result["new"], (a, b, result)
        wo, wn = statistics.median(wall["old"]), statistics.median(wall["new"])
        co, cn = statistics.median(call["old"]), statistics.median(call["new"])
        print(f"{a} {b}: process {wo:.3f} s -> {wn:.3f} s ({wn / wo:.2f}x); "
              f"call {co * 1e3:.1f} ms -> {cn * 1e3:.1f} ms ({cn / co:.2f}x)")


if __name__ == "__main__":
    main(sys.argv[1:])
