#!/usr/bin/env python3
"""Benchmark (not a test): run poiseuille and couette_cessation on successively
refined meshes and record wall time, peak memory, and the split of time
between assembly (residual, Jacobian, diagnostic integrals: our cell loop)
and the linear solves (PCSetUp = LU factorisation, KSPSolve), from -log_view.

usage: python3 cases/bench.py [--slump build/slump] [--out docs/performance.md] [--quick]
       python3 cases/bench.py --linear [--max-unknowns 1.1e6] [--out table.md]
       python3 cases/bench.py --scaling 1,2[,4,...] [--solver iterative|direct] [--out table.md]
       python3 cases/bench.py --operator [--max-unknowns 5e6] [--out table.md]

--linear: LU (MUMPS) against -linear_solver iterative on poiseuille (steady
Bingham, Stokes), cavity (steady Bingham lid-driven, Stokes) and
duct_cessation (anti-plane, to t = 0.005) from ~2e3 unknowns up to
--max-unknowns, each run's time per Newton iteration, Krylov iterations per
solve and peak memory, with the exponent of the per-Newton time fitted
against the number of unknowns (least squares on log-log, runs with at
least 1e4 unknowns); then Krylov iterations per solve against Papanastasiou
m (1e2 ... 1e6) on poiseuille 32 x 128 with a fixed Krylov tolerance, with
the default velocity V-cycle and with -stokes_velocity_deflation 1e-4.
LU runs stop at --max-lu-unknowns.

--scaling: strong and weak scaling of one scene of each type (poiseuille
32 x 128 at m = 1e4, cavity 64 x 64, duct_cessation 128 x 128) on the given
rank counts, with the METIS partition. Strong: the same mesh, speed-up
T(1)/T(r) and efficiency T(1)/(r T(r)); the results' largest relative
difference from the 1-rank run (kinetic energy, shear rates, flow rate,
arrest time, stream function, unyielded area). Weak: the mesh refined by
sqrt(r) in each direction (about r times the unknowns), efficiency the
1-rank time per Newton iteration over the r-rank one, and the same per
Krylov iteration (which leaves out the growth of the Krylov count). Ranks beyond the
machine's cores run oversubscribed: correct, but not a measure of speed.

--operator: what the node itself does to the cost per unknown. Newtonian
Poiseuille (-rheology_yield_stress 0: one linear solve whose Krylov count
the regularisation does not drive) with -linear_solver iterative from
8 x 32 up to --max-unknowns: Krylov iterations, time per Krylov iteration,
one application of the velocity block's V-cycle per velocity unknown, the
preconditioner's set-up, one Jacobian assembly, and the flop rate of
VecMAXPY (GMRES's update of the solution, a streaming kernel whose work is
exactly proportional to the unknowns), with the exponents of those times
against the unknowns over all runs with at least 1e4 unknowns and over
those with at least 5e5.
"""
import math
import argparse
import csv
import os
import re
import subprocess
import tempfile

EVENTS_ASM = ("SlumpResidual", "SlumpJacobian", "SlumpIntegral")
EVENTS_LIN = ("PCSetUp", "KSPSolve")  # PCSetUp (LU factorisation) runs inside our KSPSetUp


def logview_times(text):
    """Event name -> (count, seconds, flops) of the first -log_view table."""
    t = {}
    for line in text.splitlines():
        m = re.match(r"^(\w+)\s+(\d+)\s+[\d.]+\s+([\d.e+-]+)\s+[\d.]+\s+([\d.e+-]+)\s", line)
        if m and m.group(1) not in t:
            t[m.group(1)] = (int(m.group(2)), float(m.group(3)), float(m.group(4)))
    return t


def run_events(slump, scene, opts, ranks=1, mpiexec="mpiexec"):
    """One run: its summary.csv row and its -log_view events."""
    with tempfile.TemporaryDirectory() as d:
        cmd = [slump, "-scene", scene, "-output_dir", d, "-quiet", "-output_fields", "0", "-log_view"] + opts
        if ranks > 1:
            # more ranks than cores: idle ranks must yield, or polling swamps the run
            yield_idle = ["--mca", "mpi_yield_when_idle", "1"] if ranks > (os.cpu_count() or 1) else []
            cmd = [mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)] + yield_idle + cmd
        p = subprocess.run(cmd, capture_output=True, text=True, check=True)
        with open(os.path.join(d, "summary.csv")) as f:
            s = next(csv.DictReader(f))
    return s, logview_times(p.stdout)


def run(slump, scene, opts, ranks=1, mpiexec="mpiexec"):
    """One run: its summary.csv row, assembly seconds, linear-solve seconds."""
    s, ev = run_events(slump, scene, opts, ranks, mpiexec)
    asm = sum(ev.get(e, (0, 0.0))[1] for e in EVENTS_ASM)
    lin = sum(ev.get(e, (0, 0.0))[1] for e in EVENTS_LIN)
    petsc_asm = sum(ev.get(e, (0, 0.0))[1] for e in ("DMPlexResidualFE", "DMPlexJacobianFE"))
    return s, asm + petsc_asm, lin


def write_table(path, lines):
    if path:
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")


def fit_exponent(points):
    """Least-squares slope of log y against log x."""
    if len(points) < 2:
        return float("nan")
    lx = [math.log(x) for x, _ in points]
    ly = [math.log(y) for _, y in points]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def linear_cases(max_n, max_lu):
    """(scene, label, options, unknowns estimate) of the --linear benchmark."""
    out = []
    for ny in (32, 64, 128, 256, 512, 672):
        n = 9 * (ny // 4) * ny
        out.append(("poiseuille", "%d x %d" % (ny // 4, ny), n, ["-mesh_nx", str(ny // 4), "-mesh_ny", str(ny), "-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2"]))
    for nc in (16, 32, 64, 128, 256, 340):
        # the scene's defaults (no continuation) stop converging beyond 128 x 128
        cont = ["-steady_continuation_start", "1e2"] if nc > 128 else []
        out.append(("cavity", "%d x %d" % (nc, nc), 9 * nc * nc, ["-mesh_nx", str(nc), "-mesh_ny", str(nc)] + cont))
    for nd in (16, 32, 64, 128, 256, 512):
        out.append(("duct_cessation", "%d x %d" % (nd, nd), (2 * nd + 1) ** 2, ["-mesh_nx", str(nd), "-mesh_ny", str(nd), "-time_final", "0.005"]))
    rows = []
    for scene, label, n, opts in out:
        if n > max_n:
            continue
        if n <= max_lu:
            rows.append((scene, label, "direct", opts + ["-linear_solver", "direct"]))
        rows.append((scene, label, "iterative", opts + ["-linear_solver", "iterative"]))
    return rows


def linear_bench(a):
    head = "| scene | mesh | unknowns | linear solver | ranks | Newton | Krylov per solve | wall s | s per Newton | linear s per Newton | peak MB |"
    lines = [head, "|" + "---|" * 11]
    print("\n".join(lines), flush=True)
    series = {}
    for scene, label, kind, opts in linear_cases(a.max_unknowns, a.max_lu_unknowns):
        try:
            s, asm, lin = run(a.slump, scene, opts, a.ranks, a.mpiexec)
        except subprocess.CalledProcessError as e:
            row = "| %s | %s | | %s | %d | failed: %s | | | | | |" % (scene, label, kind, a.ranks, ((e.stderr or "").strip().splitlines() or [""])[-1])
            print(row, flush=True)
            lines.append(row)
            continue
        n, newton = int(s["unknowns"]), max(int(s["newton_its"]), 1)
        per = float(s["wall_time"]) / newton
        kry = float(s["lin_its"]) / newton  # one linear solve per Newton iteration
        row = "| %s | %s | %d | %s | %d | %d | %.1f | %.2f | %.4f | %.4f | %.0f |" % (scene, label, n, kind, a.ranks, newton, kry, float(s["wall_time"]), per, lin / newton, float(s["peak_memory_mb"]))
        print(row, flush=True)
        lines.append(row)
        if n >= 1e4:
            series.setdefault((scene, kind), []).append((n, per, lin / newton))
    lines += ["", "| scene | linear solver | exponent of s per Newton | exponent of linear s per Newton | runs |", "|---|---|---|---|---|"]
    for (scene, kind), pts in series.items():
        lines.append("| %s | %s | %.2f | %.2f | %d |" % (scene, kind, fit_exponent([(n, p) for n, p, _ in pts]), fit_exponent([(n, l) for n, _, l in pts]), len(pts)))
    # Krylov iterations against the regularisation, with the default velocity
    # V-cycle and with the deflation of the stiff regions' rigid motions
    lines += ["", "| poiseuille 32 x 128, m | velocity block | Newton | Krylov per solve (fixed tolerance 1e-10) | wall s |", "|---|---|---|---|---|"]
    for pre, extra in (("V-cycle", []), ("deflation 1e-4", ["-stokes_velocity_deflation", "1e-4"])):
        for m in ("1e2", "1e3", "1e4", "1e5", "1e6"):
            opts = ["-mesh_nx", "32", "-mesh_ny", "128", "-rheology_papanastasiou_m", m, "-steady_continuation_start", "1e2", "-linear_solver", "iterative", "-linear_forcing", "fixed"] + extra
            try:
                s, _, _ = run(a.slump, "poiseuille", opts, a.ranks, a.mpiexec)
            except subprocess.CalledProcessError as e:
                lines.append("| %s | %s | failed: %s | | |" % (m, pre, ((e.stderr or "").strip().splitlines() or [""])[-1]))
                print(lines[-1], flush=True)
                continue
            lines.append("| %s | %s | %d | %.1f | %.2f |" % (m, pre, int(s["newton_its"]), float(s["lin_its"]) / max(float(s["newton_its"]), 1.0), float(s["wall_time"])))
            print(lines[-1], flush=True)
    print("\n".join(lines[lines.index("") :]))
    write_table(a.out, lines)


SCALING_CASES = (
    ("poiseuille", 32, 128, ["-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2"]),
    ("cavity", 64, 64, []),
    ("duct_cessation", 128, 128, ["-time_final", "0.005"]),
)
SCALING_RESULTS = ("t_arrest", "kinetic_energy", "mean_shear_rate", "max_shear_rate", "flow_rate", "psi_max", "unyielded_area")


def result_difference(s, ref):
    """Largest relative difference of the result columns both runs have."""
    d, compared = 0.0, []
    for k in SCALING_RESULTS:
        try:
            a, b = float(s[k]), float(ref[k])
        except (KeyError, TypeError, ValueError):
            continue
        if b != 0.0 and math.isfinite(a) and math.isfinite(b):
            d = max(d, abs(a - b) / abs(b))
            compared.append(k)
    return "%.1e (%s)" % (d, ", ".join(compared)) if compared else "none compared"


def scaling_bench(a):
    ranks = [int(r) for r in a.scaling.split(",")]
    if 1 not in ranks:
        ranks = [1] + ranks
    head = "| scene | mesh | unknowns | ranks | kind | Newton | Krylov | wall s | s per Newton | speed-up | efficiency | result difference from 1 rank | peak MB |"
    lines = [head, "|" + "---|" * 13]
    print("\n".join(lines), flush=True)
    for scene, nx, ny, extra in SCALING_CASES:
        ref = None
        for r in ranks:
            kinds = [("strong", nx, ny)] if r == 1 else [("strong", nx, ny), ("weak", round(nx * math.sqrt(r)), round(ny * math.sqrt(r)))]
            for kind, mx, my in kinds:
                opts = ["-mesh_nx", str(mx), "-mesh_ny", str(my), "-linear_solver", a.solver] + extra
                try:
                    s, _, _ = run(a.slump, scene, opts, r, a.mpiexec)
                except subprocess.CalledProcessError as e:
                    lines.append("| %s | %d x %d | | %d | %s | failed: %s | | | | | | | |" % (scene, mx, my, r, kind, ((e.stderr or "").strip().splitlines() or [""])[-1]))
                    print(lines[-1], flush=True)
                    continue
                newton = max(int(s["newton_its"]), 1)
                wall = float(s["wall_time"])
                if r == 1:
                    ref = s
                if ref is None:
                    speed = eff = diff = ""
                elif r == 1:
                    speed, eff, diff = "1.00", "1.00", ""
                elif kind == "strong":
                    speed = "%.2f" % (float(ref["wall_time"]) / wall)
                    eff = "%.2f" % (float(ref["wall_time"]) / (r * wall))
                    diff = result_difference(s, ref)
                else:
                    speed, diff = "", ""
                    # per Newton iteration, and per Krylov iteration (without the
                    # growth of the iteration counts with the mesh)
                    eff = "%.2f" % ((float(ref["wall_time"]) / max(int(ref["newton_its"]), 1)) / (wall / newton))
                    if int(s["lin_its"]) > 0 and int(ref["lin_its"]) > 0:
                        eff += " (%.2f per Krylov)" % ((float(ref["wall_time"]) / int(ref["lin_its"])) / (wall / int(s["lin_its"])))
                lines.append("| %s | %d x %d | %s | %d | %s | %d | %s | %.2f | %.4f | %s | %s | %s | %.0f |" % (scene, mx, my, s["unknowns"], r, kind if r > 1 else "", newton, s["lin_its"], wall, wall / newton, speed, eff, diff, float(s["peak_memory_mb"])))
                print(lines[-1], flush=True)
    write_table(a.out, lines)


def operator_bench(a):
    head = "| mesh | unknowns | Krylov | KSPSolve s | ms per Krylov iteration | V-cycle µs per velocity unknown | PC set-up s | Jacobian s | VecMAXPY Gflop/s | wall s | peak MB |"
    lines = [head, "|" + "---|" * 11]
    print("\n".join(lines), flush=True)
    pts = []
    for nx in (8, 16, 32, 64, 128, 168, 256, 362, 512):
        n = 36 * nx * nx  # about 9 nx ny unknowns with ny = 4 nx
        if n > (1.6e5 if a.quick else a.max_unknowns):
            break
        s, ev = run_events(a.slump, "poiseuille", ["-mesh_nx", str(nx), "-mesh_ny", str(4 * nx), "-rheology_yield_stress", "0", "-linear_solver", "iterative"])
        n = int(s["unknowns"])
        nvel = n - (nx + 1) * (4 * nx + 1)  # P1 pressure on every vertex, the rest velocity
        its = max(int(s["lin_its"]), 1)
        ksp = ev["KSPSolve"][1]
        vc = ev["KSPSolve_FS_0"]  # one application of the velocity block (one V-cycle)
        jac = ev["SlumpJacobian"]
        axpy = ev["VecMAXPY"]
        p = dict(n=n, per_it=ksp / its, vcycle=vc[1] / vc[0], setup=ev["PCSetUp"][1], jac=jac[1] / jac[0], axpy=axpy[1] / axpy[2])
        pts.append(p)
        lines.append("| %d x %d | %d | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f | %.1f | %.0f |" % (nx, 4 * nx, n, its, ksp, 1e3 * p["per_it"], 1e6 * p["vcycle"] / nvel, p["setup"], p["jac"], 1e-9 / p["axpy"], float(s["wall_time"]), float(s["peak_memory_mb"])))
        print(lines[-1], flush=True)
    # the exponent of the time against the unknowns; for VecMAXPY, 1 + that of
    # its time per flop
    lines += ["", "| unknowns | runs | per Krylov iteration | V-cycle | PC set-up | Jacobian | VecMAXPY |", "|---|---|---|---|---|---|---|"]
    for lo, label in ((1e4, "1e4"), (5e5, "5e5")):
        sel = [p for p in pts if p["n"] >= lo]
        if len(sel) < 2:
            continue
        fit = lambda k: fit_exponent([(p["n"], p[k]) for p in sel])
        lines.append("| ≥ %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f |" % (label, len(sel), fit("per_it"), fit("vcycle"), fit("setup"), fit("jac"), 1.0 + fit("axpy")))
    print("\n".join(lines[lines.index("") :]))
    write_table(a.out, lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default="build/slump")
    ap.add_argument("--out", default=None)
    ap.add_argument("--quick", action="store_true", help="smaller meshes only")
    ap.add_argument("--linear", action="store_true", help="LU against -linear_solver iterative, up to --max-unknowns")
    ap.add_argument("--max-unknowns", type=float, default=1.1e6)
    ap.add_argument("--max-lu-unknowns", type=float, default=3e5)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--scaling", default=None, metavar="RANKS", help="strong and weak scaling on these rank counts, e.g. 1,2")
    ap.add_argument("--solver", default="iterative", choices=("iterative", "direct"), help="-linear_solver of the --scaling runs")
    ap.add_argument("--operator", action="store_true", help="the Newtonian Stokes operator's cost per unknown against the node's, up to --max-unknowns")
    a = ap.parse_args()
    if a.operator:
        operator_bench(a)
        return
    if a.scaling:
        scaling_bench(a)
        return
    if a.linear:
        linear_bench(a)
        return
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
