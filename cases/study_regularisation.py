#!/usr/bin/env python3
"""Regularisation studies (a study, not a test): one command writes CSV tables
and gnuplot figures into docs/studies/ and prints the tables.

1. Error against the analytic solution vs the regularisation parameter, on
   three meshes (after Chauchat & Medale 2014, Fig. 5): where regularisation
   error gives way to discretisation error.
     - mu(I) Bagnold flow, mui_cm (their eq. 12), lambda_r = 1e-1 ... 1e-7,
       4, 8, 16 cells across the layer;
     - Bingham plane Poiseuille (Bn = 0.3), Papanastasiou m = 1e1 ... 1e7,
       16, 32, 64 cells across the channel.
3. The duct (Mosolov problem): flow rate and plug area against Bn, with the
   exact flow threshold Bn_c = 1/(2 + sqrt(pi)).
2. Cost at equal accuracy (after their Fig. 3b and Table 1): for each of the
   four mu(I) regularisations on Bagnold (16 cells), the largest lambda_r
   (decades) whose relative L2 error is <= 1e-3, with the Newton iterations
   (continuation from 1e-1 included) and the wall time of that run.

usage: python3 cases/study_regularisation.py [--slump build/slump] [--out out/studies]
Needs gnuplot (Debian package gnuplot-nox) for the figures.
"""
import argparse
import csv
import os
import shutil
import subprocess
import tempfile


def run(slump, scene, opts):
    with tempfile.TemporaryDirectory() as d:
        p = subprocess.run([slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0"] + opts, capture_output=True, text=True)
        if p.returncode != 0:
            return None
        with open(os.path.join(d, "summary.csv")) as f:
            return next(csv.DictReader(f))


def rel(s):
    return float(s["err_u_l2"]) / float(s["norm_u_l2"])


def plot(out, name, title, xlabel, columns, reverse_x):
    """Log-log plot of relative error against the parameter, one curve per mesh."""
    if not shutil.which("gnuplot"):
        print("gnuplot not found: skipping %s.png (apt-get install gnuplot-nox)" % name)
        return
    curves = ", ".join("'%s.csv' using 1:%d with linespoints lw 2 pt 7 title '%s'" % (name, k + 2, c) for k, c in enumerate(columns))
    script = """set terminal pngcairo size 800,560 font ',11'
set output '%s.png'
set datafile separator ','
set logscale xy
set format x '10^{%%L}'
set format y '10^{%%L}'
set grid
%s
set xlabel '%s'
set ylabel 'relative L2 velocity error'
set title '%s'
set key bottom left
plot %s
""" % (name, "set xrange [*:*] reverse" if reverse_x else "", xlabel, title, curves)
    subprocess.run(["gnuplot"], input=script, text=True, cwd=out, check=True)


def sweep(slump, out, name, scene, base, param, values, meshes, meshopt, start_opt, title, xlabel, reverse_x):
    rows = []
    for v in values:
        row = [v]
        for n in meshes:
            opts = base + [param, "%g" % v, meshopt, str(n)] + start_opt(v)
            s = run(slump, scene, opts)
            row.append(rel(s) if s else float("nan"))
        rows.append(row)
        print("%-10g " % v + " ".join("%.3e" % x for x in row[1:]), flush=True)
    with open(os.path.join(out, name + ".csv"), "w") as f:
        f.write("%s,%s\n" % (param.lstrip("-"), ",".join("n%d" % n for n in meshes)))
        for r in rows:
            f.write(",".join("%.6e" % x for x in r) + "\n")
    plot(out, name, title, xlabel, ["%d cells across" % n for n in meshes], reverse_x)
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/studies", help="where the CSV files and figures go (docs/studies for the documentation's)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    slump = os.path.abspath(a.slump)

    print("1a. Bagnold, mui_cm: relative L2 error vs lambda_r (columns: 4, 8, 16 cells)")
    lams = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7]
    sweep(slump, a.out, "bagnold_error_vs_lambda", "bagnold", [], "-rheology_mui_lambda_r", lams, [4, 8, 16], "-mesh_ny",
          lambda v: ["-steady_continuation_start", "0.1"] if v < 0.1 else [],
          "mu(I) Bagnold flow, regularisation (12)", "lambda_r", True)

    print("1b. Poiseuille, Papanastasiou: relative L2 error vs m (columns: 16, 32, 64 cells)")
    ms = [1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7]
    sweep(slump, a.out, "poiseuille_error_vs_m", "poiseuille", [], "-rheology_papanastasiou_m", ms, [16, 32, 64], "-mesh_ny",
          lambda v: ["-steady_continuation_start", "10"] if v > 10 else [],
          "Bingham plane Poiseuille, Bn = 0.3, Papanastasiou", "m", False)

    duct(slump, a.out)

    print("2. mu(I) regularisations at equal accuracy (relative L2 error <= 1e-3, Bagnold, 16 cells)")
    table = []
    for t in ("mui_cm", "mui_bercovier", "mui_papanastasiou", "mui_simple"):
        found = None
        for lam in lams:
            opts = ["-rheology_type", t, "-rheology_mui_lambda_r", "%g" % lam, "-mesh_ny", "16"] + (["-steady_continuation_start", "0.1"] if lam < 0.1 else [])
            s = run(slump, "bagnold", opts)
            if s and rel(s) <= 1e-3:
                found = (lam, rel(s), int(s["newton_its"]), float(s["wall_time"]))
                break
        table.append((t, found))
        if found:
            print("%-18s lambda_r %-8g error %.3e  Newton %3d  wall %.3f s" % ((t,) + found))
        else:
            print("%-18s no lambda_r >= 1e-7 reaches 1e-3" % t)
    with open(os.path.join(a.out, "mui_equal_accuracy.csv"), "w") as f:
        f.write("model,lambda_r,rel_error,newton_its,wall_time\n")
        for t, r in table:
            f.write("%s,%s\n" % (t, ",".join("%g" % x for x in r) if r else "none,,,"))


def duct(slump, out):
    print("3. Duct: flow rate (relative to Newtonian) and plug area vs Bn (16 x 16, m = 1e5)")
    rows = []
    for bn in (0.0, 0.025, 0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2, 0.225, 0.25, 0.26, 0.27, 0.28, 0.3):
        opts = ["-bn", "%g" % bn, "-rheology_papanastasiou_m", "1e5"] + (["-steady_continuation_start", "1e2"] if bn > 0 else [])
        s = run(slump, "duct", opts)
        q, qn, plug, bnc = float(s["flow_rate"]), float(s["flow_rate_newtonian"]), float(s["plug_area"]), float(s["bn_critical"])
        rows.append((bn, q / qn, plug))
        print("Bn %-6g Q/Q_newtonian %.4e  plug area %.4f" % (bn, q / qn, plug), flush=True)
    with open(os.path.join(out, "duct_threshold.csv"), "w") as f:
        f.write("bn,flow_rate_over_newtonian,plug_area\n")
        for r in rows:
            f.write("%g,%.6e,%.6f\n" % r)
    if shutil.which("gnuplot"):
        script = """set terminal pngcairo size 800,560 font ',11'
set output 'duct_threshold.png'
set datafile separator ','
set logscale y
set format y '10^{%%L}'
set y2range [0:1.05]
set y2tics
set ytics nomirror
set grid
set xlabel 'Bn = tau_0 / (G L)'
set ylabel 'flow rate / Newtonian flow rate'
set y2label 'plug (unyielded) area / L^2'
set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lw 2
set label 'Bn_c = 1/(2+sqrt(pi))' at %g, graph 0.9 right offset -1,0
set title 'Square duct (Mosolov problem), Papanastasiou m = 1e5'
set key center left
plot 'duct_threshold.csv' using 1:2 axes x1y1 with linespoints lw 2 pt 7 title 'flow rate', \\
     'duct_threshold.csv' using 1:3 axes x1y2 with linespoints lw 2 pt 5 title 'plug area'
""" % (bnc, bnc, bnc)
        subprocess.run(["gnuplot"], input=script, text=True, cwd=out, check=True)


if __name__ == "__main__":
    main()
