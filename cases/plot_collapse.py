#!/usr/bin/env python3
"""Plot a collapse run (scenes dam_break, bingham_dam_break, column_collapse):
the front x_max and the material height on the symmetry axis against time,
in the units of the column (Z = x/r_i, H = h/h_i; T = t sqrt(2 g / r_i) as
in Martin & Moyce, or T = t sqrt(g / h_i) with --time-scale gravity, the
default for column_collapse), with the reference data if given, the energy
partition (kinetic, potential released, dissipated, and the potential
energy the reinitialisations and volume corrections added) and, when the run wrote
deposit.csv, the final deposit over the initial column. With --compare
DIR (repeatable) the deposits of other runs of the same column are drawn
on the same axes and their differences from this run's deposit printed:
the largest height difference and the L1 difference over the deposit's
area (both in units of h_i and of the area).

usage: python3 cases/plot_collapse.py OUTPUT_DIR [--reference CSV] [--g 9.81]
                                      [--compare DIR [--compare DIR ...]]
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


def profile(path):
    """(x, h) pairs of a deposit.csv, sorted in x; h = 0 where the column is empty"""
    out = []
    for r in rows(path):
        h = float(r["height"])
        out.append((float(r["x"]), 0.0 if math.isnan(h) else h))
    return sorted(out)


def height_at(prof, x):
    """the profile's height at x, linear between samples, 0 beyond them"""
    if x < prof[0][0] or x > prof[-1][0]:
        return 0.0
    for (x0, h0), (x1, h1) in zip(prof, prof[1:]):
        if x <= x1:
            return h0 if x1 == x0 else h0 + (h1 - h0) * (x - x0) / (x1 - x0)
    return prof[-1][1]


def area(prof):
    return sum(0.5 * (x1 - x0) * (h0 + h1) for (x0, h0), (x1, h1) in zip(prof, prof[1:]))


def thick_front(prof, hi):
    """the last x where the deposit is at least 5 % of h_i thick"""
    xs = [x for x, h in prof if h >= 0.05 * hi]
    return xs[-1] if xs else 0.0


def difference(p, q):
    """largest |p - q| and the L1 norm of p - q, on the union of both samples"""
    xs = sorted(set(x for x, _ in p) | set(x for x, _ in q))
    d = [abs(height_at(p, x) - height_at(q, x)) for x in xs]
    return max(d), sum(0.5 * (x1 - x0) * (d0 + d1) for x0, x1, d0, d1 in zip(xs, xs[1:], d, d[1:]))


def compared_deposits(a, ri, hi):
    """the --compare runs' deposits, after checking they are runs of the same column"""
    if len(a.compare_label) > len(a.compare):
        raise SystemExit("plot_collapse.py: %d --compare-label for %d --compare; give at most one label per --compare DIR"
                         % (len(a.compare_label), len(a.compare)))
    out = []
    for k, d in enumerate(a.compare):
        dep, summ = os.path.join(d, "deposit.csv"), os.path.join(d, "summary.csv")
        if not (os.path.exists(dep) and os.path.exists(summ)):
            raise SystemExit("plot_collapse.py: --compare %s: no deposit.csv and summary.csv there; give the output directory of a finished collapse run" % d)
        s = rows(summ)[0]
        if abs(float(s["column_width"]) - ri) > 1e-12 * ri or abs(float(s["column_height"]) - hi) > 1e-12 * hi:
            raise SystemExit("plot_collapse.py: --compare %s: its column is %s x %s, not %g x %g; compare runs of the same column"
                             % (d, s["column_width"], s["column_height"], ri, hi))
        label = a.compare_label[k] if k < len(a.compare_label) else d
        out.append(("%s, t = %.4g" % (label, float(s["t_final"])), profile(dep)))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--reference", default=None, help="CSV with columns T,Z (front)")
    ap.add_argument("--reference-height", default=None, help="CSV with columns T,H (height on the axis)")
    ap.add_argument("--reference-title", default="reference", help="legend of the reference points")
    ap.add_argument("--g", type=float, default=9.81)
    ap.add_argument("--title", default=None)
    ap.add_argument("--label", default="deposit", help="legend of this run's deposit")
    ap.add_argument("--compare", action="append", default=[], metavar="DIR",
                    help="another run's output directory whose deposit is overlaid (repeatable)")
    ap.add_argument("--compare-label", action="append", default=[], metavar="TEXT",
                    help="legend of the matching --compare run (default: its directory)")
    ap.add_argument("--time-scale", choices=["martin", "gravity"], default=None,
                    help="T = t sqrt(2 g/r_i) (martin, default) or t sqrt(g/h_i) (gravity, default for column_collapse)")
    a = ap.parse_args()
    s = rows(os.path.join(a.dir, "summary.csv"))[0]
    ri, hi = float(s["column_width"]), float(s["column_height"])
    others = compared_deposits(a, ri, hi)  # checked before anything is written
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
    # energies: potential released, kinetic, dissipated: the run's own total
    # over its steps (material, ambient fluid and friction walls), or in runs
    # older than that column the material's dissipation integrated over the
    # outputs (trapezoidal rule)
    ser = rows(os.path.join(a.dir, "series.csv"))
    ep0 = float(ser[0]["potential_energy"])
    total = "dissipated" in ser[0]
    diss, prev, j = 0.0, None, 0
    # potential energy added by the reinitialisations and volume corrections
    # (interface.csv, one row per step; absent in runs older than the tally)
    tally = "energy_reinit" in ifc[0]
    with open(os.path.join(a.dir, "energy.dat"), "w") as f:
        for r in ser:
            t, d = float(r["t"]), float(r["dissipation"])
            if total:
                diss = float(r["dissipated"]) - float(ser[0]["dissipated"])
            elif prev:
                diss += 0.5 * (t - prev[0]) * (d + prev[1])
            prev = (t, d)
            while j + 1 < len(ifc) and float(ifc[j + 1]["t"]) <= t * (1 + 1e-12):
                j += 1
            added = float(ifc[j]["energy_reinit"]) + float(ifc[j]["energy_correction"]) if tally else 0.0
            f.write("%.8g %.8g %.8g %.8g %.8g\n" % (t, ep0 - float(r["potential_energy"]), float(r["kinetic_energy"]), diss, added))
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
plot 'energy.dat' using 1:2 with lines lw 2 title 'potential energy released', 'energy.dat' using 1:3 with lines lw 2 title 'kinetic', 'energy.dat' using 1:4 with lines lw 2 title '%s'%s
""" % (title.replace("'", ""), tlabel, ", ".join(plots), "dissipated (material, ambient, walls)" if total else "dissipated (material)",
       ", 'energy.dat' using 1:5 with lines lw 2 title 'added by reinitialisation and volume correction', 'energy.dat' using 1:($2+$5-$3-$4) with lines dt 2 lw 2 lc 'black' title 'released + added - kinetic - dissipated'"
       if tally else ", 'energy.dat' using 1:($2-$3-$4) with lines dt 2 title 'released - kinetic - dissipated'")
    wrote = ["front.png", "energy.png"]
    dep = os.path.join(a.dir, "deposit.csv")
    if os.path.exists(dep):
        mine = profile(dep)
        label = "%s, t = %.4g" % (a.label, float(s["t_final"])) if others else a.label
        with open(os.path.join(a.dir, "deposit.dat"), "w") as f:
            for x, h in mine:
                f.write("%.8g %.8g\n" % (x / ri, h / hi))
        with open(os.path.join(a.dir, "column.dat"), "w") as f:
            f.write("0 1\n1 1\n1 0\n")
        dplots = ["'column.dat' using 1:2 with lines dt 2 lw 2 title 'initial column'",
                  "'deposit.dat' using 1:2 with lines lw 2 title '%s'" % label.replace("'", "")]
        print("%-28s axis height %.4g h_i, front (h >= 5 %% h_i) %.4g r_i" % (label, mine[0][1] / hi, thick_front(mine, hi) / ri))
        for k, (olabel, other) in enumerate(others):
            name = "deposit_compare_%d.dat" % k
            with open(os.path.join(a.dir, name), "w") as f:
                for x, h in other:
                    f.write("%.8g %.8g\n" % (x / ri, h / hi))
            dplots.append("'%s' using 1:2 with lines lw 2 title '%s'" % (name, olabel.replace("'", "")))
            dmax, dl1 = difference(mine, other)
            print("%-28s axis height %.4g h_i, front (h >= 5 %% h_i) %.4g r_i; against %s: max |dh| %.4g h_i, L1 %.4g of the area"
                  % (olabel, other[0][1] / hi, thick_front(other, hi) / ri, a.label, dmax / hi, dl1 / area(mine)))
        script += """set output 'deposit.png'
set title '%s: %s'
set xlabel 'x / r_i'
set ylabel 'h / h_i'
set key top right
set size ratio -1
plot %s
""" % (title.replace("'", ""), "deposits" if others else "deposit at t = %g" % float(s["t_final"]), ", ".join(dplots))
        wrote.append("deposit.png")
    subprocess.run(["gnuplot"], input=script, text=True, cwd=a.dir, check=True)
    print("wrote " + ", ".join(os.path.join(a.dir, w) for w in wrote))


if __name__ == "__main__":
    main()
