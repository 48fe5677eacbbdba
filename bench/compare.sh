#!/usr/bin/env bash
# Whole-process comparison (docs/benchmarks.md, "Whole-process volume"), in one run:
#   * builds Release with the peers (-DPOLYVOL_PEERS=ON: CGAL, VTK, Open3D from Debian);
#   * generates UV spheres of ~1M and ~8M triangles (build/bench/make_mesh) as
#     binary STL, ASCII STL, binary PLY and OBJ in a temporary directory
#     (deleted at the end);
#   * runs `polyvol volume`, naive_stl_volume (binary STL only), peer_cgal,
#     peer_vtk and peer_open3d (1M files only: its watertightness check is
#     quadratic) RUNS times each, in rounds (each tool once per round, the
#     order rotating), and prints the median wall seconds, the median peak
#     RSS, the volumes, and the ratios polyvol/naive and peer/polyvol;
#   * prints loading and the in-memory volume call of each tool's harness
#     (their own medians, and the call's ratio per round; polyvol's also on
#     the binary STL's packed float32 triangles, and two plain loops for
#     scale) and polyvol_bench's;
#   * measures peak RSS of `polyvol volume` (and of the naive mmap loop) on a
#     BIG_TRIANGLES-triangle binary STL (default 60M = 3 GB).
# Usage: bench/compare.sh [BUILD_DIR]      (env: RUNS=5, TIMEOUT=600, JOBS=2,
#        BIG_TRIANGLES=60000000, OFFSET=0, SIZES="1000000 8000000",
#        SKIP_BUILD=1 to reuse BUILD_DIR, PEERS=0 for polyvol and the naive loop only; Open3D runs on the smallest size only,
#        with OPEN3D_TIMEOUT=20 per run: its quadratic watertightness check takes ~30 s at 100k triangles, so 1M never finishes)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build-bench}
RUNS=${RUNS:-5}
TIMEOUT=${TIMEOUT:-600}
JOBS=${JOBS:-2}
BIG_TRIANGLES=${BIG_TRIANGLES:-60000000}
OFFSET=${OFFSET:-0}
SIZES=${SIZES:-"1000000 8000000"}
OPEN3D_TIMEOUT=${OPEN3D_TIMEOUT:-20}
PEERS=${PEERS:-1}   # 0: polyvol and the naive loop only (quick runs)

echo "## machine"
echo "nproc: $(nproc); CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'); $(grep MemTotal /proc/meminfo | tr -s ' ')"
echo "command: $0 $*  (RUNS=$RUNS TIMEOUT=$TIMEOUT JOBS=$JOBS BIG_TRIANGLES=$BIG_TRIANGLES OFFSET=$OFFSET SIZES=\"$SIZES\")"
echo "date: $(date -u +%Y-%m-%dT%H:%MZ); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

if [ "${SKIP_BUILD:-0}" != 1 ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPOLYVOL_PEERS=ON >/dev/null
  cmake --build "$build" -j"$JOBS" --target polyvol_cli polyvol_bench make_mesh naive_stl_volume \
    harness_polyvol peer_cgal peer_vtk peer_open3d >/dev/null
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/polyvol-compare.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

tags=""
for n in $SIZES; do
  if [ "$n" -ge 1000000 ]; then tag=$((n / 1000000))m; else tag=$((n / 1000))k; fi
  tags="$tags $tag"
  for ext in stl ascii.stl ply obj; do
    "$build/bench/make_mesh" "$n" "$OFFSET" "$tmp/sphere$tag.$ext"
  done
done
ls -l "$tmp" | sed 's/^/    /'
# The meshes just written are still being flushed to disk: writeback would
# take a core from the timed runs (polyvol uses both), so wait for it.
sync

python3 - "$build" "$tmp" "$RUNS" "$TIMEOUT" "$BIG_TRIANGLES" "$OFFSET" "$tags" "$OPEN3D_TIMEOUT" "$PEERS" <<'PY'
import os, subprocess, sys, time, statistics, signal

build, tmp, runs, timeout, big, offset = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5]), sys.argv[6]
tags = sys.argv[7].split()
open3d_timeout = float(sys.argv[8])
with_peers = sys.argv[9] != "0"
B = lambda *p: os.path.join(build, *p)

def run_wait4(cmd, timeout=timeout):
    """Wall seconds, peak RSS (KB, from wait4), stdout, exit code (None on timeout)."""
    t0 = time.monotonic()
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(r)
        os.dup2(w, 1)
        dn = os.open(os.devnull, os.O_WRONLY)
        os.dup2(dn, 2)
        try:
            os.execv(cmd[0], cmd)
        finally:
            os._exit(127)
    os.close(w)
    chunks = []
    deadline = t0 + timeout
    import select
    killed = False
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            os.kill(pid, signal.SIGKILL)
            killed = True
            break
        ready, _, _ = select.select([r], [], [], min(left, 1.0))
        if ready:
            b = os.read(r, 65536)
            if not b:
                break
            chunks.append(b)
    _, status, ru = os.wait4(pid, 0)
    wall = time.monotonic() - t0
    os.close(r)
    if killed:
        return wall, ru.ru_maxrss, "", None
    return wall, ru.ru_maxrss, b"".join(chunks).decode(errors="replace"), os.waitstatus_to_exitcode(status)

def warm(path):
    """Reads the file once so that the next run finds it in the page cache: this VM runs DAMON
    with a pageout scheme (kdamond), which evicts pages of files left idle for a while."""
    with open(path, "rb") as f:
        while f.read(1 << 22):
            pass

def limit_of(name):
    """A run's time limit: Open3D's is shorter (its watertightness check is quadratic)."""
    return min(timeout, open3d_timeout) if name == "open3d" else timeout

def bench_rounds(tools, n):
    """Each tool once per round, n rounds, the order rotating: the shared machine's state drifts, so
    the runs of one round, minutes apart at most, see much the same machine. Returns
    per tool (median wall s, median peak RSS KB, last stdout, last exit code, every stdout), or None
    once a run timed out (that tool is not run again); and the rounds themselves (name -> that
    run's stdout)."""
    walls = {name: [] for name, _ in tools}
    rss = {name: [] for name, _ in tools}
    outs = {name: [] for name, _ in tools}
    codes = {}
    dead = set()
    rounds = []
    for i in range(n):
        k = i % len(tools)
        this = {}
        for name, cmd in tools[k:] + tools[:k]:
            if name in dead:
                continue
            if os.path.isfile(cmd[-1]):
                warm(cmd[-1])
            w, m, o, c = run_wait4(cmd, limit_of(name))
            if c is None:
                dead.add(name)
                continue
            walls[name].append(w); rss[name].append(m); outs[name].append(o); codes[name] = c
            this[name] = o
        rounds.append(this)
    res = {}
    for name, _ in tools:
        if name in dead or not walls[name]:
            res[name] = None
        else:
            res[name] = (statistics.median(walls[name]), statistics.median(rss[name]), outs[name][-1], codes[name], outs[name])
    return res, rounds

def volume_of(tool, out):
    try:
        if tool == "polyvol":
            line = out.splitlines()[1]
            return float(line.split()[2])
        if tool == "naive":
            return float(out.split()[0])
        return float(out.split()[1])
    except Exception:
        return float("nan")

def inmem_of(tool, out):
    try:
        return float(out.split()[3]) if tool not in ("polyvol", "naive") else None
    except Exception:
        return None

def field_of(out, i):
    """polyvol-harness only: field i (5: READ_SECONDS, 6: NAIVE_SECONDS, 7: PACKED_LOAD_SECONDS,
    8: PACKED_SECONDS), None when absent or negative."""
    try:
        x = float(out.split()[i])
        return x if x >= 0 else None
    except Exception:
        return None

def load_of(tool, out):
    """The harnesses' LOAD_SECONDS: reading into memory plus one volume call."""
    try:
        return float(out.split()[2]) if tool not in ("polyvol", "naive") else None
    except Exception:
        return None

def paired_call_ratios(rounds):
    """Per round: the fastest peer's in-memory call (CGAL or VTK) / polyvol's, both from that round's runs."""
    ratios = []
    for r in rounds:
        pc = inmem_of("polyvol-harness", r["polyvol-harness"]) if "polyvol-harness" in r else None
        peer = [x for x in (inmem_of(n, r[n]) for n in ("cgal", "vtk") if n in r) if x]
        if pc and peer:
            ratios.append(min(peer) / pc)
    return sorted(ratios)

rows = []
paired = {}  # (tag, ext) -> sorted per-round ratios of the in-memory call (fastest peer / polyvol)
for tag in tags:
    for ext in ("stl", "ascii.stl", "ply", "obj"):
        f = os.path.join(tmp, f"sphere{tag}.{ext}")
        tools = [("polyvol", [B("polyvol"), "volume", f]), ("polyvol-harness", [B("bench", "harness_polyvol"), f])]
        if ext == "stl":
            tools.append(("naive", [B("bench", "naive_stl_volume"), f]))
        if with_peers:
            tools += [("cgal", [B("bench", "peer_cgal"), f]), ("vtk", [B("bench", "peer_vtk"), f])]
        if with_peers and tag == tags[0]:
            tools.append(("open3d", [B("bench", "peer_open3d"), f]))
        res, rounds = bench_rounds(tools, runs)
        for name, _ in tools:
            r = res[name]
            if r is None:
                print(f"    {tag} {ext:9} {name:8} timeout (> {limit_of(name):.0f} s)", flush=True)
            else:
                print(f"    {tag} {ext:9} {name:8} {r[0]:8.3f} s  {r[1]/1024:8.1f} MB  exit {r[3]}  volume {volume_of(name, r[2])!r}"
                      + (f"  in-memory {inmem_of(name, r[2]):.4f} s" if inmem_of(name, r[2]) is not None else ""), flush=True)
        rows.append((tag, ext, res))
        paired[(tag, ext)] = paired_call_ratios(rounds)

print()
print("| mesh | format | tool | median wall s | median peak RSS MB | ratio to polyvol | volume | peer in-memory volume call s |")
print("|---|---|---|---|---|---|---|---|")
for tag, ext, res in rows:
    pv = res.get("polyvol")
    for name, r in res.items():
        if r is None:
            print(f"| {tag} | {ext} | {name} | timeout > {limit_of(name):.0f} | | | | |")
            continue
        ratio = "" if pv is None or name == "polyvol" else f"{r[0] / pv[0]:.2f}"
        im = inmem_of(name, r[2])
        print(f"| {tag} | {ext} | {name} | {r[0]:.3f} | {r[1]/1024:.1f} | {ratio} | {volume_of(name, r[2])!r} | {'' if im is None else f'{im:.4f}'} |")
print()
for tag, ext, res in rows:
    if ext == "stl" and res.get("polyvol") and res.get("naive"):
        print(f"polyvol/naive ({tag} binary STL, median wall): {res['polyvol'][0] / res['naive'][0]:.2f}")

def fresh(path):
    """Evicts the file's pages, then reads it afresh: the page cache then holds it in large folios,
    and the naive loop's mmap faults cost almost nothing (the state in which it is fastest)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
    finally:
        os.close(fd)
    warm(path)

print()
print("Binary STL, polyvol volume (and volume --volume-only) against the naive loop in interleaved")
print("runs (the order rotating; the shared machine's state drifts, so neighbours compare like with like):")
print("median of the per-round ratios. warm: the file read once before each run; fresh: its pages evicted")
print("and read afresh before each run (large folios: the naive loop's best case).")
interleaved = {}  # (tag, state) -> median of the rounds' volume-only / naive
for tag in tags:
    f = os.path.join(tmp, f"sphere{tag}.stl")
    cmds = {"polyvol": [B("polyvol"), "volume", f], "volume-only": [B("polyvol"), "volume", "--volume-only", f],
            "naive": [B("bench", "naive_stl_volume"), f]}
    for state, prepare in (("warm", warm), ("fresh", fresh)):
        rounds = []
        names = list(cmds)
        for i in range(4 * runs):
            order = names[i % 3:] + names[:i % 3]
            t = {}
            for name in order:
                prepare(f)
                t[name] = run_wait4(cmds[name])[0]
            rounds.append(t)
        n = statistics.median(r["naive"] for r in rounds)
        interleaved[(tag, state)] = statistics.median(r["volume-only"] / r["naive"] for r in rounds)
        line = f"    {tag} {state}: naive {n * 1e3:.1f} ms"
        for name in ("polyvol", "volume-only"):
            ratios = sorted(r[name] / r["naive"] for r in rounds)
            q = statistics.quantiles(ratios, n=4)
            line += (f"; {name} {statistics.median(r[name] for r in rounds) * 1e3:.1f} ms, /naive median "
                     f"{statistics.median(ratios):.2f} (quartiles {q[0]:.2f}..{q[2]:.2f})")
        print(line + f" ({len(rounds)} rounds)", flush=True)

print()
print("Loading (read into memory + one volume call) and the in-memory volume call, each tool's own")
print("harness (medians over runs of the in-process figures); ratio = fastest peer / polyvol.")
print()
print("read loop / naive det: plain scalar loops over the same arrays on all cores, reading and adding the")
print("coordinates (no determinant) / summing det in plain double (bench/peers/polyvol_volume.cpp); for")
print("scale, not lower bounds. 5x the fastest peer needs a call below fastest/5. Every tool holds an indexed")
print("mesh (the STL readers, polyvol's too, merge the facets' corners). packed (binary STL only): the file read as its own")
print("float32 triangles (read_binary_stl_triangles, 36 bytes a triangle) and soup_volume on them, load and")
print("call, with the call's ratio; the same correctly rounded volume. paired: the call ratio per round")
print("(the fastest peer's call / polyvol's, both from the same round of runs), median and range over the rounds.")
print()
print("| mesh | format | polyvol load s | CGAL load s | VTK load s | load ratio | polyvol volume call s | CGAL call s | VTK call s | call ratio | paired call ratio | packed load s | packed call s | packed call ratio | fastest/5 s | read loop s | naive det s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
def med(fn, name, r):
    """Median over a tool's runs of fn(name, output); None when no run gave a figure."""
    xs = [x for x in (fn(name, o) for o in r[4]) if x is not None]
    return statistics.median(xs) if xs else None
def paired_text(ratios):
    return "" if not ratios else f"{statistics.median(ratios):.1f} ({ratios[0]:.1f}..{ratios[-1]:.1f})"
harness = {}  # (tag, ext) -> (fastest peer load, fastest peer call, polyvol load, call, packed call)
for tag, ext, res in rows:
    h = res.get("polyvol-harness")
    if h is None:
        continue
    pl, pc = med(load_of, "polyvol-harness", h), med(inmem_of, "polyvol-harness", h)
    ppl = med(lambda n, o: field_of(o, 7), "polyvol-harness", h)
    pp = med(lambda n, o: field_of(o, 8), "polyvol-harness", h)
    loads = {n: med(load_of, n, res[n]) for n in ("cgal", "vtk") if res.get(n)}
    calls = {n: med(inmem_of, n, res[n]) for n in ("cgal", "vtk") if res.get(n)}
    fl = min([x for x in loads.values() if x], default=None)
    fc = min([x for x in calls.values() if x], default=None)
    harness[(tag, ext)] = (fl, fc, pl, pc, pp)
    fmt = lambda x: "" if x is None else f"{x:.4f}"
    print(f"| {tag} | {ext} | {fmt(pl)} | {fmt(loads.get('cgal'))} | {fmt(loads.get('vtk'))} | "
          f"{'' if not (fl and pl) else f'{fl / pl:.1f}'} | {fmt(pc)} | {fmt(calls.get('cgal'))} | {fmt(calls.get('vtk'))} | "
          f"{'' if not (fc and pc) else f'{fc / pc:.1f}'} | {paired_text(paired.get((tag, ext)))} | {fmt(ppl)} | {fmt(pp)} | {'' if not (fc and pp) else f'{fc / pp:.1f}'} | "
          f"{fmt(fc / 5 if fc else None)} | "
          f"{fmt(med(lambda n, o: field_of(o, 5), 'polyvol-harness', h))} | {fmt(med(lambda n, o: field_of(o, 6), 'polyvol-harness', h))} |")

print()
print("## in-memory volume call, polyvol (polyvol_bench)")
sys.stdout.flush()
subprocess.run([B("bench", "polyvol_bench"), "--benchmark_filter=SoupVolume|NaiveRecords|Volume<.*cone.*correctly", "--benchmark_repetitions=3",
                "--benchmark_report_aggregates_only=true"], check=False)

print()
print(f"## peak RSS on a {big}-triangle binary STL")
bigf = os.path.join(tmp, "big.stl")
t0 = time.monotonic()
subprocess.run([B("bench", "make_mesh"), str(big), offset, bigf], check=True)
os.sync()  # its writeback would take a core from the timed runs
print(f"    generated {os.path.getsize(bigf) / 1e9:.2f} GB in {time.monotonic() - t0:.1f} s; MemAvailable "
      + open("/proc/meminfo").read().split("MemAvailable:")[1].split("\n")[0].strip())
big_rss = None
for name, cmd in (("polyvol volume", [B("polyvol"), "volume", bigf]), ("naive (mmap)", [B("bench", "naive_stl_volume"), bigf])):
    r = bench_rounds([(name, cmd)], 3)[0][name]
    if r is None:
        print(f"    {name}: timeout")
    else:
        if name == "polyvol volume":
            big_rss = r[1] / 1024
        print(f"    {name}: median wall {r[0]:.3f} s, median peak RSS {r[1]/1024:.1f} MB, volume {volume_of('polyvol' if name.startswith('polyvol') else 'naive', r[2])!r}")

# The issue's targets, from this run's own figures (docs/benchmarks.md says
# how to read them). A ratio is "fastest peer / polyvol" unless said.
print()
print("## issue #3 targets in this run")
for (tag, state), q in sorted(interleaved.items()):
    print(f"    {tag} binary STL, {state}: volume --volume-only / naive loop, median of rounds {q:.2f} (target <= 1)")
for tag, ext, res in rows:
    pv = res.get("polyvol")
    peers = [res[n][0] for n in ("cgal", "vtk", "open3d") if res.get(n)]
    if pv and peers:
        print(f"    {tag} {ext}: end to end {min(peers) / pv[0]:.1f}x (target >= 20 for binary STL)")
    fl, fc, pl, pc, pp = harness.get((tag, ext), (None,) * 5)
    parts = [f"{label} {fc / x:.1f}x" for label, x in (("as read", pc), ("packed", pp)) if fc and x]
    if parts:
        if paired.get((tag, ext)):
            parts.append(f"as read, paired rounds {paired_text(paired[(tag, ext)])}")
        print(f"    {tag} {ext}: in memory " + ", ".join(parts) + " (target >= 5)")
    if fl and pl:
        print(f"    {tag} {ext}: loading {fl / pl:.1f}x (target >= 5 for ASCII STL and PLY)")
if big_rss is not None:
    print(f"    {big}-triangle binary STL: peak RSS {big_rss:.1f} MB (target: constant)")
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
