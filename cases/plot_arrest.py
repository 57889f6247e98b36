#!/usr/bin/env python3
"""Plot a run's step history: h(t) (log scale) with the arrest times marked,
above the diagnostics that triggered them with their thresholds.

usage: python3 cases/plot_arrest.py OUTPUT_DIR [--title TEXT]
Reads steps.csv, series.csv and summary.csv of a slump run and writes
OUTPUT_DIR/arrest.png with gnuplot (Debian package gnuplot-nox)."""
import argparse
import csv
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--title", default=None)
    a = ap.parse_args()
    with open(os.path.join(a.dir, "summary.csv")) as f:
        s = next(csv.DictReader(f))
    crit = []
    for k, v in s.items():
        # an arrest criterion's columns come in pairs, t_arrest_NAME and
        # threshold_NAME; t_arrest_exact (the exact model's time) has no threshold
        name = k[len("t_arrest_"):]
        if k.startswith("t_arrest_") and "threshold_" + name in s and v and float(v) >= 0:
            crit.append((name, float(v), float(s["threshold_" + name])))
    if not crit:
        print("no arrest time in %s/summary.csv" % a.dir)
    cols = {}
    with open(os.path.join(a.dir, "series.csv")) as f:
        for i, c in enumerate(next(csv.reader(f))):
            cols[c] = i + 1
    title = a.title or "%s: %s %s = %s" % (s["scene"], s["rheology"], s["regularisation"], s["regularisation_value"])
    arrows = "\n".join("set arrow from %.10g, graph 0 to %.10g, graph 1 nohead dt 2 lc rgb '#aa0000'" % (t, t) for _, t, _ in crit)
    plots = []
    for name, t, thr in crit:
        base = name.replace("_relative", "").replace("_creep", "").split("_0")[0]
        if base in cols:
            plots.append((base, thr, name))
    seen = []
    lines = []
    for base, thr, name in plots:
        if base not in seen:
            lines.append("'series.csv' using 1:%d with lines lw 2 title '%s'" % (cols[base], base.replace("_", " ")))
            seen.append(base)
        lines.append("%.10g with lines dt 3 lw 1 title 'threshold (%s)'" % (thr, name.replace("_", " ")))
    script = """set terminal pngcairo size 900,800 font ',11' noenhanced
set output 'arrest.png'
set datafile separator ','
set multiplot layout 2,1 title '%s'
set logscale y
set format y '1e%%L'
set grid
%s
set ylabel 'step size h'
set xlabel ''
plot 'steps.csv' using 1:2 with linespoints pt 7 ps 0.3 title 'h (IDA steps)'
set ylabel 'diagnostic'
set yrange [1e-8:*]
set xlabel 't'
plot %s
unset multiplot
""" % (title.replace("'", ""), arrows, ", ".join(lines) if lines else "'series.csv' using 1:3 with lines title 'mean shear rate'")
    subprocess.run(["gnuplot"], input=script, text=True, cwd=a.dir, check=True)
    print("wrote %s" % os.path.join(a.dir, "arrest.png"))


if __name__ == "__main__":
    sys.exit(main())
