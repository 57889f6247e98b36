#!/usr/bin/env python3
"""Plot a collapse run (scenes dam_break, bingham_dam_break): the front
x_max and the material height on the symmetry axis against time, in the
units of the column (Z = x/r_i, H = h/h_i, T = t sqrt(2 g / r_i) for
dam_break as in Martin & Moyce), with the reference data if given, and the
energy partition (kinetic, potential released, dissipated).

usage: python3 cases/plot_collapse.py OUTPUT_DIR [--reference CSV] [--g 9.81]
Reads interface.csv, series.csv and summary.csv; writes OUTPUT_DIR/front.png
and OUTPUT_DIR/energy.png with gnuplot (Debian package gnuplot-nox). The
reference CSV has columns T,Z (front) and optionally T,H in a second file
given by --reference-height."""
import argparse
import csv
import math
import os
import subprocess


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--reference", default=None, help="CSV with columns T,Z (front)")
    ap.add_argument("--reference-height", default=None, help="CSV with columns T,H (height on the axis)")
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--title", default=None)
    a = ap.parse_args()
    s = rows(os.path.join(a.dir, "summary.csv"))[0]
    ri, hi = float(s["column_width"]), float(s["column_height"])
    tscale = math.sqrt(2.0 * a.g / ri)
    ifc = rows(os.path.join(a.dir, "interface.csv"))
    axis = [k for k in ifc[0] if k.startswith("height_at_")][0]
    with open(os.path.join(a.dir, "front.dat"), "w") as f:
        for r in ifc:
            h = float(r[axis]) if r[axis] != "nan" else 0.0
            f.write("%.8g %.8g %.8g\n" % (float(r["t"]) * tscale, float(r["x_max"]) / ri, h / hi))
    # energies: potential released, kinetic, dissipated (trapezoidal in time)
    ser = rows(os.path.join(a.dir, "series.csv"))
    ep0 = float(ser[0]["potential_energy"])
    diss, prev = 0.0, None
    with open(os.path.join(a.dir, "energy.dat"), "w") as f:
        for r in ser:
            t, d = float(r["t"]), float(r["dissipation"])
            if prev:
                diss += 0.5 * (t - prev[0]) * (d + prev[1])
            prev = (t, d)
            f.write("%.8g %.8g %.8g %.8g\n" % (t, ep0 - float(r["potential_energy"]), float(r["kinetic_energy"]), diss))
    title = a.title or "%s, %s cells" % (s["scene"], s["cells"])
    plots = ["'front.dat' using 1:2 with lines lw 2 title 'front Z = x_f / r_i'",
             "'front.dat' using 1:3 with lines lw 2 title 'height on the axis H = h / h_i'"]
    if a.reference:
        plots.append("'%s' using 1:2 with points pt 7 title 'front, reference'" % os.path.abspath(a.reference))
    if a.reference_height:
        plots.append("'%s' using 1:2 with points pt 5 title 'height, reference'" % os.path.abspath(a.reference_height))
    script = """set terminal pngcairo size 800,550 noenhanced
set output 'front.png'
set title '%s'
set xlabel 'T = t sqrt(2 g / r_i)'
set key top left
set grid
plot %s
set output 'energy.png'
set xlabel 't'
set ylabel 'energy per unit depth'
set key top left
plot 'energy.dat' using 1:2 with lines lw 2 title 'potential energy released', 'energy.dat' using 1:3 with lines lw 2 title 'kinetic', 'energy.dat' using 1:4 with lines lw 2 title 'dissipated (material)', 'energy.dat' using 1:($2-$3-$4) with lines dt 2 title 'released - kinetic - dissipated'
""" % (title.replace("'", ""), ", ".join(plots))
    subprocess.run(["gnuplot"], input=script, text=True, cwd=a.dir, check=True)
    print("wrote %s/front.png and %s/energy.png" % (a.dir, a.dir))


if __name__ == "__main__":
    main()
