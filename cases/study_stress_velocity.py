#!/usr/bin/env python3
"""Study of issue 31: the stress-velocity Newton against the primal one.

  stages   IDA with its default options on couette_cessation (Bn 1),
           poiseuille_cessation (Bn 0.5) and duct_cessation (Bn 0.1), to
           arrest, for Papanastasiou m = 1e2 ... 1e7, with the
           stress-velocity Newton (the default) and the primal modified
           Newton (-newton_linearisation primal, at most 20000 steps):
           steps, Newton iterations per step, the share of steps with a
           nonlinear convergence failure, error-test failures, residual
           evaluations, wall time, the arrest time and the smallest step in
           the last decade of kinetic-energy decay before arrest;
  steady   the steady duct (Mosolov problem) at Bn 0.05 on 40 x 40 cells,
           m = 1e2 ... 1e8: Newton iterations of one KINSOL solve from rest
           for each linearisation, with and without KINSOL's line search,
           and with continuation in m from 1e2 (factor 10, each
           linearisation's default globalisation: line search for the
           primal, full steps for the stress-velocity Newton), and from a
           viscous start: one solve at m = 1e-3 (the fluid is then nearly
           Newtonian, eta_p + 1e-3 tau0), then the target m.

Writes <out>/sv_stages.csv and <out>/sv_steady.csv and prints the tables of
docs/arrest.md.

usage: python3 cases/study_stress_velocity.py [stages|steady|all] [--slump build/slump] [--out out/study_sv]"""
import argparse
import csv
import os
import subprocess
import tempfile

SCENES = [("couette_cessation", ["-bn", "1"]), ("poiseuille_cessation", ["-bn", "0.5"]), ("duct_cessation", ["-bn", "0.1"])]


def run(slump, scene, opts, timeout=1800):
    with tempfile.TemporaryDirectory() as d:
        p = subprocess.run([slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0"] + opts, capture_output=True, text=True, timeout=timeout)
        s, st = None, []
        if os.path.exists(os.path.join(d, "summary.csv")):
            with open(os.path.join(d, "summary.csv")) as f:
                s = next(csv.DictReader(f))
        if os.path.exists(os.path.join(d, "steps.csv")):
            with open(os.path.join(d, "steps.csv")) as f:
                st = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
        return p, s, st


def last_decade_hmin(steps, t_arrest):
    """smallest h among the steps before the arrest whose kinetic energy is
    within a factor 10 of the energy at arrest (as tests/check.py)"""
    before = [r for r in steps if r["t"] <= t_arrest]
    if not before:
        return float("nan")
    e_end = before[-1]["kinetic_energy"]
    return min(r["h"] for r in before if r["kinetic_energy"] <= 10 * e_end)


def stages(a):
    rows = []
    hdr = "%-20s %-6s %-16s %6s %7s %7s %6s %7s %8s %10s %9s" % ("scene", "m", "linearisation", "steps", "Newton", "fail %", "etf", "res", "wall s", "arrest", "hmin/t_a")
    print(hdr, flush=True)
    for scene, opts in SCENES:
        for m in ("1e2", "1e3", "1e4", "1e5", "1e6", "1e7"):
            for lin in ("stress_velocity", "primal"):
                extra = ["-newton_linearisation", lin, "-time_max_steps", "20000"]
                p, s, st = run(a.slump, scene, opts + ["-rheology_papanastasiou_m", m, "-arrest_stop", "first"] + extra)
                if p.returncode or s is None:
                    msg = (p.stderr.strip().splitlines() or ["failed"])[-1]
                    rows.append(dict(scene=scene, m=m, linearisation=lin, status="failed", message=msg))
                    print("%-20s %-6s %-16s failed: %s" % (scene, m, lin, msg[:110]), flush=True)
                    continue
                n = int(s["steps"])
                ta = float(s["t_arrest"])
                r = dict(scene=scene, m=m, linearisation=lin, status="ok", steps=n, newton_per_step=int(s["newton_its"]) / max(n, 1),
                         fail_share=int(s["conv_fails"]) / max(n, 1), conv_fails=int(s["conv_fails"]), err_test_fails=int(s["err_test_fails"]),
                         res_evals=int(s["res_evals"]), jac_evals=int(s["jac_evals"]), wall_time=float(s["wall_time"]), t_arrest=ta,
                         hmin_last_decade_rel=last_decade_hmin(st, ta) / ta if ta > 0 else float("nan"), message="")
                rows.append(r)
                print("%-20s %-6s %-16s %6d %7.2f %7.1f %6d %7d %8.1f %10.6f %9.1e" % (scene, m, lin, n, r["newton_per_step"], 100 * r["fail_share"], r["err_test_fails"], r["res_evals"], r["wall_time"], ta, r["hmin_last_decade_rel"]), flush=True)
    write(os.path.join(a.out, "sv_stages.csv"), rows)


def steady(a):
    rows = []
    print("%-6s %-16s %-13s %8s %10s" % ("m", "linearisation", "globalisation", "Newton", "status"), flush=True)
    base = ["-bn", "0.05", "-mesh_nx", "40", "-mesh_ny", "40", "-newton_max_it", "200"]
    for m in ("1e2", "1e3", "1e4", "1e5", "1e6", "1e7", "1e8"):
        for lin in ("primal", "stress_velocity"):
            for glob, extra in (("line search", ["-newton_linesearch", "1"]), ("full steps", ["-newton_linesearch", "0"]), ("continuation", ["-steady_continuation_start", "1e2"]),
                                ("viscous start", ["-steady_continuation_start", "1e-3", "-steady_continuation_factor", "1e12"])):
                p, s, st = run(a.slump, "duct", base + ["-rheology_papanastasiou_m", m, "-newton_linearisation", lin] + extra, timeout=600)
                its = [int(l.split("Newton")[1].split()[0]) for l in p.stdout.splitlines() if l.startswith("steady:")]
                ok = p.returncode == 0
                total = sum(its)
                r = dict(m=m, linearisation=lin, globalisation=glob, newton=its[-1] if its else -1, newton_total=total, solves=len(its), status="ok" if ok else "not converged")
                rows.append(r)
                print("%-6s %-16s %-13s %8s %10s" % (m, lin, glob, ("%d" % r["newton"]) + (" (%d in %d solves)" % (total, len(its)) if len(its) > 1 else ""), r["status"]), flush=True)
    write(os.path.join(a.out, "sv_steady.csv"), rows)


def write(path, rows):
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("what", nargs="?", default="all", choices=["stages", "steady", "all"])
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default="out/study_sv")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.what in ("steady", "all"):
        steady(a)
    if a.what in ("stages", "all"):
        stages(a)


if __name__ == "__main__":
    main()
