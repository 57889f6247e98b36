#!/usr/bin/env python3
"""Study: IDA's own modified Newton against the globalised stage solver
(-ida_nonlinear_solver linesearch: KINSOL, line search, exact Jacobian) on
Couette cessation (Bn = 1) for Papanastasiou m = 1e4, 1e5, 1e6, at rtol 1e-3,
atol 1e-5: steps, nonlinear (convergence) failures, error-test failures,
residual and Jacobian evaluations, wall time and the arrest time.
Writes docs/studies/nonlinear_solvers.csv.

usage: python3 cases/study_nonlinear.py [--slump build/slump] [--out out/studies]"""
import argparse
import csv
import os
import subprocess
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/studies", help="where the CSV file goes (docs/studies for the documentation's)")
    a = ap.parse_args()
    rows = []
    print("%-8s %-10s %6s %8s %8s %8s %8s %8s %10s" % ("m", "solver", "steps", "nl fails", "etf", "res", "jac", "wall s", "arrest"))
    for m in (1e4, 1e5, 1e6):
        for solver in ("newton", "linesearch"):
            with tempfile.TemporaryDirectory() as d:
                subprocess.run([a.slump, "-scene", "couette_cessation", "-output_dir", d, "-quiet", "-output_fields", "0", "-time_final", "0.12",
                                "-time_rtol", "1e-3", "-time_atol", "1e-5", "-rheology_papanastasiou_m", "%g" % m, "-ida_nonlinear_solver", solver], check=True, capture_output=True)
                with open(os.path.join(d, "summary.csv")) as f:
                    s = next(csv.DictReader(f))
            r = [m, solver, int(s["steps"]), int(s["conv_fails"]), int(s["err_test_fails"]), int(s["res_evals"]), int(s["jac_evals"]), float(s["wall_time"]), float(s["t_arrest"])]
            rows.append(r)
            print("%-8g %-10s %6d %8d %8d %8d %8d %8.1f %10.6f" % tuple(r), flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "nonlinear_solvers.csv"), "w") as f:
        f.write("m,solver,steps,nonlinear_failures,error_test_failures,res_evals,jac_evals,wall_time,t_arrest\n")
        for r in rows:
            f.write(",".join(str(x) for x in r) + "\n")


if __name__ == "__main__":
    main()
