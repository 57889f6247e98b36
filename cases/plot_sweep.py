#!/usr/bin/env python3
"""Plots from sweep.csv files (slump -sweep), rendered by gnuplot (Debian
package gnuplot-nox, installed by cases/setup.sh).

  python3 cases/plot_sweep.py arrest SWEEP.csv[:LABEL] ... --x COLUMN [--panel COLUMN] [--invert-x] --out FIG.png
      arrest time (first criterion) against the swept COLUMN on a log axis,
      one curve per file, one panel per value of --panel, with the exact
      model's stopping time and arrest time as horizontal lines.
  python3 cases/plot_sweep.py error SWEEP.csv[:LABEL] ... --x COLUMN [--curve COLUMN] [--invert-x] --out FIG.png
      arrest-time error against the exact model (arrest_error) and the wall
      time, against COLUMN (log-log), one curve per file and value of --curve.
  python3 cases/plot_sweep.py work SWEEP.csv[:LABEL] ... [--curve COLUMN] [--error COLUMN] [--work COLUMN] --out FIG.png
      work-precision: the error column (default arrest_error) against the
      work column (default wall_time; e.g. res_evals), one curve per file
      (and value of --curve), points in sweep order.
--x stiffness stands for the regularisation's stiffness: m for the
Papanastasiou models, 1/eps for the others. Rows whose status is not 'ok'
are left out (and counted)."""
import argparse
import csv
import os
import subprocess
import sys
import tempfile


def load(spec):
    path, _, label = spec.partition(":")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    bad = [r for r in rows if r["status"] != "ok"]
    if bad:
        print("%s: %d of %d rows left out (status %s)" % (path, len(bad), len(rows), ", ".join(sorted(set(r["status"] for r in bad)))))
    return label or os.path.basename(os.path.dirname(os.path.abspath(path))), [r for r in rows if r["status"] == "ok"]


def num(r, k):
    try:
        return float(r[k])
    except (KeyError, ValueError):
        return None


def gnuplot(script):
    p = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
    if p.returncode != 0:
        sys.exit("gnuplot failed: " + p.stderr)


def write_data(tmp, name, pts):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        for p in pts:
            f.write(" ".join("%.10g" % v for v in p) + "\n")
    return path


def xval(r, a):
    if a.x == "stiffness":
        # m for the Papanastasiou models, 1/eps for the eps ones
        v = num(r, "regularisation_value")
        if v is None or v <= 0:
            return None
        return v if r.get("regularisation") == "m" else 1.0 / v
    x = num(r, a.x)
    if x is None or x <= 0:
        return None
    return 1.0 / x if a.invert_x else x


def plot_arrest(a, sets, tmp):
    panels = sorted(set(r.get(a.panel, "") for _, rows in sets for r in rows), key=lambda v: float(v) if v.replace(".", "", 1).replace("e", "", 1).replace("-", "").isdigit() else v) if a.panel else [""]
    s = ["set terminal pngcairo size %d,%d font ',10'" % (420 * len(panels), 400), "set output '%s'" % a.out,
         "set multiplot layout 1,%d title '%s'" % (len(panels), a.title or "arrest time against the regularisation"), "set logscale x", "set format x '10^{%L}'",
         "set xlabel '%s'" % (a.xlabel or (("1/" if a.invert_x else "") + a.x).replace("_", "\\_")), "set ylabel 'arrest time'", "set key bottom right"]
    for pv in panels:
        plots = []
        exact_stop = exact_arrest = None
        for i, (label, rows) in enumerate(sets):
            pts = sorted((xval(r, a), num(r, "t_arrest")) for r in rows if (not a.panel or r.get(a.panel) == pv) and xval(r, a) and num(r, "t_arrest") is not None)
            for r in rows:
                if not a.panel or r.get(a.panel) == pv:
                    exact_stop = num(r, "t_stop_exact") or exact_stop
                    exact_arrest = num(r, "t_arrest_exact") or exact_arrest
            if pts:
                plots.append("'%s' u 1:2 w lp pt %d title '%s'" % (write_data(tmp, "a%s_%d" % (pv, i), pts), 5 + 2 * i, label))
        if exact_stop:
            plots.append("%.10g w l dt 2 lc rgb 'black' title 'exact stop %.5g'" % (exact_stop, exact_stop))
        if exact_arrest:
            plots.append("%.10g w l dt 3 lc rgb '#aa0000' title 'exact, same criterion %.5g'" % (exact_arrest, exact_arrest))
        s.append("set title '%s'" % ("%s = %s" % (a.panel, pv) if a.panel else ""))
        s.append("plot " + ", ".join(plots) if plots else "plot 0 notitle")
    s.append("unset multiplot")
    gnuplot("\n".join(s) + "\n")


def curves(a, sets):
    out = []
    for label, rows in sets:
        keys = sorted(set(r.get(a.curve, "") for r in rows), key=lambda v: (len(v), v)) if a.curve else [""]
        for k in keys:
            sub = [r for r in rows if not a.curve or r.get(a.curve) == k]
            out.append(("%s %s=%s" % (label, a.curve, k) if a.curve else label, sub))
    return out


def plot_error(a, sets, tmp):
    s = ["set terminal pngcairo size 900,400 font ',10'", "set output '%s'" % a.out, "set multiplot layout 1,2 title '%s'" % (a.title or ""),
         "set logscale xy", "set format x '10^{%L}'", "set format y '10^{%L}'", "set key outside right", "set xlabel '%s'" % (a.xlabel or (("1/" if a.invert_x else "") + a.x).replace("_", "\\_"))]
    for col, ylabel in ((a.error, "relative arrest-time error"), ("wall_time", "wall time (s)")):
        plots = []
        for i, (label, rows) in enumerate(curves(a, sets)):
            pts = sorted((xval(r, a), num(r, col)) for r in rows if xval(r, a) and num(r, col))
            if pts:
                plots.append("'%s' u 1:2 w lp pt %d lc %d title '%s'" % (write_data(tmp, "e%s_%d" % (col, i), pts), 4 + i, i + 1, label.replace("_", "\\_")))
        s += ["set ylabel '%s'" % ylabel, "plot " + (", ".join(plots) if plots else "0 notitle")]
    s.append("unset multiplot")
    gnuplot("\n".join(s) + "\n")


def plot_work(a, sets, tmp):
    xlabel = {"wall_time": "wall time (s)", "res_evals": "residual evaluations"}.get(a.work, a.work.replace("_", " "))
    s = ["set terminal pngcairo size 760,560 font ',10'", "set output '%s'" % a.out, "set title '%s'" % (a.title or "work-precision"), "set logscale xy",
         "set format x '10^{%L}'", "set format y '10^{%L}'", "set xlabel '%s'" % xlabel, "set ylabel '%s'" % a.error.replace("_", " "), "set key below"]
    plots = []
    for i, (label, rows) in enumerate(curves(a, sets)):
        pts = [(num(r, a.work), num(r, a.error)) for r in rows if num(r, a.work) and num(r, a.error)]
        if pts:
            plots.append("'%s' u 1:2 w lp pt %d lc %d title '%s'" % (write_data(tmp, "w%d" % i, pts), 4 + i % 10, i + 1, label.replace("_", "\\_")))
    s.append("plot " + (", ".join(plots) if plots else "0 notitle"))
    gnuplot("\n".join(s) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["arrest", "error", "work"])
    ap.add_argument("csv", nargs="+", help="sweep.csv[:label]")
    ap.add_argument("--x", help="swept column on the x axis (arrest, error)")
    ap.add_argument("--xlabel")
    ap.add_argument("--work", default="wall_time", help="work column of the work-precision plot (wall_time, res_evals, ...)")
    ap.add_argument("--invert-x", action="store_true", help="plot 1/x (e.g. 1/eps next to m)")
    ap.add_argument("--panel", help="one panel per value of this column (arrest)")
    ap.add_argument("--curve", help="one curve per value of this column (error, work)")
    ap.add_argument("--error", default="arrest_error")
    ap.add_argument("--title")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    if a.kind in ("arrest", "error") and not a.x:
        ap.error("--x COLUMN is needed for '%s'" % a.kind)
    sets = [load(c) for c in a.csv]
    with tempfile.TemporaryDirectory() as tmp:
        {"arrest": plot_arrest, "error": plot_error, "work": plot_work}[a.kind](a, sets, tmp)
    print("wrote " + a.out)


if __name__ == "__main__":
    main()
