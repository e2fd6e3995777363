#!/usr/bin/env bash
# The cost of the motors (issue 36): `joints --torques` with a robot that has motors (the
# torque-limited optimal profile, and each row's inverse dynamics written) against `joints` on
# the built-in robot without motors, on the same generated program (output to /dev/null, one
# core, median user CPU time of 7 interleaved runs). Target: at most 1.3×.
#   mixed      100,000 lines of G0/G1/G2/G3 with X Y Z C (scripts/gen-program.sh mixed)
# Usage: benches/torques.sh [ROBOT]   (default data/robots/servo-example.json)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
robot=${1:-data/robots/servo-example.json}
cargo build --release --locked --quiet --bin biscara
bin=$PWD/target/release/biscara
work=target/bench
mkdir -p "$work"
program=$work/mixed-100000.ngc
[ -f "$program" ] || scripts/gen-program.sh mixed 100000 > "$program"

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

plain=() torques=() limited=()
for _ in 1 2 3 4 5 6 7; do
  /usr/bin/time -f "%U" -o "$work/time.txt" "$bin" joints "$program" -o /dev/null 2> /dev/null
  plain+=("$(cat "$work/time.txt")")
  /usr/bin/time -f "%U" -o "$work/time.txt" "$bin" --robot "$robot" joints "$program" -o /dev/null 2> /dev/null
  limited+=("$(cat "$work/time.txt")")
  /usr/bin/time -f "%U" -o "$work/time.txt" "$bin" --robot "$robot" joints --torques "$program" -o /dev/null 2> /dev/null
  torques+=("$(cat "$work/time.txt")")
done
p=$(printf '%s\n' "${plain[@]}" | median)
l=$(printf '%s\n' "${limited[@]}" | median)
t=$(printf '%s\n' "${torques[@]}" | median)
samples=$("$bin" --robot "$robot" joints "$program" 2> /dev/null | tail -n +2 | wc -l)
echo "mixed 100,000 lines ($samples samples with $robot), user CPU s, median of 7:"
echo "  joints (no motors)                  $p"
echo "  joints, motors (torque-limited)     $l  ($(awk -v a="$l" -v b="$p" 'BEGIN { printf "%.2f", a / b }')x)"
echo "  joints --torques, motors            $t  ($(awk -v a="$t" -v b="$p" 'BEGIN { printf "%.2f", a / b }')x; target <= 1.3x)"
echo "($(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
