#!/usr/bin/env bash
# End-to-end figures (docs/performance.md), median of 5 runs each, on deterministic generated programs:
#   mixed      1,000,000 lines of G0/G1/G2/G3 with X Y Z C (scripts/gen-program.sh mixed)
#   engraving    200,000 lines of short G1 strokes, laser-engraving style
# For `interpret`, `interpolate` and `joints` (G-code in, CSV out to /dev/null, one core): wall
# time, MB/s and lines/s of G-code, samples/s, and peak resident memory (GNU time); then the
# minimal loop (benches/minimal_loop.rs: the same work with no checks) and `joints` as a fraction
# of its speed (target ≥ 0.55); and, where LinuxCNC's rs274 is installed, `interpret` against it
# on the same file (target ≥ 6×).
# Usage: benches/pipeline.sh [SCALE]   (SCALE divides the line counts, for a quick run: 10 → 10 %)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scale=${1:-1}
cargo build --release --locked --quiet --bin biscara --example minimal_loop
bin=$PWD/target/release/biscara
minimal=$PWD/target/release/examples/minimal_loop
work=target/bench
mkdir -p "$work"

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# run NAME COMMAND...: 5 runs; prints "seconds peak_kib" medians.
measure() {
  local times=() rss=()
  for _ in 1 2 3 4 5; do
    /usr/bin/time -f "%e %M" -o "$work/time.txt" "$@" > /dev/null 2> /dev/null
    read -r seconds kib < "$work/time.txt"
    times+=("$seconds"); rss+=("$kib")
  done
  echo "$(printf '%s\n' "${times[@]}" | median) $(printf '%s\n' "${rss[@]}" | median)"
}

printf '%-10s %-12s %9s %10s %12s %14s %10s\n' program command seconds MB/s lines/s samples/s peak_MiB
for spec in "mixed 1000000" "engraving 200000"; do
  set -- $spec
  kind=$1; lines=$(( $2 / scale ))
  program=$work/$kind-$lines.ngc
  [ -f "$program" ] || scripts/gen-program.sh "$kind" "$lines" > "$program"
  bytes=$(stat -c %s "$program")
  samples=$("$bin" interpolate "$program" 2> /dev/null | tail -n +2 | wc -l)
  for command in interpret interpolate joints minimal; do
    if [ "$command" = minimal ]; then
      read -r seconds kib <<< "$(measure "$minimal" "$program")"
      echo "  joints at $(awk -v j="$joints" -v m="$seconds" 'BEGIN { if (j > 0) printf "%.2f", m / j; else printf "?" }')x the minimal loop's speed"
    else
      read -r seconds kib <<< "$(measure "$bin" "$command" "$program")"
    fi
    if [ "$command" = joints ]; then joints=$seconds; fi
    awk -v p="$kind" -v c="$command" -v s="$seconds" -v b="$bytes" -v l="$lines" -v n="$samples" -v k="$kib" 'BEGIN {
      rate = (c == "interpret") ? "-" : sprintf("%.2f M", n / s / 1e6)
      printf "%-10s %-12s %9.2f %10.1f %12.0f %14s %10.1f\n", p, c, s, b / s / 1e6, l / s, rate, k / 1024
    }'
    if [ "$command" = interpret ] && [ -x /usr/bin/rs274 ]; then
      # interpret against LinuxCNC's standalone interpreter on the same file.
      read -r theirs _ <<< "$(measure /usr/bin/rs274 -g "$program" "$work/rs274.out")"
      echo "  interpret at $(awk -v o="$seconds" -v r="$theirs" 'BEGIN { if (o > 0) printf "%.1f", r / o; else printf "?" }')x rs274's speed (rs274: $theirs s)"
    fi
  done
done
echo "($(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); samples at dt 1 ms, the default optimal profile)"
