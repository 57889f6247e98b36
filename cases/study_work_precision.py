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

usage: python3 cases/study_work_precision.py couette|duct [--ranks 2] [--quick]
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
    ap.add_argument("--docs", default=os.path.join(HERE, "..", "docs"))
    ap.add_argument("--work", default="out/study_wp")
    ap.add_argument("--methods", default="ida,ida_linesearch,bdf2", help="comma-separated subset of ida, ida_linesearch, bdf2")
    ap.add_argument("--reuse", action="store_true", help="keep the CSV files of methods already in docs/studies")
    a = ap.parse_args()
    s = SETUPS[a.case]
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
    methods = (("ida", "time_rtol", s["rtols"], ["-time_atol", "1e-9"]),
               ("ida_linesearch", "time_rtol", s["rtols"], ["-time_atol", "1e-9", "-ida_nonlinear_solver", "linesearch"]),
               ("bdf2", "time_dt", s["dts"], ["-time_integrator", "bdf2"]))
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
    labels = {"ida": "IDA Newton", "ida_linesearch": "IDA line search", "bdf2": "BDF2 fixed"}
    subprocess.run([sys.executable, os.path.join(HERE, "plot_sweep.py"), "work"] + [files[m] + ":" + labels[m] for m in files] + [ "--curve", s["mesh"],
                    "--title", "%s: arrest-time error against wall time" % s["title"], "--out", os.path.join(a.docs, "wp_%s.png" % a.case)], check=True)
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
        for method in ("ida", "ida_linesearch", "bdf2"):
            r = best.get((mesh, method))
            if r:
                lines.append("%-8s %-6s %-10s %-12s %-10s %-10s %-8s" % (mesh, method, r["time_dt" if method == "bdf2" else "time_rtol"], r["arrest_error"], r["res_evals"], r["wall_time"], r["steps"]))
        if (mesh, "ida") in best and (mesh, "bdf2") in best:
            ratio = int(best[(mesh, "bdf2")]["res_evals"]) / int(best[(mesh, "ida")]["res_evals"])
            lines.append("%-8s ratio of residual evaluations BDF2 / IDA (Newton) at 1 %%: %.3f" % (mesh, ratio))
        if (mesh, "ida_linesearch") in best and (mesh, "bdf2") in best:
            ratio = int(best[(mesh, "bdf2")]["res_evals"]) / int(best[(mesh, "ida_linesearch")]["res_evals"])
            lines.append("%-8s ratio of residual evaluations BDF2 / IDA (line search) at 1 %%: %.3f" % (mesh, ratio))
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.docs, "studies", "wp_%s.txt" % a.case), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
