#!/usr/bin/env python3
"""Plot a collapse run (scenes dam_break, bingham_dam_break, column_collapse):
the front x_max and the material height on the symmetry axis against time,
in the units of the column (Z = x/r_i, H = h/h_i; T = t sqrt(2 g / r_i) as
in Martin & Moyce, or T = t sqrt(g / h_i) with --time-scale gravity, the
default for column_collapse), with the reference data if given, the energy
partition (kinetic, potential released, dissipated) and, when the run wrote
deposit.csv, the final deposit over the initial column.

usage: python3 cases/plot_collapse.py OUTPUT_DIR [--reference CSV] [--g 9.81]
Reads interface.csv, series.csv, summary.csv (and deposit.csv); writes
OUTPUT_DIR/front.png, OUTPUT_DIR/energy.png (and OUTPUT_DIR/deposit.png) with
gnuplot (Debian package gnuplot-nox). The reference CSV has columns T,Z
(front) and optionally T,H in a second file given by --reference-height;
lines starting with # are comments (e.g. cases/data/martin_moyce_1952.csv)."""
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
    ap.add_argument("--reference-title", default="reference", help="legend of the reference points")
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--title", default=None)
    ap.add_argument("--time-scale", choices=["martin", "gravity"], default=None,
                    help="T = t sqrt(2 g/r_i) (martin, default) or t sqrt(g/h_i) (gravity, default for column_collapse)")
    a = ap.parse_args()
    s = rows(os.path.join(a.dir, "summary.csv"))[0]
    ri, hi = float(s["column_width"]), float(s["column_height"])
    if a.time_scale is None:
        a.time_scale = "gravity" if s["scene"] == "column_collapse" else "martin"
    if s["scene"] == "column_collapse":
        a.g = 1.0  # the scene is dimensionless
    tscale = math.sqrt(2.0 * a.g / ri) if a.time_scale == "martin" else math.sqrt(a.g / hi)
    tlabel = "T = t sqrt(2 g / r_i)" if a.time_scale == "martin" else "T = t sqrt(g / h_i)"
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
    for ref, name, pt, what in ((a.reference, "reference_front.dat", 7, "front"), (a.reference_height, "reference_height.dat", 5, "height")):
        if ref:
            with open(ref) as f:
                pts = list(csv.DictReader(l for l in f if not l.startswith("#")))
            col = "Z" if what == "front" else "H"
            with open(os.path.join(a.dir, name), "w") as f:
                tlast = float(ifc[-1]["t"]) * tscale
                for r in pts:
                    if float(r["T"]) <= 1.05 * tlast:  # the run's time span
                        f.write("%s %s\n" % (r["T"], r[col]))
            plots.append("'%s' using 1:2 with points pt %d title '%s, %s'" % (name, pt, what, a.reference_title))
    script = """set terminal pngcairo size 800,550 noenhanced
set output 'front.png'
set title '%s'
set xlabel '%s'
set key top left
set grid
plot %s
set output 'energy.png'
set xlabel 't'
set ylabel 'energy per unit depth'
set key top left
plot 'energy.dat' using 1:2 with lines lw 2 title 'potential energy released', 'energy.dat' using 1:3 with lines lw 2 title 'kinetic', 'energy.dat' using 1:4 with lines lw 2 title 'dissipated (material)', 'energy.dat' using 1:($2-$3-$4) with lines dt 2 title 'released - kinetic - dissipated'
""" % (title.replace("'", ""), tlabel, ", ".join(plots))
    wrote = ["front.png", "energy.png"]
    dep = os.path.join(a.dir, "deposit.csv")
    if os.path.exists(dep):
        with open(os.path.join(a.dir, "deposit.dat"), "w") as f:
            for r in rows(dep):
                f.write("%.8g %.8g\n" % (float(r["x"]) / ri, float(r["height"]) / hi))
        with open(os.path.join(a.dir, "column.dat"), "w") as f:
            f.write("0 1\n1 1\n1 0\n")
        script += """set output 'deposit.png'
set title '%s: deposit at t = %s'
set xlabel 'x / r_i'
set ylabel 'h / h_i'
set key top right
set size ratio -1
plot 'column.dat' using 1:2 with lines dt 2 lw 2 title 'initial column', 'deposit.dat' using 1:2 with lines lw 2 title 'deposit'
""" % (title.replace("'", ""), "%g" % float(s["t_final"]))
        wrote.append("deposit.png")
    subprocess.run(["gnuplot"], input=script, text=True, cwd=a.dir, check=True)
    print("wrote " + ", ".join(os.path.join(a.dir, w) for w in wrote))


if __name__ == "__main__":
    main()
