#!/usr/bin/env python3
"""Yielded and unyielded regions of a steady run, as a figure.

Reads <run>/yield_map.csv (x, y, yielded at every quadrature point, written by
every steady run) and, when present, <run>/cavity_grid.csv (the cavity's
stream function on a grid): unyielded points are drawn black, yielded ones
light grey, with streamlines (contours of psi) over them. Needs gnuplot
(Debian package gnuplot-nox).

usage: python3 cases/plot_yield.py RUN_DIR [--out FILE.png] [--title TEXT] [--xrange XMIN XMAX]
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--out", help="the PNG to write (default RUN/yield_map.png)")
    ap.add_argument("--title", default="")
    ap.add_argument("--xrange", nargs=2, type=float, metavar=("XMIN", "XMAX"), help="the part of the domain to draw (default: all of it)")
    a = ap.parse_args()
    ymap = os.path.join(a.run, "yield_map.csv")
    if not os.path.exists(ymap):
        sys.exit("plot_yield.py: %s has no yield_map.csv; give the output directory of a steady run" % a.run)
    if not shutil.which("gnuplot"):
        sys.exit("plot_yield.py: gnuplot not found (apt-get install gnuplot-nox)")
    out = os.path.abspath(a.out or os.path.join(a.run, "yield_map.png"))
    with open(ymap) as f:
        rows = list(csv.DictReader(f))
    if a.xrange:
        rows = [r for r in rows if a.xrange[0] <= float(r["x"]) <= a.xrange[1]]
        if not rows:
            sys.exit("plot_yield.py: --xrange %g %g holds no point of the mesh" % tuple(a.xrange))
    xs = [float(r["x"]) for r in rows]
    ys = [float(r["y"]) for r in rows]
    with tempfile.TemporaryDirectory() as tmp:
        for k, name in ((0, "unyielded"), (1, "yielded")):
            with open(os.path.join(tmp, name + ".dat"), "w") as f:
                for r in rows:
                    if int(r["yielded"]) == k:
                        f.write("%s %s\n" % (r["x"], r["y"]))
        grid = os.path.join(a.run, "cavity_grid.csv")
        stream = ""
        if os.path.exists(grid):
            # psi on its grid as gnuplot's matrix-like blocks, then its contours
            with open(grid) as f:
                g = list(csv.DictReader(f))
            with open(os.path.join(tmp, "psi.dat"), "w") as f:
                last = None
                for r in g:
                    if last is not None and r["y"] != last:
                        f.write("\n")
                    last = r["y"]
                    f.write("%s %s %s\n" % (r["x"], r["y"], r["psi"]))
            psis = [float(r["psi"]) for r in g]
            lo, hi = min(psis), max(psis)
            ext = lo if abs(lo) > abs(hi) else hi
            levels = ",".join("%g" % (ext * s) for s in (0.02, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 0.97))
            subprocess.run(["gnuplot"], input="""set table 'contours.dat'
unset surface
set contour base
set cntrparam levels discrete %s
splot 'psi.dat' using 1:2:3 with lines
unset table
""" % levels, text=True, cwd=tmp, check=True)
            stream = ", 'contours.dat' using 1:2 with lines lc rgb '#1f4fd0' lw 1.5 title 'streamlines'"
        script = """set terminal pngcairo size %d,%d font ',11'
set output '%s'
set size ratio -1
set xrange [%g:%g]
set yrange [%g:%g]
set title '%s' noenhanced
set key outside bottom center horizontal
plot 'yielded.dat' with points pt 7 ps 0.35 lc rgb '#d8d8d8' title 'yielded', 'unyielded.dat' with points pt 7 ps 0.35 lc rgb 'black' title 'unyielded'%s
""" % (900, max(260, min(900, int(900 * (max(ys) - min(ys)) / (max(xs) - min(xs)) + 140))), out, min(xs), max(xs), min(ys), max(ys), a.title.replace("'", ""), stream)
        subprocess.run(["gnuplot"], input=script, text=True, cwd=tmp, check=True)
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
