#!/usr/bin/env bash
# Regenerates the figures in docs/: the speed analogue S'(φ) of the MATEC 2018 case (the
# paper's Fig. 2 shape) and Basu's Example 1 cam profile.   bash scripts/figures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh >/dev/null
mkdir -p docs
tmp=$(mktemp -d)
./build/needle synth cases/matec-2018-synth.toml --csv "$tmp/law.csv" >/dev/null || true  # exit 1: undercut check
./build/needle profile cases/basu-example1.toml --csv "$tmp/ex1.csv" >/dev/null
gnuplot <<GP
set datafile separator ","
set terminal svg size 760,440 font "sans,12"
set output "docs/matec-2018-speed.svg"
set title "MATEC 2018 case: speed analogue S' against cam angle (rise and mirrored fall)"
set xlabel "cam angle (deg)"
set ylabel "S' (mm/rad)"
set grid
set key off
plot "$tmp/law.csv" using 1:3 every ::1 with lines lw 2
set output "docs/basu-example1-cam.svg"
set size ratio -1
set title "Basu Example 1 cam (disk 460 mm, roller 90 mm, 1 mm roller play)"
set xlabel "x (mm)"
set ylabel "y (mm)"
plot "$tmp/ex1.csv" using 2:3 every ::1 with lines lw 2
GP
rm -rf "$tmp"
echo "wrote docs/matec-2018-speed.svg and docs/basu-example1-cam.svg"
