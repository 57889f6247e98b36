#!/usr/bin/env python3
"""Benchmark (not a test): run poiseuille and couette_cessation on successively
refined meshes and record wall time, peak memory, and the split of time
between assembly (residual, Jacobian, diagnostic integrals: our cell loop)
and the linear solves (PCSetUp = LU factorisation, KSPSolve), from -log_view.

usage: python3 cases/bench.py [--slump build/slump] [--out docs/performance.md] [--quick]
"""
import argparse
import csv
import os
import re
import subprocess
import tempfile

EVENTS_ASM = ("SlumpResidual", "SlumpJacobian", "SlumpIntegral")
EVENTS_LIN = ("PCSetUp", "KSPSolve")  # PCSetUp (LU factorisation) runs inside our KSPSetUp


def logview_times(text):
    t = {}
    for line in text.splitlines():
        m = re.match(r"^(\w+)\s+(\d+)\s+[\d.]+\s+([\d.e+-]+)\s", line)
        if m and m.group(1) not in t:
            t[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return t


def run(slump, scene, opts):
    with tempfile.TemporaryDirectory() as d:
        cmd = [slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0", "-log_view"] + opts
        p = subprocess.run(cmd, capture_output=True, text=True, check=True)
        with open(os.path.join(d, "summary.csv")) as f:
            s = next(csv.DictReader(f))
    ev = logview_times(p.stdout)
    asm = sum(ev.get(e, (0, 0.0))[1] for e in EVENTS_ASM)
    lin = sum(ev.get(e, (0, 0.0))[1] for e in EVENTS_LIN)
    petsc_asm = sum(ev.get(e, (0, 0.0))[1] for e in ("DMPlexResidualFE", "DMPlexJacobianFE"))
    return s, asm + petsc_asm, lin


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default=None)
    ap.add_argument("--quick", action="store_true", help="smaller meshes only")
    a = ap.parse_args()
    cases = []
    ps = (32, 64, 128) if a.quick else (32, 64, 128, 256)
    for ny in ps:
        cases.append(("poiseuille", ["-mesh_nx", str(max(4, ny // 4)), "-mesh_ny", str(ny), "-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2"]))
    cs = (16, 32, 64) if a.quick else (16, 32, 64, 128)
    for ny in cs:
        cases.append(("couette_cessation", ["-mesh_nx", "2", "-mesh_ny", str(ny), "-time_rtol", "1e-3", "-time_atol", "1e-6"]))
    cases.append(("poiseuille", ["-mesh_nx", "32", "-mesh_ny", "128", "-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2", "-assembly", "petsc"]))
    rows = []
    head = "| scene | mesh | cells | unknowns | assembly | steps | Newton | Jacobians | wall s | assembly s | linear solve s | assembly / linear | peak MB |"
    print(head)
    print("|" + "---|" * 13)
    for scene, opts in cases:
        s, asm, lin = run(a.slump, scene, opts)
        mesh = "%s x %s" % (opts[opts.index("-mesh_nx") + 1], opts[opts.index("-mesh_ny") + 1])
        kind = "petsc" if "petsc" in opts else "slump"
        row = "| %s | %s | %s | %s | %s | %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.0f |" % (
            scene, mesh, s["cells"], s["unknowns"], kind, s["steps"], s["newton_its"], s["jac_evals"], float(s["wall_time"]), asm, lin, asm / lin if lin > 0 else float("nan"), float(s["peak_memory_mb"]))
        print(row, flush=True)
        rows.append(row)
    if a.out:
        with open(a.out, "w") as f:
            f.write(head + "\n|" + "---|" * 13 + "\n" + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
