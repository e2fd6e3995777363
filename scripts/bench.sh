#!/usr/bin/env bash
# End-to-end figures of SPEC §10 on a generated program: interpret MB/s, joints samples/s and
# the peak resident memory of joints (GNU time). Prints one line per figure.
# Usage: scripts/bench.sh [LINES]   (default 1,000,000 lines)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
lines=${1:-1000000}
cargo build --release --locked --quiet
bin=target/release/biscara
mkdir -p target/bench
program=target/bench/program-$lines.ngc
[ -f "$program" ] || scripts/gen-program.sh "$lines" > "$program"
bytes=$(stat -c %s "$program")

seconds() { # seconds of wall time of a command, its output discarded
  local start end
  start=$(date +%s.%N); "$@" > /dev/null 2>&1; end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}

samples=$("$bin" interpolate "$program" 2> /dev/null | tail -n +2 | wc -l)
interpret_s=$(seconds "$bin" interpret "$program")
joints_s=$(seconds "$bin" joints "$program")
/usr/bin/time -v -o target/bench/time.txt "$bin" joints "$program" > /dev/null 2>&1
rss_kb=$(awk '/Maximum resident/ {print $6}' target/bench/time.txt)

printf 'program: %s lines, %.1f MB, %s samples (dt 1 ms, trapezoid)\n' "$lines" "$(echo "$bytes / 1000000" | bc -l)" "$samples"
printf 'interpret: %.2f s, %.1f MB/s\n' "$interpret_s" "$(echo "$bytes / 1000000 / $interpret_s" | bc -l)"
printf 'joints (G-code in, CSV out): %.2f s, %.2f M samples/s\n' "$joints_s" "$(echo "$samples / 1000000 / $joints_s" | bc -l)"
printf 'joints peak resident memory: %.1f MiB\n' "$(echo "$rss_kb / 1024" | bc -l)"
