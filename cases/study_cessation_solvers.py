#!/usr/bin/env python3
"""IDA's own Newton against the line-search stage solver on the corners of
the cessation stability sweep: every cessation scene, Papanastasiou m = 1e4
and 1e6, Bn = 0.1 and 100, rtol 1e-3, atol 1e-5, coarse meshes (the options
of tests/check.py's SWEEP_SCENES), -time_max_steps 20000.

usage: python3 cases/study_cessation_solvers.py [--slump build/slump] [--out out/study_solvers]
Prints a markdown table (docs/arrest.md) and writes solvers.csv in --out.
"""
import argparse
import csv
import os
import re
import subprocess

SCENES = [
    ("couette_cessation", ["-mesh_ny", "16", "-time_final", "0.6"]),
    ("poiseuille_cessation", ["-initial_flow", "newtonian", "-mesh_ny", "16", "-time_final", "1.2"]),
    ("duct_cessation", ["-initial_flow", "newtonian", "-mesh_nx", "8", "-mesh_ny", "8", "-time_final", "0.6"]),
    ("cavity_cessation", ["-mesh_nx", "8", "-mesh_ny", "8", "-time_final", "0.6"]),
]


def one(slump, scene, opts, m, bn, nls, d):
    cmd = [slump, "-scene", scene, "-output_dir", d, "-quiet"] + opts + [
        "-rheology_papanastasiou_m", "%g" % m, "-bn", "%g" % bn, "-time_rtol", "1e-3", "-time_atol", "1e-5",
        "-arrest_stop", "none", "-time_output_dt", "0.01", "-output_fields", "0", "-time_max_steps", "20000",
        "-ida_nonlinear_solver", nls]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode == 0:
        with open(os.path.join(d, "summary.csv")) as f:
            s = next(csv.DictReader(f))
        return dict(ok=1, t_arrest=float(s["t_arrest"]), steps=int(s["steps"]),
                    failures=int(s["conv_fails"]) + int(s["err_test_fails"]), wall=float(s["wall_time"]), t_stop=float(s["t_final"]))
    mm = re.search(r"stopped at t = ([0-9.e+-]+) \(h = ([0-9.e+-]+)\)", p.stderr)
    return dict(ok=0, t_arrest=-1, steps=-1, failures=-1, wall=-1, t_stop=float(mm.group(1)) if mm else -1,
                h=float(mm.group(2)) if mm else -1, error=p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "")


def cell(r):
    if r["ok"]:
        return "%.6f (%d steps, %d failures, %.1f s)" % (r["t_arrest"], r["steps"], r["failures"], r["wall"])
    return "**stuck**: 20000 steps reached t = %.3g only, h = %.2g" % (r["t_stop"], r.get("h", -1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/study_solvers")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    print("| scene | m | Bn | IDA Newton | line search |\n|---|---|---|---|---|")
    for scene, opts in SCENES:
        for m in (1e4, 1e6):
            for bn in (0.1, 100):
                r = {nls: one(a.slump, scene, opts, m, bn, nls, os.path.join(a.out, "%s_m%g_bn%g_%s" % (scene, m, bn, nls)))
                     for nls in ("newton", "linesearch")}
                print("| %s | %g | %g | %s | %s |" % (scene, m, bn, cell(r["newton"]), cell(r["linesearch"])), flush=True)
                for nls, x in r.items():
                    rows.append(dict(scene=scene, m=m, bn=bn, solver=nls, **{k: x[k] for k in ("ok", "t_arrest", "steps", "failures", "wall", "t_stop")}))
    with open(os.path.join(a.out, "solvers.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
