#!/usr/bin/env bash
# Writes a long, deterministic G-code program to stdout, for benchmarks. Every move stays inside
# the reduced workspace of the default robot.
#   scripts/gen-program.sh mixed [LINES]      G0/G1/G2/G3 with X Y Z C (default 1,000,000 lines)
#   scripts/gen-program.sh engraving [LINES]  laser-engraving style: short G1 strokes, G0 between
#                                             them, M3/M5 around each stroke (default 200,000)
#   scripts/gen-program.sh [LINES]            the older zig-zag of 1 mm G1 moves with C turning
set -euo pipefail
kind=zigzag
case "${1:-}" in
  mixed|engraving|zigzag) kind=$1; shift ;;
esac
case "$kind" in
  mixed) lines=${1:-1000000} ;;
  engraving) lines=${1:-200000} ;;
  zigzag) lines=${1:-1000000} ;;
esac
awk -v n="$lines" -v kind="$kind" 'BEGIN {
  print "%"
  print "(benchmark program: " kind ", " n " lines)"
  print "G21 G17 G90 G94"
  if (kind == "mixed") {
    for (i = 0; i < n - 4; i++) {
      k = int(i / 4); phase = i % 4
      x = -100 + (k % 40) * 5; y = 300 + (int(k / 40) % 20) * 5
      if (phase == 0) printf "G0 X%.3f Y%.3f Z40.000 C%.3f\n", x, y, (k % 91) - 45
      else if (phase == 1) printf "G1 X%.3f Y%.3f Z30.000 F3000\n", x + 2, y
      else if (phase == 2) printf "G2 X%.3f Y%.3f I1.000 J0.000\n", x + 4, y
      else printf "G3 X%.3f Y%.3f I-1.000 J0.000\n", x + 2, y
    }
  } else if (kind == "engraving") {
    print "G0 Z20"
    for (i = 0; i < n - 6; i++) {
      stroke = int(i / 50); step = i % 50
      x0 = -90 + (stroke % 60) * 3; y0 = 310 + (int(stroke / 60) % 25) * 3
      if (step == 0) printf "G0 X%.3f Y%.3f\n", x0, y0
      else if (step == 1) print "M3 S1000"
      else if (step == 49) print "M5"
      else printf "G1 X%.3f Y%.3f F1800\n", x0 + 0.05 * step, y0 + 0.4 * sin(step * 0.7)
    }
  } else {
    print "G0 X-100 Y300 Z50 C0"
    for (i = 0; i < n - 6; i++) {
      col = i % 200; row = int(i / 200) % 100
      x = (row % 2 == 0) ? -100 + col : 99 - col
      printf "G1 X%.3f Y%.3f C%.3f F6000\n", x, 300 + row, (i % 90) - 45
    }
  }
  print "M2"
  print "%"
}'
