#!/usr/bin/env python3
"""Benchmark: parallel efficiency of a sweep. The same sweep of N runs (Couette
cessation, Bn 1, Papanastasiou m spread over 1e3..2e3 so every run costs
about the same) on P = 1 and P = 2 ranks (one rank per run); efficiency
E = T1 / (P T_P), T the sweep's wall time (its last line). Writes
docs/studies/bench_sweep.csv.

usage: python3 cases/bench_sweep.py [--runs 8] [--slump build/slump]
"""
import argparse
import os
import re
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default=os.path.join(HERE, "..", "build", "slump"))
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--runs", type=int, default=8)
    ap.add_argument("--docs", default=os.path.join(HERE, "..", "docs"))
    a = ap.parse_args()
    ms = ",".join("%.4g" % (1e3 * (1 + k / a.runs)) for k in range(a.runs))
    times = {}
    for p in (1, 2):
        cmd = [a.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(p), a.slump, "-scene", "couette_cessation", "-mesh_ny", "16",
               "-arrest_stop", "first", "-sweep", "rheology_papanastasiou_m:" + ms, "-output_dir", "out/bench_sweep_p%d" % p]
        print(" ".join(cmd), flush=True)
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        t = float(re.search(r"failed \(see the status column\), ([0-9.]+) s on", out).group(1))
        times[p] = t
        print("P = %d: %d runs in %.2f s" % (p, a.runs, t))
    eff = times[1] / (2 * times[2])
    print("parallel efficiency on 2 ranks: %.3f" % eff)
    os.makedirs(os.path.join(a.docs, "studies"), exist_ok=True)
    with open(os.path.join(a.docs, "studies", "bench_sweep.csv"), "w") as f:
        f.write("runs,ranks,wall_time,efficiency\n%d,1,%.3f,1.000\n%d,2,%.3f,%.3f\n" % (a.runs, times[1], a.runs, times[2], eff))


if __name__ == "__main__":
    main()
