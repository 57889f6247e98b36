#!/usr/bin/env python3
"""Studies 2 and 3 of docs/sweeps.md: work-precision of the arrest time.
Adaptive IDA (a sweep over -time_rtol) against fixed-step BDF2 (a sweep over
-time_dt), each on several meshes (-sweep2 mesh_n or mesh_ny), under
mpirun. Error: the relative arrest-time error (mean shear rate < 1e-3)
against the exact model's arrest time where the scene has one (Couette:
arrest_error), otherwise against the reference run given by --reference
(the duct: a finer, tighter run, stated in the output). Writes
docs/studies/wp_<scene>_{ida,bdf2}.csv, docs/wp_<scene>.png and the ratio of
residual evaluations BDF2 / IDA at 1 % accuracy to docs/studies/wp_<scene>.txt.

Methods: ida (IDA with the default stress-velocity Newton), ida_primal
(IDA's modified Newton on the primal tangent), ida_linesearch, bdf2 (fixed
step, KINSOL, the default stress-velocity tangent with full Newton steps),
bdf2_primal (primal tangent, KINSOL's line search, the default with it) and
bdf2_linesearch (stress-velocity with the line search).
IDA runs use the default absolute tolerance (1e-3 rtol max|u(0)|).

usage: python3 cases/study_work_precision.py couette|duct|poiseuille [--ranks 2]
       [--meshes 32] [--methods ida,ida_primal,bdf2,bdf2_primal] [--docs out/docs] [--quick]
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SETUPS = {
    "couette": dict(scene="couette_cessation", mesh="mesh_ny", meshes="8,16,32,64",
                    rtols="1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8", dts="1e-2,5e-3,2.5e-3,1.25e-3,6.25e-4,3.125e-4,1.5625e-4",
                    opts=["-bn", "1", "-rheology_papanastasiou_m", "1e4", "-time_final", "0.2"], reference=None, title="Couette cessation, Bn 1, m 1e4"),
    "duct": dict(scene="duct_cessation", mesh="mesh_n", meshes="8,16",
                 rtols="1e-3,1e-4,1e-5,1e-6", dts="4e-3,2e-3,1e-3,5e-4,2.5e-4,1.25e-4",
                 opts=["-rheology_papanastasiou_m", "1e4", "-time_final", "0.1"],
                 reference=["-mesh_n", "64", "-time_rtol", "1e-5", "-time_atol", "1e-9"], title="duct cessation, Bn 0.1, m 1e4"),
    # the issue 31 set-ups: one mesh each, the temporal error against a tight
    # run on the same mesh (duct) or the exact model (Poiseuille, Couette)
    "duct32": dict(scene="duct_cessation", mesh="mesh_n", meshes="32",
                   rtols="3e-2,1e-2,3e-3,1e-3,1e-4", dts="8e-3,4e-3,2e-3,1e-3,5e-4",
                   opts=["-rheology_papanastasiou_m", "1e4", "-time_final", "0.1"],
                   reference=["-mesh_n", "32", "-time_rtol", "1e-7"], title="duct cessation 32 x 32, Bn 0.1, m 1e4"),
    "poiseuille": dict(scene="poiseuille_cessation", mesh="mesh_ny", meshes="32",
                       rtols="3e-2,1e-2,3e-3,1e-3,1e-4", dts="1e-2,5e-3,2.5e-3,1.25e-3,6.25e-4",
                       opts=["-bn", "0.5", "-rheology_papanastasiou_m", "1e4", "-time_final", "1"], reference=None, title="Poiseuille cessation, Bn 0.5, m 1e4"),
}
COMMON = ["-arrest_stop", "first", "-time_max_steps", "20000"]


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def write(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=SETUPS.keys())
    ap.add_argument("--slump", default=os.path.join(HERE, "..", "build", "slump"))
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--docs", default="out/docs", help="where CSV files (DOCS/studies) and figures go; docs for the documentation's")
    ap.add_argument("--work", default="out/study_wp")
    ap.add_argument("--methods", default="ida,ida_primal,bdf2,bdf2_primal,bdf2_linesearch", help="comma-separated subset of ida, ida_primal, ida_linesearch, bdf2, bdf2_primal, bdf2_linesearch")
    ap.add_argument("--meshes", default=None, help="the meshes of the sweep (default: the set-up's)")
    ap.add_argument("--reuse", action="store_true", help="keep the CSV files of methods already in DOCS/studies")
    ap.add_argument("--quick", action="store_true", help="a first look: the set-up's coarsest mesh, IDA and BDF2 only (unless --meshes/--methods say otherwise)")
    a = ap.parse_args()
    s = dict(SETUPS[a.case])
    if a.quick:
        s["meshes"] = str(s["meshes"]).split(",")[0]
        if "--methods" not in sys.argv:
            a.methods = "ida,bdf2"
    if a.meshes:
        s["meshes"] = a.meshes
    mpi = [a.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(a.ranks)]
    os.makedirs(os.path.join(a.docs, "studies"), exist_ok=True)
    ref = None
    if s["reference"]:
        out = os.path.join(a.work, a.case + "_reference")
    if s["reference"] and not (a.reuse and os.path.exists(os.path.join(out, "summary.csv"))):
        cmd = mpi + [a.slump, "-scene", s["scene"], "-output_dir", out, "-output_fields", "0", "-quiet"] + s["opts"] + COMMON + s["reference"]
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, check=True)
    if s["reference"]:
        ref = float(rows_of(os.path.join(out, "summary.csv"))[0]["t_arrest"])
        print("reference arrest time %.10g (%s)" % (ref, " ".join(s["reference"])))
    files = {}
    methods = (("ida", "time_rtol", s["rtols"], []),
               ("ida_primal", "time_rtol", s["rtols"], ["-newton_linearisation", "primal"]),
               ("ida_linesearch", "time_rtol", s["rtols"], ["-ida_nonlinear_solver", "linesearch"]),
               ("bdf2", "time_dt", s["dts"], ["-time_integrator", "bdf2"]),
               ("bdf2_primal", "time_dt", s["dts"], ["-time_integrator", "bdf2", "-newton_linearisation", "primal"]),
               ("bdf2_linesearch", "time_dt", s["dts"], ["-time_integrator", "bdf2", "-newton_linesearch", "1"]))
    for method, opt, values, extra in methods:
        if method not in a.methods.split(","):
            continue
        dst = os.path.join(a.docs, "studies", "wp_%s_%s.csv" % (a.case, method))
        if a.reuse and os.path.exists(dst):
            print("reusing " + dst)
            files[method] = dst
            continue
        out = os.path.join(a.work, "%s_%s" % (a.case, method))
        cmd = mpi + [a.slump, "-scene", s["scene"], "-sweep", "%s:%s" % (opt, values), "-sweep2", "%s:%s" % (s["mesh"], s["meshes"]), "-output_dir", out] + s["opts"] + COMMON + extra
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, check=True)
        rows = rows_of(os.path.join(out, "sweep.csv"))
        for r in rows:
            r["method"] = method
            if ref is not None:
                r["reference"] = "%.10e" % ref
                r["arrest_error"] = "%.6e" % (abs(float(r["t_arrest"]) - ref) / ref) if r["status"] == "ok" and r["t_arrest"] else ""
        write(dst, rows)
        files[method] = dst
    labels = {"ida": "IDA stress-velocity", "ida_primal": "IDA primal", "ida_linesearch": "IDA line search", "bdf2": "BDF2 fixed (stress-velocity)", "bdf2_primal": "BDF2 fixed (primal, line search)", "bdf2_linesearch": "BDF2 fixed (stress-velocity, line search)"}
    for work, suffix, what in (("res_evals", "", "residual evaluations"), ("wall_time", "_time", "wall time")):
        subprocess.run([sys.executable, os.path.join(HERE, "plot_sweep.py"), "work"] + [files[m] + ":" + labels[m] for m in files] + ["--curve", s["mesh"], "--work", work,
                        "--title", "%s: arrest-time error against %s" % (s["title"], what), "--out", os.path.join(a.docs, "wp_%s%s.png" % (a.case, suffix))], check=True)
    # the cheapest run reaching 1 % for each method and mesh, and the ratio
    lines = ["%s: cheapest run (fewest residual evaluations) with arrest-time error <= 1e-2 (error against %s)" % (s["scene"], "the reference run " + " ".join(s["reference"]) if ref else "the exact model's arrest time"),
             "%-8s %-6s %-10s %-12s %-10s %-10s %-8s" % ("mesh", "method", "parameter", "error", "res_evals", "wall_time", "steps")]
    best = {}
    for method in files:
        for r in rows_of(files[method]):
            if r["status"] != "ok" or not r["arrest_error"] or float(r["arrest_error"]) > 1e-2:
                continue
            key = (r[s["mesh"]], method)
            if key not in best or int(r["res_evals"]) < int(best[key]["res_evals"]):
                best[key] = r
    for mesh in s["meshes"].split(","):
        for method in ("ida", "ida_primal", "ida_linesearch", "bdf2", "bdf2_primal", "bdf2_linesearch"):
            r = best.get((mesh, method))
            if r:
                lines.append("%-8s %-14s %-10s %-12s %-10s %-10s %-8s" % (mesh, method, r["time_dt" if method.startswith("bdf2") else "time_rtol"], r["arrest_error"], r["res_evals"], r["wall_time"], r["steps"]))
        fixed = [best[(mesh, m)] for m in ("bdf2", "bdf2_primal", "bdf2_linesearch") if (mesh, m) in best]
        if fixed:
            cheapest = min(int(r["res_evals"]) for r in fixed)
            for m in ("ida", "ida_primal", "ida_linesearch"):
                if (mesh, m) in best:
                    lines.append("%-8s ratio of residual evaluations best BDF2 / %s at 1 %%: %.3f" % (mesh, m, cheapest / int(best[(mesh, m)]["res_evals"])))
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.docs, "studies", "wp_%s.txt" % a.case), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
