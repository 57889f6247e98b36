#!/usr/bin/env python3
"""Arrest study (a study, not a test): the arrest time of each criterion as
the Papanastasiou regularisation stiffens, m = 1e2 ... 1e6, on Couette
cessation (Bn = 1) and Poiseuille cessation (Bn = 0.5; Bn = 1 would leave the
channel at rest), with the cost of each run and the smallest step in the last
decade of kinetic-energy decay before arrest. Writes docs/studies/arrest_*.csv
and the h(t) figures for Couette at m = 1e3 and 1e6.

usage: python3 cases/study_arrest.py [--slump build/slump] [--out out/studies]"""
import argparse
import csv
import os
import shutil
import subprocess

CRITERIA = "mean_shear_rate:1e-3,max_shear_rate:1e-3,kinetic_energy:1e-6:relative,yielded_fraction:1e-3"
NAMES = ["mean_shear_rate", "max_shear_rate", "kinetic_energy_relative", "yielded_fraction"]


def run(slump, scene, opts, d):
    shutil.rmtree(d, ignore_errors=True)
    subprocess.run([slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0", "-arrest", CRITERIA] + opts, check=True, capture_output=True)
    with open(os.path.join(d, "summary.csv")) as f:
        s = next(csv.DictReader(f))
    with open(os.path.join(d, "series.csv")) as f:
        ser = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    with open(os.path.join(d, "steps.csv")) as f:
        steps = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    # last decade of kinetic-energy decay before the mean-shear-rate arrest
    ta = float(s["t_arrest_mean_shear_rate"])
    ke_at = None
    for r in ser:
        if r["t"] <= ta:
            ke_at = r["kinetic_energy"]
    t_dec = max((r["t"] for r in ser if r["kinetic_energy"] >= 10 * (ke_at or 0)), default=0.0)
    hmin = min((st["h"] for st in steps if t_dec <= st["t"] <= ta), default=float("nan"))
    return s, hmin


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/studies", help="where the CSV files and figures go (docs/studies for the documentation's)")
    a = ap.parse_args()
    slump = os.path.abspath(a.slump)
    os.makedirs(a.out, exist_ok=True)
    work = os.path.join(a.out, "_runs")
    for scene, extra, tf in (("couette_cessation", [], "0.15"), ("poiseuille_cessation", [], "0.3")):
        rows = []
        print("%s: arrest time per criterion vs m" % scene)
        print("%-8s %s %6s %8s %8s %10s" % ("m", " ".join("%-12s" % n[:12] for n in NAMES), "steps", "wall s", "bound", "h_min(last decade)"))
        for m in (1e2, 1e3, 1e4, 1e5, 1e6):
            d = os.path.join(work, "%s_m%g" % (scene, m))
            s, hmin = run(slump, scene, extra + ["-rheology_papanastasiou_m", "%g" % m, "-time_final", tf], d)
            ts = [float(s["t_arrest_" + n]) for n in NAMES]
            rows.append([m] + ts + [int(s["steps"]), float(s["wall_time"]), float(s["t_stop_bound"]), hmin])
            print("%-8g %s %6d %8.2f %8.5f %10.3e" % ((m, " ".join("%-12.6f" % t for t in ts)) + tuple(rows[-1][5:])), flush=True)
            if scene == "couette_cessation" and m in (1e3, 1e6) and shutil.which("gnuplot"):
                subprocess.run(["python3", os.path.join(os.path.dirname(__file__), "plot_arrest.py"), d, "--title", "Couette cessation, Bn = 1, Papanastasiou m = %g" % m], check=True, capture_output=True)
                shutil.copy(os.path.join(d, "arrest.png"), os.path.join(a.out, "arrest_couette_m1e%d.png" % round(__import__("math").log10(m))))
        with open(os.path.join(a.out, "arrest_%s.csv" % scene), "w") as f:
            f.write("m," + ",".join("t_" + n for n in NAMES) + ",steps,wall_time,t_stop_bound,h_min_last_decade\n")
            for r in rows:
                f.write(",".join("%.10g" % x for x in r) + "\n")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
