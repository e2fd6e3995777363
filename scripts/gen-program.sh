#!/usr/bin/env bash
# Writes a long G-code program to stdout for benchmarks: LINES lines (default 1,000,000) of short
# feed moves zig-zagging through the reduced workspace of the default robot, with C turning.
# Usage: scripts/gen-program.sh [LINES] > program.ngc
set -euo pipefail
lines=${1:-1000000}
awk -v n="$lines" 'BEGIN {
  print "%"
  print "(benchmark program: " n " lines)"
  print "G21 G17 G90 G94"
  print "G0 X-100 Y300 Z50 C0"
  for (i = 0; i < n - 6; i++) {
    col = i % 200; row = int(i / 200) % 100
    x = (row % 2 == 0) ? -100 + col : 99 - col
    printf "G1 X%.3f Y%.3f C%.3f F6000\n", x, 300 + row, (i % 90) - 45
  }
  print "M2"
  print "%"
}'
