#!/usr/bin/env python3
"""Regularised against exact (a study, not a test): how far Papanastasiou and
Bercovier-Engelman runs are from the unregularised Bingham solution that
-method exact (ALG2 on the same mesh) computes, and what each costs.

For each case the exact run is made once; then one regularised run per
parameter value (Papanastasiou m = 1e1 ... 1e6, continuation from 1e1 above
it; Bercovier eps = 1e-1 ... 1e-6). Measured against the exact run on the
same mesh (so the discretisation error cancels):
  - flow-rate error |Q - Q_exact| / Q_exact (duct; cavity: the error of the
    stream-function maximum; Poiseuille: the L2 velocity error against the
    analytic solution instead);
  - yield-surface error: |A_plug - A_plug,exact| / A_plug,exact, the
    unyielded area (duct, cavity) or the plug half-width (Poiseuille); the
    regularised plug is where ||tau|| <= tau0 at the quadrature points, the
    exact one where ALG2's gamma vanishes;
  - cost: wall time, residual evaluations, Newton (ALG2) iterations.
Cases: duct (Mosolov) Bn 0.1 and 0.2 on 16 x 16 and 32 x 32 cells; plane
Poiseuille Bn 0.3 on 32 cells across; the lid-driven cavity on 32 x 32
cells at Bn 1.392 and 14.04 (Vola et al.'s yield stresses 1.968 and 19.86),
and at Bn 1.392 with inertia, Re 1000.

usage: python3 cases/study_exact.py [--slump build/slump] [--out out/studies] [--only SUBSTRING]
Writes <out>/exact_<case>.csv, exact_flow_<case>.png and exact_plug_<case>.png
(gnuplot), and prints the tables (docs/exact.md quotes them).
"""
import argparse
import csv
import os
import shutil
import subprocess
import tempfile

CASES = [
    ("duct_bn0.1_16", "duct", ["-bn", "0.1"]),
    ("duct_bn0.2_16", "duct", ["-bn", "0.2"]),
    ("duct_bn0.1_32", "duct", ["-bn", "0.1", "-mesh_nx", "32", "-mesh_ny", "32"]),
    ("poiseuille_bn0.3_32", "poiseuille", ["-bn", "0.3"]),
    ("cavity_bn1.39_32", "cavity", ["-bn", "1.3918808", "-output_yield_map", "0"]),
    ("cavity_bn14.0_32", "cavity", ["-bn", "14.044999", "-output_yield_map", "0"]),
    ("cavity_re1000_bn1.39_32", "cavity", ["-bn", "1.3918808", "-re", "1000", "-output_yield_map", "0"]),
]
PAPANASTASIOU = [1e1, 1e2, 1e3, 1e4, 1e5, 1e6]
BERCOVIER = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6]


def run(slump, scene, opts):
    with tempfile.TemporaryDirectory() as d:
        p = subprocess.run([slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0"] + opts, capture_output=True, text=True)
        if p.returncode != 0:
            print("failed: %s %s\n%s" % (scene, " ".join(opts), p.stderr.strip()[-400:]))
            return None
        with open(os.path.join(d, "summary.csv")) as f:
            return {k: (float(v) if k not in ("scene", "rheology", "regularisation", "integrator", "status", "reason") else v) for k, v in next(csv.DictReader(f)).items()}


def metrics(scene, s, ex):
    if scene == "duct":
        flow = abs(s["flow_rate"] - ex["flow_rate"]) / ex["flow_rate"]
        plug = abs(s["plug_area"] - ex["plug_area"]) / ex["plug_area"]
    elif scene == "cavity":
        flow = abs(s["psi_max"] - ex["psi_max"]) / ex["psi_max"]
        plug = abs(s["unyielded_area"] - ex["unyielded_area"]) / ex["unyielded_area"]
    else:
        flow = s["err_u_l2"] / s["norm_u_l2"]
        plug = abs(s["plug_half_width"] - ex["plug_half_width"]) / ex["plug_half_width"]
    return flow, plug


def plot(out, name, ylabel, title):
    if not shutil.which("gnuplot"):
        print("gnuplot not found: skipping %s.png (apt-get install gnuplot-nox)" % name)
        return
    script = """set terminal pngcairo size 800,560 font ',11'
set output '%s.png'
set datafile separator ','
set logscale xy
set format x '10^{%%L}'
set format y '10^{%%L}'
set grid
set xlabel 'wall time of the run [s]'
set ylabel '%s'
set title '%s' noenhanced
set key outside right
plot '%s.dat' index 0 using 1:2 with linespoints lw 2 pt 7 title 'Papanastasiou m', \\
     '%s.dat' index 1 using 1:2 with linespoints lw 2 pt 5 title 'Bercovier eps', \\
     '%s.dat' index 2 using 1:2 with points pt 9 ps 2 title 'exact (ALG2): time'
""" % (name, ylabel, title, name, name, name)
    subprocess.run(["gnuplot"], input=script, text=True, cwd=out, check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/studies")
    ap.add_argument("--only", default="", help="run only the cases whose name contains this")
    a = ap.parse_args()
    slump = os.path.abspath(a.slump)
    os.makedirs(a.out, exist_ok=True)
    for name, scene, opts in CASES:
        if a.only not in name:
            continue
        ex = run(slump, scene, opts + ["-method", "exact"])
        if ex is None:
            continue
        rows = [("exact", 0.0, 0.0, 0.0, ex["wall_time"], ex["res_evals"], ex["newton_its"])]
        for reg, values in (("papanastasiou", PAPANASTASIOU), ("bercovier", BERCOVIER)):
            for v in values:
                o = opts + ["-rheology_type", reg]
                if reg == "papanastasiou":
                    o += ["-rheology_papanastasiou_m", "%g" % v] + (["-steady_continuation_start", "1e1"] if v > 1e1 else [])
                else:
                    o += ["-rheology_bercovier_eps", "%g" % v] + (["-steady_continuation_start", "1e-1"] if v < 1e-1 else [])
                s = run(slump, scene, o)
                if s is None:
                    continue
                flow, plug = metrics(scene, s, ex)
                rows.append((reg, v, flow, plug, s["wall_time"], s["res_evals"], s["newton_its"]))
        path = os.path.join(a.out, "exact_%s.csv" % name)
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["method", "parameter", "flow_error", "plug_error", "wall_time", "res_evals", "iterations"])
            w.writerows(rows)
        fl = {"duct": "flow-rate error", "cavity": "psi_max error"}.get(scene, "L2 velocity error")
        if scene == "cavity":
            print("\n%s: exact (ALG2) %.2f s, %d iterations; psi_max %.6f, unyielded area %.5f" % (name, ex["wall_time"], ex["newton_its"], ex["psi_max"], ex["unyielded_area"]))
        else:
            print("\n%s: exact (ALG2) %.2f s, %d iterations; Q %.7e, plug %.5f" % (name, ex["wall_time"], ex["newton_its"], ex["flow_rate"], ex["plug_area"] if scene == "duct" else ex["plug_half_width"]))
        print("| regularisation | parameter | %s | plug error | wall time [s] | residual evaluations |" % fl)
        print("|---|---|---|---|---|---|")
        for r in rows[1:]:
            print("| %s | %g | %.2e | %.2e | %.2f | %d |" % (r[0], r[1], r[2], r[3], r[4], r[5]))
        for what, col, label in (("flow", 2, fl), ("plug", 3, "plug (yield-surface) error")):
            dat = os.path.join(a.out, "exact_%s_%s.dat" % (what, name))
            with open(dat, "w") as f:
                for reg in ("papanastasiou", "bercovier"):
                    for r in rows:
                        if r[0] == reg and r[col] > 0:
                            f.write("%g,%g\n" % (r[4], r[col]))
                    f.write("\n\n")
                # the exact run: its time, at the smallest error of the plot
                small = min([r[col] for r in rows[1:] if r[col] > 0] or [1e-8])
                f.write("%g,%g\n" % (ex["wall_time"], small))
            plot(a.out, "exact_%s_%s" % (what, name), label + " against the exact run", "%s: regularised vs exact, cost" % name)


if __name__ == "__main__":
    main()
