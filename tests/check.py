#!/usr/bin/env python3
"""Verification, parallel and input tests of the slump program (run by ctest).

Each test runs `slump` and asserts numbers read back from its CSV outputs,
with the tolerance stated next to the assertion. On failure it prints the
expected and the obtained value and exits 1; on success it prints one line.

usage: check.py TEST --slump PATH --mpiexec PATH --work DIR
"""
import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys

ARGS = None


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run(scene, opts, outdir, ranks=1, expect_ok=True):
    cmd = []
    if ranks > 1:
        cmd = [ARGS.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)]
        # more ranks than cores: waiting ranks yield the core instead of
        # polling (4 ranks on 2 cores took 161 s instead of ~6 s without it)
        if ranks > 2:
            cmd += ["--mca", "mpi_yield_when_idle", "1"]
    cmd += [ARGS.slump, "-scene", scene, "-output_dir", outdir, "-quiet"] + opts
    p = subprocess.run(cmd, capture_output=True, text=True)
    if expect_ok and p.returncode != 0:
        fail("command failed (%d): %s\n%s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-3000:], p.stderr[-3000:]))
    return p


def summary(outdir):
    with open(os.path.join(outdir, "summary.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: (float(v) if _isnum(v) else v) for k, v in rows[0].items()}


def series(outdir):
    with open(os.path.join(outdir, "series.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def dissipated(ser, column="dissipation"):
    """A dissipation rate in series.csv integrated over the outputs (trapezoidal rule)."""
    return sum(0.5 * (b["t"] - a["t"]) * (a[column] + b[column]) for a, b in zip(ser, ser[1:]))


def energy_budget(outdir):
    """A free-surface run's energy budget at its last output: the potential
    energy released, the energy dissipated (the run's own total over its
    steps: material, ambient fluid and friction walls, and the parts of it
    integrated over the outputs), the kinetic energy, the potential energy
    the between-step actions added (reinitialisations and volume
    corrections, from interface.csv) and the imbalance
    (dissipated + kinetic - released - added) / (released + added)."""
    ser = series(outdir)
    with open(os.path.join(outdir, "interface.csv")) as f:
        ifc = [r for r in csv.DictReader(f) if float(r["t"]) <= ser[-1]["t"] * (1 + 1e-12)]
    reinit, correction = float(ifc[-1]["energy_reinit"]), float(ifc[-1]["energy_correction"])
    added = reinit + correction
    released = ser[0]["potential_energy"] - ser[-1]["potential_energy"]
    diss, ke = ser[-1]["dissipated"] - ser[0]["dissipated"], ser[-1]["kinetic_energy"] - ser[0]["kinetic_energy"]
    return {"released": released, "dissipated": diss, "kinetic": ke, "added": added, "reinit": reinit, "correction": correction,
            "material": dissipated(ser), "ambient": dissipated(ser, "dissipation_ambient"), "wall": dissipated(ser, "dissipation_wall"),
            "imbalance": (diss + ke - released - added) / (released + added)}


def _isnum(v):
    try:
        float(v)
        return True
    except ValueError:
        return False


def order(e1, e2, ratio=2.0):
    return math.log(e1 / e2) / math.log(ratio)


def work(name):
    d = os.path.join(ARGS.work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    return d


# ----------------------------------------------------------------- tests
def mms_orders(name, extra):
    """L2 errors and observed orders of mms_stokes on 8, 16, 32 cells a side."""
    w = work(name)
    eu, ep = [], []
    for n in (8, 16, 32):
        d = os.path.join(w, "n%d" % n)
        p = run("mms_stokes", extra + ["-mesh_nx", str(n), "-mesh_ny", str(n), "-output_fields", "0"], d)
        s = summary(d)
        eu.append(s["err_u_l2"])
        ep.append(s["err_p_l2"])
    return eu, ep, [order(eu[i], eu[i + 1]) for i in range(2)], [order(ep[i], ep[i + 1]) for i in range(2)], p


def test_mms_stokes():
    """Taylor-Hood P2/P1 on the manufactured Stokes solution: L2 orders over
    three refinements, velocity >= 2.8, pressure >= 1.8."""
    eu, ep, ou, op, _ = mms_orders("mms", [])
    print("velocity L2 errors %s orders %s; pressure L2 errors %s orders %s" % (eu, ou, ep, op))
    if min(ou) < 2.8:
        fail("velocity order expected >= 2.8, got %s" % ou)
    if min(op) < 1.8:
        fail("pressure order expected >= 1.8, got %s" % op)


def test_mms_enclosed():
    """Enclosed flow (Dirichlet on all sides): the pressure level is fixed at
    one vertex and the same orders hold: velocity >= 2.8, pressure >= 1.8."""
    eu, ep, ou, op, p = mms_orders("mms_enclosed", ["-mms_enclosed"])
    if "pressure fixed at one vertex" not in p.stdout:
        fail("an enclosed flow should report its pressure pin")
    print("enclosed: velocity orders %s, pressure orders %s" % (ou, op))
    if min(ou) < 2.8 or min(op) < 1.8:
        fail("enclosed orders expected >= 2.8 and >= 1.8, got %s and %s" % (ou, op))


POISEUILLE_MODELS = [
    # (label, options); continuation from soft to the target regularisation
    ("bingham bercovier eps=1e-6", ["-rheology_type", "bercovier", "-rheology_bercovier_eps", "1e-6", "-steady_continuation_start", "1e-2"]),
    ("bingham simple eps=1e-6", ["-rheology_type", "bingham_simple", "-rheology_simple_eps", "1e-6", "-steady_continuation_start", "1e-2"]),
    ("HB n=0.5 papanastasiou m=1e6", ["-rheology_type", "hb_papanastasiou", "-rheology_hb_n", "0.5", "-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2"]),
    ("HB n=0.5 bercovier eps=1e-6", ["-rheology_type", "hb_bercovier", "-rheology_hb_n", "0.5", "-rheology_bercovier_eps", "1e-6", "-steady_continuation_start", "1e-2"]),
    ("HB n=1.5 simple eps=1e-6", ["-rheology_type", "hb_simple", "-rheology_hb_n", "1.5", "-rheology_simple_eps", "1e-6", "-steady_continuation_start", "1e-2"]),
]


def test_poiseuille_models():
    """Plane Poiseuille with every Bingham regularisation and with
    Herschel-Bulkley (n = 0.5, 1.5), 32 cells across, Bn = 0.3: relative L2
    velocity error <= 1e-3 against the exact profile and the plug half-width
    within one cell (2/32) of tau0/G."""
    w = work("poiseuille_models")
    for k, (label, opts) in enumerate(POISEUILLE_MODELS):
        d = os.path.join(w, "m%d" % k)
        run("poiseuille", opts + ["-output_fields", "0"], d)
        s = summary(d)
        rel = s["err_u_l2"] / s["norm_u_l2"]
        print("%-30s relative L2 error %.3e, plug half-width %.4f (exact %.4f), %d Newton" % (label, rel, s["plug_half_width"], s["plug_half_width_exact"], s["newton_its"]))
        if not rel <= 1e-3:
            fail("%s: relative L2 error expected <= 1e-3, got %g" % (label, rel))
        if not abs(s["plug_half_width"] - s["plug_half_width_exact"]) <= 2.0 / 32:
            fail("%s: plug half-width expected within %g of %g, got %g" % (label, 2.0 / 32, s["plug_half_width_exact"], s["plug_half_width"]))


def test_stability_poiseuille_plug90():
    """Hard case: Bingham-Papanastasiou Poiseuille at m = 1e6 with the plug
    filling 90 % of the channel (Bn = 0.9), continuation from m = 1e2: every
    continuation step converges within 15 Newton iterations (budget), the
    outputs are finite, and the plug half-width is within one cell of 0.9."""
    d = work("stability_plug90")
    p = run("poiseuille", ["-bn", "0.9", "-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2", "-output_fields", "0"], d)
    its = continuation_newton(p.stdout)
    s = summary(d)
    print("Newton iterations per continuation step %s; plug half-width %.4f; relative L2 error %.3e" % (its, s["plug_half_width"], s["err_u_l2"] / s["norm_u_l2"]))
    if len(its) != 5 or max(its) > 15:
        fail("expected 5 continuation steps of <= 15 Newton iterations, got %s" % its)
    for k in ("kinetic_energy", "mean_shear_rate", "err_u_l2", "flow_rate"):
        if not math.isfinite(s[k]):
            fail("%s is not finite: %s" % (k, s[k]))
    if not abs(s["plug_half_width"] - 0.9) <= 2.0 / 32:
        fail("plug half-width expected within %g of 0.9, got %g" % (2.0 / 32, s["plug_half_width"]))


def test_poiseuille_half():
    """Free slip: the half channel 0 <= y <= 1 with a free-slip symmetry plane
    at y = 0 (16 cells across) reproduces the Bingham profile: relative L2
    error <= 1e-3 at m = 1e6 and the plug half-width within one cell."""
    d = work("poiseuille_half")
    run("poiseuille", ["-half_channel", "-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2", "-output_fields", "0"], d)
    s = summary(d)
    rel = s["err_u_l2"] / s["norm_u_l2"]
    h = 1.0 / 16
    print("half channel, m = 1e6: relative L2 error %.3e; plug half-width %.4f (exact %.4f)" % (rel, s["plug_half_width"], s["plug_half_width_exact"]))
    if not rel <= 1e-3:
        fail("relative L2 velocity error expected <= 1e-3, got %g" % rel)
    if not abs(s["plug_half_width"] - s["plug_half_width_exact"]) <= h:
        fail("plug half-width expected within %g of %g, got %g" % (h, s["plug_half_width_exact"], s["plug_half_width"]))


def bdf2_order_check(scene, w, dts):
    """Fixed-step BDF2 at the halving steps dts: observed order in time >= 1.9."""
    err = []
    for dt in dts:
        d = os.path.join(w, "bdf2_%g" % dt)
        run(scene, ["-time_integrator", "bdf2", "-time_dt", str(dt), "-output_fields", "0"], d)
        s = summary(d)
        err.append(s["err_u_l2"] / s["norm_u_l2"])
    o = [order(err[i], err[i + 1]) for i in range(len(err) - 1)]
    print("BDF2 relative errors %s, orders %s" % (err, o))
    if min(o) < 1.9:
        fail("BDF2 order expected >= 1.9, got %s" % o)


def test_decay_bdf2():
    """Fixed-step BDF2 on the decaying sine: observed order in time >= 1.9."""
    bdf2_order_check("decay", work("decay_bdf2"), (0.01, 0.005, 0.0025))


def test_decay_ida():
    """Adaptive IDA (BDF, order <= 2): relative L2 error at t = 0.1 within 10x
    rtol for rtol = 1e-3, 1e-4; within 40x for 1e-5, 1e-6 (per-step error
    control accumulates over the ~70-150 steps; measured 18.7x and 31.7x), and
    the error falls by at least 50x from rtol 1e-3 to 1e-6."""
    w = work("decay_ida")
    errs = {}
    for rtol, factor in ((1e-3, 10), (1e-4, 10), (1e-5, 40), (1e-6, 40)):
        d = os.path.join(w, "r%g" % rtol)
        run("decay", ["-time_rtol", str(rtol), "-time_atol", str(rtol * 1e-3), "-output_fields", "0"], d)
        s = summary(d)
        e = s["err_u_l2"] / s["norm_u_l2"]
        errs[rtol] = e
        print("rtol %g: relative error %.3e (%.1f x rtol), %d steps" % (rtol, e, e / rtol, s["steps"]))
        if not e <= factor * rtol:
            fail("rtol %g: error expected <= %g x rtol = %g, got %g" % (rtol, factor, factor * rtol, e))
    if not errs[1e-6] <= errs[1e-3] / 50:
        fail("error at rtol 1e-6 expected <= 1/50 of that at 1e-3 (%g), got %g" % (errs[1e-3] / 50, errs[1e-6]))


def test_startup():
    """Time-dependent Dirichlet data: Couette start-up with the top plate at
    V(t) = 1 - exp(-t/0.05), against the exact series solution at t = 0.2.
    IDA: relative L2 error <= 10 x rtol for rtol = 1e-3, 1e-4; fixed-step
    BDF2 (dt = 4e-3, 2e-3, 1e-3): observed order >= 1.9."""
    w = work("startup")
    for rtol in (1e-3, 1e-4):
        d = os.path.join(w, "ida%g" % rtol)
        run("couette_startup", ["-time_rtol", str(rtol), "-time_atol", "1e-8", "-output_fields", "0"], d)
        s = summary(d)
        e = s["err_u_l2"] / s["norm_u_l2"]
        print("IDA rtol %g: relative error %.3e (%.2f x rtol), %d steps" % (rtol, e, e / rtol, s["steps"]))
        if not e <= 10 * rtol:
            fail("rtol %g: error expected <= %g, got %g" % (rtol, 10 * rtol, e))
    bdf2_order_check("couette_startup", w, (0.004, 0.002, 0.001))


def continuation_newton(stdout):
    """Newton iterations of each continuation step (the 'steady:' lines)."""
    return [int(l.split("Newton")[1].split()[0]) for l in stdout.splitlines() if l.startswith("steady:")]


def newton_histories(stdout):
    """Per continuation step, the max|F| history printed by -newton_monitor."""
    hist, cur = [], []
    for line in stdout.splitlines():
        if line.startswith("  newton"):
            cur.append(float(line.split("max|F|")[1].split()[0]))
        elif line.startswith("steady:"):
            hist.append((line.split("Newton")[0].strip(), cur))
            cur = []
    return hist


def test_newton_quadratic():
    """Exact tangents (including the pressure coupling of mu(I)) give
    quadratic Newton convergence. On Bingham-Papanastasiou Poiseuille
    (continuation m = 1e2 ... 1e6) and mu(I) Bagnold (lambda_r = 1e-1 ...
    1e-4, 16 cells), at every continuation step with at least two Newton
    contractions whose result is above round-off (>= 1e-9), the last two
    satisfy r_{k+1} <= C r_k^2 with C = 1e3 (max-norm residuals); at least
    three steps per scene qualify."""
    cases = [("poiseuille", ["-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2"]),
             ("bagnold", ["-mesh_ny", "16", "-steady_continuation_start", "1e-1"])]
    for scene, opts in cases:
        d = work("newton_quadratic_" + scene)
        p = run(scene, opts + ["-newton_monitor", "-output_fields", "0"], d)
        judged = 0
        for label, r in newton_histories(p.stdout):
            pairs = [(r[k], r[k + 1]) for k in range(len(r) - 1) if r[k + 1] >= 1e-9][-2:]
            ratios = [b / a ** 2 for a, b in pairs]
            print("%-10s %-26s residuals %s; last contractions r1/r0^2 = %s" % (scene, label, " ".join("%.1e" % x for x in r), " ".join("%.0f" % x for x in ratios)))
            if len(pairs) < 2:
                continue
            judged += 1
            if max(ratios) > 1e3:
                fail("%s %s: contraction r_{k+1}/r_k^2 expected <= 1e3, got %s" % (scene, label, ratios))
        if judged < 3:
            fail("%s: only %d continuation steps had enough Newton steps above round-off to judge" % (scene, judged))


def test_bagnold():
    """mu(I) Bagnold flow on the incline (Chauchat & Medale's parameters):
    with their eq. 12 (mui_cm, lambda_r = 1e-4) the L2 (RMS) velocity error
    falls with observed order >= 1.5 over 4, 8, 16 cells across the layer
    and the surface velocity is within 1 % of the analytic one on each mesh;
    the other three regularisations converge (8 cells) with relative L2
    error <= 1e-2 (their regularisation error; measured 7.7e-3 for the
    simple form (9), 2.1e-4 for (10) and (11))."""
    w = work("bagnold")
    err = []
    for n in (4, 8, 16):
        d = os.path.join(w, "cm%d" % n)
        run("bagnold", ["-mesh_ny", str(n), "-steady_continuation_start", "1e-1", "-output_fields", "0"], d)
        s = summary(d)
        err.append(s["err_u_l2"])
        surf = abs(s["surface_velocity"] - s["surface_velocity_exact"]) / s["surface_velocity_exact"]
        print("mui_cm %2d cells: L2 error %.3e, surface velocity %.5f (exact %.5f, %.3f %%)" % (n, s["err_u_l2"], s["surface_velocity"], s["surface_velocity_exact"], 100 * surf))
        if not surf <= 0.01:
            fail("surface velocity expected within 1 %%, got %.3f %%" % (100 * surf))
    o = [order(err[i], err[i + 1]) for i in range(2)]
    print("observed orders %s" % o)
    if min(o) < 1.5:
        fail("observed order expected >= 1.5, got %s" % o)
    for t in ("mui_simple", "mui_bercovier", "mui_papanastasiou"):
        d = os.path.join(w, t)
        run("bagnold", ["-rheology_type", t, "-mesh_ny", "8", "-steady_continuation_start", "1e-1", "-output_fields", "0"], d)
        s = summary(d)
        rel = s["err_u_l2"] / s["norm_u_l2"]
        print("%-18s 8 cells: relative L2 error %.3e, %d Newton" % (t, rel, s["newton_its"]))
        if not rel <= 1e-2:
            fail("%s: relative error expected <= 1e-2, got %g" % (t, rel))


def test_vertical_chute():
    """mu(I) vertical chute at p = 28, b = 28 (mui_cm, lambda_r = 1e-4), 32
    cells across: relative L2 velocity error <= 2e-3 against the analytic
    profile and the plug half-width within one cell (b/32) of mu_s p."""
    d = work("vertical_chute")
    run("vertical_chute", ["-mesh_ny", "32", "-steady_continuation_start", "1e-1", "-output_fields", "0"], d)
    s = summary(d)
    rel = s["err_u_l2"] / s["norm_u_l2"]
    print("relative L2 error %.3e; plug half-width %.4f (exact %.4f, cell %.4f)" % (rel, s["plug_half_width"], s["plug_half_width_exact"], 28.0 / 32))
    if not rel <= 2e-3:
        fail("relative L2 error expected <= 2e-3, got %g" % rel)
    if not abs(s["plug_half_width"] - s["plug_half_width_exact"]) <= 28.0 / 32:
        fail("plug half-width expected within %g of %g, got %g" % (28.0 / 32, s["plug_half_width_exact"], s["plug_half_width"]))


def test_duct():
    """Anti-plane Bingham flow in a square duct (Mosolov problem), 16 x 16
    cells, Papanastasiou m = 1e5 (continuation from 1e2).
    Newtonian: flow rate within 1e-4 of the series value 0.035144.
    Bingham: the flow rate decreases and the plug area grows with Bn; the
    flow threshold Bn_c = 1/(2 + sqrt(pi)) = 0.26508 (Cheeger constant of the
    square) is bracketed: at Bn = 0.25 (6 % below) Q/Q_newtonian > 1e-3 and
    the plug covers < 80 % of the duct; at Bn = 0.28 (6 % above)
    Q/Q_newtonian < 1e-3 (regularised creep) and the plug covers > 99 %."""
    w = work("duct")
    d = os.path.join(w, "newtonian")
    run("duct", ["-rheology_type", "newtonian", "-output_fields", "0"], d)
    s = summary(d)
    rel = abs(s["flow_rate"] - s["flow_rate_newtonian"]) / s["flow_rate_newtonian"]
    print("Newtonian flow rate %.7f, series %.7f (rel diff %.1e)" % (s["flow_rate"], s["flow_rate_newtonian"], rel))
    if not rel <= 1e-4:
        fail("Newtonian flow rate expected within 1e-4 of the series, got %g" % rel)
    qn = s["flow_rate_newtonian"]
    prev = None
    res = {}
    for bn in (0.1, 0.2, 0.25, 0.28, 0.5):
        d = os.path.join(w, "bn%g" % bn)
        run("duct", ["-bn", str(bn), "-rheology_papanastasiou_m", "1e5", "-steady_continuation_start", "1e2", "-output_fields", "0"], d)
        s = summary(d)
        res[bn] = s
        print("Bn %.2f: Q/Q_newtonian %.3e, plug area %.4f (Bn_c %.5f)" % (bn, s["flow_rate"] / qn, s["plug_area"], s["bn_critical"]))
        if prev is not None and not (s["flow_rate"] < prev["flow_rate"] and s["plug_area"] >= prev["plug_area"]):
            fail("flow rate must fall and plug area grow with Bn (Bn %g)" % bn)
        prev = s
    if not (res[0.25]["flow_rate"] / qn > 1e-3 and res[0.25]["plug_area"] < 0.8):
        fail("Bn = 0.25 (below Bn_c) should flow: Q/Qn %g, plug area %g" % (res[0.25]["flow_rate"] / qn, res[0.25]["plug_area"]))
    if not (res[0.28]["flow_rate"] / qn < 1e-3 and res[0.28]["plug_area"] > 0.99):
        fail("Bn = 0.28 (above Bn_c) should be arrested: Q/Qn %g, plug area %g" % (res[0.28]["flow_rate"] / qn, res[0.28]["plug_area"]))


def test_stability_duct_bn1():
    """Hard case: the duct at Bn = 1.0 (far beyond the threshold), Papanastasiou
    m = 1e5, continuation from 1e2: every step converges within 15 Newton
    iterations (budget), outputs finite, the whole duct unyielded."""
    d = work("stability_duct")
    p = run("duct", ["-bn", "1.0", "-rheology_papanastasiou_m", "1e5", "-steady_continuation_start", "1e2", "-output_fields", "0"], d)
    its = continuation_newton(p.stdout)
    s = summary(d)
    print("Newton iterations per continuation step %s; plug area %.4f; flow rate %.3e" % (its, s["plug_area"], s["flow_rate"]))
    if len(its) != 4 or max(its) > 15:
        fail("expected 4 continuation steps of <= 15 Newton iterations, got %s" % its)
    if not (math.isfinite(s["flow_rate"]) and s["plug_area"] > 0.999):
        fail("expected a finite creep flow rate and a plug covering the duct, got %g and %g" % (s["flow_rate"], s["plug_area"]))


def test_stability_bagnold_lambda1e8():
    """Hard case: mu(I) Bagnold with lambda_r = 1e-8 (vanishing pressure at the
    free surface), continuation from 1e-1: every step converges within 10
    Newton iterations (budget), outputs finite, relative error <= 1e-3."""
    d = work("stability_bagnold")
    p = run("bagnold", ["-rheology_mui_lambda_r", "1e-8", "-steady_continuation_start", "1e-1", "-output_fields", "0"], d)
    its = continuation_newton(p.stdout)
    s = summary(d)
    rel = s["err_u_l2"] / s["norm_u_l2"]
    print("Newton iterations per continuation step %s; relative L2 error %.3e" % (its, rel))
    if len(its) != 8 or max(its) > 10:
        fail("expected 8 continuation steps of <= 10 Newton iterations, got %s" % its)
    for k in ("kinetic_energy", "mean_shear_rate", "err_u_l2", "surface_velocity"):
        if not math.isfinite(s[k]):
            fail("%s is not finite" % k)
    if not rel <= 1e-3:
        fail("relative L2 error expected <= 1e-3, got %g" % rel)


def test_poiseuille():
    """Bingham-Papanastasiou plane Poiseuille, continuation m = 1e2 -> 1e6 on a
    32-cell-across mesh: relative L2 velocity error <= 1e-3; plug half-width
    within one cell (2H/32) of tau0/G."""
    d = work("poiseuille")
    run("poiseuille", ["-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2", "-mesh_ny", "32"], d)
    s = summary(d)
    rel = s["err_u_l2"] / s["norm_u_l2"]
    h = 2.0 * s["H"] / 32
    print("m = 1e6: relative L2 error %.3e; plug half-width %.4f (exact %.4f, cell %.4f)" % (rel, s["plug_half_width"], s["plug_half_width_exact"], h))
    if not rel <= 1e-3:
        fail("relative L2 velocity error expected <= 1e-3, got %g" % rel)
    if not abs(s["plug_half_width"] - s["plug_half_width_exact"]) <= h:
        fail("plug half-width expected within %g of %g, got %g" % (h, s["plug_half_width_exact"], s["plug_half_width"]))


def test_poiseuille_parallel():
    """poiseuille on 2 ranks gives the 1-rank diagnostics to 1e-8 relative."""
    w = work("poiseuille_parallel")
    opts = ["-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2", "-output_fields", "0", "-newton_rtol", "1e-12"]
    run("poiseuille", opts, os.path.join(w, "p1"))
    run("poiseuille", opts, os.path.join(w, "p2"), ranks=2)
    s1, s2 = summary(os.path.join(w, "p1")), summary(os.path.join(w, "p2"))
    if s2["ranks"] != 2:
        fail("expected a 2-rank run, summary says %s" % s2["ranks"])
    for k in ("kinetic_energy", "mean_shear_rate", "max_shear_rate", "flow_rate", "err_u_l2"):
        rel = abs(s1[k] - s2[k]) / max(abs(s1[k]), 1e-300)
        print("%-16s 1 rank %.12e  2 ranks %.12e  rel diff %.2e" % (k, s1[k], s2[k], rel))
        if not rel <= 1e-8:
            fail("%s: 1 and 2 ranks expected equal to 1e-8 relative, got %g" % (k, rel))


def test_couette_parallel():
    """couette_cessation on 2 ranks agrees with 1 rank within 10x rtol: arrest
    time, and every output of the kinetic energy, mean and L2 shear rates and
    dissipation, each difference scaled by that series' largest value.

    The 2-rank run is not bitwise reproducible: with MUMPS on 2 ranks the
    roundoff differs from run to run when the machine is loaded (with GMRES
    and block-Jacobi PETSc LU instead, three loaded runs were identical), and
    a roundoff-level change can flip one of IDA's step decisions. The
    trajectory then differs at the level of rtol, which is what this test
    allows. It does not compare values relative to themselves near arrest:
    there the kinetic energy behaves like (T - t)^2, so a shift of T by 3e-4
    relative (within the tolerance) changes the energy at t = 0.1 by 2e-2
    relative. 1-rank runs at rtol x (1 +- 1e-3), which take other steps,
    differ from the nominal run by 1.4e-4 of the series' largest value and
    4.4e-4 in arrest time."""
    w = work("couette_parallel")
    rtol = 1e-4
    opts = ["-time_rtol", str(rtol), "-time_atol", "1e-6", "-output_fields", "0", "-time_final", "0.12"]
    run("couette_cessation", opts, os.path.join(w, "p1"))
    run("couette_cessation", opts, os.path.join(w, "p2"), ranks=2)
    s1, s2 = summary(os.path.join(w, "p1")), summary(os.path.join(w, "p2"))
    rel = abs(s1["t_arrest"] - s2["t_arrest"]) / s1["t_arrest"]
    print("arrest time: 1 rank %.8f, 2 ranks %.8f, rel diff %.2e; steps %d vs %d" % (s1["t_arrest"], s2["t_arrest"], rel, s1["steps"], s2["steps"]))
    if not rel <= 10 * rtol:
        fail("arrest times differ by %g relative, expected <= %g" % (rel, 10 * rtol))
    a, b = series(os.path.join(w, "p1")), series(os.path.join(w, "p2"))
    if len(a) != len(b):
        fail("series have %d and %d outputs" % (len(a), len(b)))
    for k in ("kinetic_energy", "mean_shear_rate", "l2_shear_rate", "dissipation"):
        scale = max(abs(r[k]) for r in a)
        worst = max(abs(r1[k] - r2[k]) for r1, r2 in zip(a, b)) / scale
        print("%s: largest difference %.2e of the series' largest value %.6e" % (k, worst, scale))
        if not worst <= 10 * rtol:
            fail("%s series differ by %g of their largest value, expected <= %g" % (k, worst, 10 * rtol))


def test_demo():
    """The flagship demo: Bingham Couette cessation, Bn = 1, m = 1e4, adaptive
    BDF2. The arrest time (mean shear rate < 1e-3) lies below the energy bound
    T <= ln(1 + pi^2/(2 sqrt(3) Bn))/pi^2 = 0.1366 and above half of it; the
    kinetic energy never increases (to 1e-12 relative); the outputs exist."""
    d = work("demo")
    run("couette_cessation", [], d)
    s = summary(d)
    bound = math.log(1 + math.pi ** 2 / (2 * math.sqrt(3) * 1.0)) / math.pi ** 2
    print("arrest at %.6f, energy bound %.6f (scene says %.6f); %d steps" % (s["t_arrest"], bound, s["t_stop_bound"], s["steps"]))
    if abs(s["t_stop_bound"] - bound) > 1e-9 * bound:
        fail("bound expected %g, got %g" % (bound, s["t_stop_bound"]))
    if not 0.5 * bound < s["t_arrest"] < bound:
        fail("arrest time expected in (%g, %g), got %g" % (0.5 * bound, bound, s["t_arrest"]))
    ser = series(d)
    ke_never_increases(ser, "demo", floor=1e-30)
    for f in ("summary.csv", "series.csv", "steps.csv", "fields.h5", "fields.xmf"):
        if not os.path.getsize(os.path.join(d, f)) > 0:
            fail("missing output %s" % f)
    with open(os.path.join(d, "fields.xmf")) as f:
        xmf = f.read()
    ntimes = xmf.count("<Time ")
    if ntimes != len(ser):
        fail("fields.xmf expected %d time steps, got %d" % (len(ser), ntimes))
    check_xdmf(d)


def check_xdmf(d):
    """Every HDF5 dataset fields.xmf points to exists in fields.h5 with the
    dimensions the XDMF file declares (read with h5ls)."""
    import xml.etree.ElementTree as ET
    h5 = subprocess.run(["h5ls", "-r", os.path.join(d, "fields.h5")], capture_output=True, text=True, check=True).stdout
    dims = {}
    for line in h5.splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2 and parts[1].startswith("Dataset"):
            dims[parts[0]] = [int(x.split("/")[0]) for x in parts[1].split("{")[1].rstrip("}").split(",")]
    n = 0
    for item in ET.parse(os.path.join(d, "fields.xmf")).iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        path = item.text.strip().split(":", 1)[1]
        want = [int(x) for x in item.get("Dimensions").split()]
        if dims.get(path) != want:
            fail("fields.xmf declares %s with dimensions %s; fields.h5 has %s" % (path, want, dims.get(path)))
        n += 1
    print("fields.xmf: %d HDF5 references, all present with the declared dimensions" % n)


def test_couette_steady_initial():
    """KINSOL computes the initial state (steady flow with the plate moving,
    -couette_initial steady); the arrest time agrees with the run from the
    analytic profile u = y within 10 x rtol (rtol = 1e-4)."""
    w = work("couette_steady_initial")
    opts = ["-time_final", "0.11", "-output_fields", "0"]
    run("couette_cessation", opts, os.path.join(w, "analytic"))
    p = run("couette_cessation", opts + ["-couette_initial", "steady"], os.path.join(w, "steady"))
    if not any(l.startswith("steady:") and "Newton" in l for l in p.stdout.splitlines()):
        fail("the steady initial solve did not report its Newton line")
    a, b = summary(os.path.join(w, "analytic")), summary(os.path.join(w, "steady"))
    rel = abs(a["t_arrest"] - b["t_arrest"]) / a["t_arrest"]
    print("arrest time: analytic start %.8f, steady start %.8f, rel diff %.2e" % (a["t_arrest"], b["t_arrest"], rel))
    if not rel <= 1e-3:
        fail("arrest times expected to agree within 1e-3 relative, got %g" % rel)


def test_arrest_criteria():
    """Several arrest criteria at once on the demo (Couette cessation, Bn = 1,
    m = 1e4), each root-found by IDA with its own time: mean, max and L2
    shear rate < 1e-3, kinetic energy < 1e-6 x its initial value (relative),
    yielded fraction < 1e-3, and the creep threshold 10 x tau_c/(eta_p + tau0 m)
    on the mean shear rate. Every criterion fires, between half the energy
    bound and the bound (0.1366); thresholds resolve as stated (1e-12
    relative); the step count equals that of a single-criterion run. The
    fixed-step BDF2 mode (dt = 4e-4, 300 steps) finds the mean-shear-rate
    arrest within 1e-3 relative of IDA's."""
    w = work("arrest_criteria")
    spec = "mean_shear_rate:1e-3,max_shear_rate:1e-3,l2_shear_rate:1e-3,kinetic_energy:1e-6:relative,yielded_fraction:1e-3,mean_shear_rate:10:creep"
    d = os.path.join(w, "ida")
    run("couette_cessation", ["-arrest", spec, "-output_fields", "0", "-time_final", "0.12"], d)
    s = summary(d)
    ke0 = series(d)[0]["kinetic_energy"]
    bound = s["t_stop_bound"]
    expect = {"mean_shear_rate": 1e-3, "max_shear_rate": 1e-3, "l2_shear_rate": 1e-3, "kinetic_energy_relative": 1e-6 * ke0, "yielded_fraction": 1e-3, "mean_shear_rate_creep": 10.0 / (1.0 + 1.0 * 1e4)}
    for name, thr in expect.items():
        t = s["t_arrest_" + name]
        print("%-26s threshold %.4e (expected %.4e)  arrest at t = %.6f" % (name, s["threshold_" + name], thr, t))
        if abs(s["threshold_" + name] - thr) > 1e-9 * thr:
            fail("%s: threshold expected %g, got %g" % (name, thr, s["threshold_" + name]))
        if not 0.5 * bound < t < bound:
            fail("%s: arrest time expected in (%g, %g), got %g" % (name, 0.5 * bound, bound, t))
    d1 = os.path.join(w, "single")
    run("couette_cessation", ["-output_fields", "0", "-time_final", "0.12"], d1)
    s1 = summary(d1)
    if s1["steps"] != s["steps"]:
        fail("root functions changed the step sequence: %d steps vs %d" % (s["steps"], s1["steps"]))
    d2 = os.path.join(w, "bdf2")
    run("couette_cessation", ["-time_integrator", "bdf2", "-time_dt", "4e-4", "-output_fields", "0", "-time_final", "0.12"], d2)
    s2 = summary(d2)
    rel = abs(s2["t_arrest_mean_shear_rate"] - s["t_arrest_mean_shear_rate"]) / s["t_arrest_mean_shear_rate"]
    print("BDF2 dt 4e-4: arrest %.6f in %d steps; IDA %.6f in %d steps (run to 0.12); rel diff %.1e" % (s2["t_arrest_mean_shear_rate"], s2["steps"], s["t_arrest_mean_shear_rate"], s["steps"], rel))
    if not rel <= 1e-3:
        fail("BDF2 and IDA arrest times expected within 1e-3, got %g" % rel)


def test_eigen_bounds():
    """SLEPc: lambda1 of the viscous operator with the scene's walls matches
    pi^2/L^2 on the Couette strip and 2 pi^2/L^2 on the square duct (scalar
    Laplacian) to 0.5 %; the energy bound printed for Couette cessation lies
    above the detected arrest time."""
    w = work("eigen")
    d = os.path.join(w, "couette")
    p = run("couette_cessation", ["-viscous_eigenvalue", "-time_final", "0.12", "-output_fields", "0"], d)
    s = summary(d)
    rel = abs(s["lambda1"] - math.pi ** 2) / math.pi ** 2
    print("Couette strip: lambda1 %.8f (pi^2 = %.8f, rel %.1e); bound %.6f > arrest %.6f" % (s["lambda1"], math.pi ** 2, rel, s["t_stop_bound_slepc"], s["t_arrest"]))
    if not rel <= 5e-3:
        fail("Couette lambda1 expected within 0.5 %% of pi^2, got %g" % s["lambda1"])
    if "energy bound on the exact stopping time" not in p.stdout or not s["t_arrest"] < s["t_stop_bound_slepc"]:
        fail("expected a printed bound above the arrest time, got %g vs %g" % (s["t_stop_bound_slepc"], s["t_arrest"]))
    d = os.path.join(w, "duct")
    run("duct", ["-viscous_eigenvalue", "-rheology_type", "newtonian", "-output_fields", "0"], d)
    s = summary(d)
    rel = abs(s["lambda1"] - 2 * math.pi ** 2) / (2 * math.pi ** 2)
    print("square duct: lambda1 %.8f (2 pi^2 = %.8f, rel %.1e)" % (s["lambda1"], 2 * math.pi ** 2, rel))
    if not rel <= 5e-3:
        fail("duct lambda1 expected within 0.5 %% of 2 pi^2, got %g" % s["lambda1"])


def test_poiseuille_cessation():
    """Bingham Poiseuille cessation (Bn = 0.5, m = 1e4): KINSOL's steady
    initial state has the L2 norm of the exact steady profile across the
    channel within 1e-3; the kinetic energy never increases after the driving
    is removed; the mean-shear-rate arrest lies between half the energy bound
    (4/pi^2) ln(1 + pi^2 ||u0|| / (4 sqrt(2) Bn)) and the bound."""
    d = work("poiseuille_cessation")
    run("poiseuille_cessation", ["-output_fields", "0", "-arrest_stop", "first"], d)
    s = summary(d)
    n = 20000
    tot = 0.0
    for i in range(n):
        y = -1 + (i + 0.5) * 2.0 / n
        ay = max(abs(y), 0.5)
        u = (1 - ay * ay) / 2 - 0.5 * (1 - ay)
        tot += u * u * 2.0 / n
    exact = math.sqrt(tot)
    bound = 4 / math.pi ** 2 * math.log(1 + math.pi ** 2 * exact / (4 * math.sqrt(2) * 0.5))
    print("||u0|| %.6f (exact steady %.6f); arrest %.6f; bound %.6f (scene %.6f)" % (s["u0_norm"], exact, s["t_arrest"], bound, s["t_stop_bound"]))
    if abs(s["u0_norm"] - exact) > 1e-3 * exact:
        fail("initial norm expected %g, got %g" % (exact, s["u0_norm"]))
    if not 0.5 * bound < s["t_arrest"] < bound:
        fail("arrest expected in (%g, %g), got %g" % (0.5 * bound, bound, s["t_arrest"]))
    ke_never_increases(series(d), "Poiseuille cessation", floor=1e-30)


def test_arrest_convergence():
    """Poiseuille cessation (Bn = 0.5): as Papanastasiou m grows 1e2 ... 1e6 the
    arrest time of every criterion (mean and max shear rate < 1e-3, kinetic
    energy < 1e-6 x initial, yielded fraction < 1e-3) converges: successive
    differences shrink until they reach the temporal error (1e-3 relative),
    the last one below 2e-4 relative (yielded fraction:
    1.3e-4, the slowest; mean shear rate 6e-6); for m >= 1e3 every
    arrest lies below the energy bound (at m = 1e2 the soft model creeps past
    the exact model's bound: measured 0.1795 > 0.1779 for kinetic energy)."""
    w = work("arrest_convergence")
    names = ["mean_shear_rate", "max_shear_rate", "kinetic_energy_relative", "yielded_fraction"]
    spec = "mean_shear_rate:1e-3,max_shear_rate:1e-3,kinetic_energy:1e-6:relative,yielded_fraction:1e-3"
    times = {n: [] for n in names}
    for m in (1e2, 1e3, 1e4, 1e5, 1e6):
        d = os.path.join(w, "m%g" % m)
        # atol pinned at 1e-8: the temporal error stays below the m-differences
        # (the default 1e-3 rtol max|u0| leaves 8e-5 of noise in max_shear_rate)
        run("poiseuille_cessation", ["-rheology_papanastasiou_m", "%g" % m, "-arrest", spec, "-time_final", "0.3", "-output_fields", "0", "-time_atol", "1e-8"], d)
        s = summary(d)
        for n in names:
            times[n].append(s["t_arrest_" + n])
            if m >= 1e3 and not s["t_arrest_" + n] < s["t_stop_bound"]:
                fail("m = %g, %s: arrest %g expected below the bound %g" % (m, n, s["t_arrest_" + n], s["t_stop_bound"]))
    for n in names:
        t = times[n]
        diffs = [abs(t[i + 1] - t[i]) for i in range(len(t) - 1)]
        print("%-24s %s  differences %s" % (n, " ".join("%.6f" % x for x in t), " ".join("%.1e" % x for x in diffs)))
        # differences below 1e-3 relative are at the level of the temporal
        # error (rtol 1e-4): there they need not shrink (max_shear_rate at
        # m = 1e3, 1e4, 1e5: 0.148327, 0.148262, 0.148340 at rtol 1e-4 and
        # 0.148327, 0.148222, 0.148300 at 1e-5, both linearisations alike)
        if any(diffs[i + 1] >= diffs[i] and diffs[i + 1] > 1e-3 * t[-1] for i in range(len(diffs) - 1)) or diffs[-1] > 2e-4 * t[-1]:
            fail("%s: successive differences expected to shrink (down to the temporal error, 1e-3 relative) and the last to be < 2e-4 relative, got %s" % (n, diffs))


def test_ida_linesearch():
    """IDA's stage solvers on the demo at rtol 1e-3, atol 1e-5: the primal
    modified Newton, the globalised one (-ida_nonlinear_solver linesearch:
    KINSOL, exact Jacobian, line search per BDF stage) and the default
    stress-velocity Newton each find the arrest time within 3e-3 of the
    exact model's (measured 1.3e-3, 8.0e-4, 2.4e-3: the solvers differ by
    1e-3 at this rtol); the line search needs fewer than a fifth of the
    primal Newton's steps (measured 200 against 2289), and the
    stress-velocity Newton has no convergence failure and fewer than a fifth
    of the primal steps (measured 308)."""
    w = work("ida_linesearch")
    opts = ["-time_rtol", "1e-3", "-time_atol", "1e-5", "-time_final", "0.12", "-output_fields", "0"]
    run("couette_cessation", opts + ["-newton_linearisation", "primal"], os.path.join(w, "newton"))
    run("couette_cessation", opts + ["-newton_linearisation", "primal", "-ida_nonlinear_solver", "linesearch"], os.path.join(w, "linesearch"))
    run("couette_cessation", opts, os.path.join(w, "stress_velocity"))
    a, b, c = summary(os.path.join(w, "newton")), summary(os.path.join(w, "linesearch")), summary(os.path.join(w, "stress_velocity"))
    rel = abs(a["t_arrest"] - b["t_arrest"]) / a["t_arrest"]
    relc = abs(a["t_arrest"] - c["t_arrest"]) / a["t_arrest"]
    errs = [abs(x["t_arrest"] - x["t_arrest_exact"]) / x["t_arrest_exact"] for x in (a, b, c)]
    print("errors against the exact arrest time %.6f: primal %.1e, line search %.1e, stress-velocity %.1e" % (a["t_arrest_exact"], errs[0], errs[1], errs[2]))
    print("IDA Newton: arrest %.6f, %d steps, %d convergence failures, %.1f s; line search: %.6f, %d steps, %d failures, %.1f s; rel diff %.1e"
          % (a["t_arrest"], a["steps"], a["conv_fails"], a["wall_time"], b["t_arrest"], b["steps"], b["conv_fails"], b["wall_time"], rel))
    print("stress-velocity Newton: arrest %.6f, %d steps, %d Newton iterations, %d convergence failures, %.1f s; rel diff %.1e"
          % (c["t_arrest"], c["steps"], c["newton_its"], c["conv_fails"], c["wall_time"], relc))
    if not max(errs) <= 3e-3:
        fail("arrest times expected within 3e-3 of the exact one, got %s" % errs)
    if not b["steps"] * 5 < a["steps"]:
        fail("line search expected to need < 1/5 of the steps: %d vs %d" % (b["steps"], a["steps"]))
    if c["conv_fails"] != 0 or not c["steps"] * 5 < a["steps"]:
        fail("stress-velocity Newton expected without convergence failures and < 1/5 of the steps: %d failures, %d vs %d steps" % (c["conv_fails"], c["steps"], a["steps"]))


def steps(outdir):
    with open(os.path.join(outdir, "steps.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def ke_never_increases(ser, what, rel=1e-9, floor=None):
    """Kinetic energy non-increasing along the output series, to 1e-12
    relative plus an absolute floor: rel x its initial value (round-off once
    the flow has stopped) unless `floor` is given."""
    if floor is None:
        floor = rel * ser[0]["kinetic_energy"]
    for r0, r1 in zip(ser, ser[1:]):
        if r1["kinetic_energy"] > r0["kinetic_energy"] * (1 + 1e-12) + floor:
            fail("%s: kinetic energy increased at t = %g (%.6e -> %.6e)" % (what, r1["t"], r0["kinetic_energy"], r1["kinetic_energy"]))


def test_duct_cessation():
    """Anti-plane duct cessation. (1) Newtonian fluid from its steady duct
    flow: the initial mean velocity matches the series value 0.0351442 G L^2 /
    eta within 2e-3, and after the gradient is removed the energy decays at
    late times as exp(-2 lambda1 t), lambda1 = 2 pi^2, within 0.5 %. (2)
    Bingham, Bn = tau0/(G L) = 0.1, m = 1e4, from the steady Bingham flow
    (KINSOL): every criterion fires below the energy bound with beta = 2
    sqrt(pi) (analytic lambda1, and the SLEPc one within 1e-3 of it); the
    kinetic energy never increases."""
    w = work("duct_cessation")
    s_newt = 0.0
    for m in range(1, 400, 2):
        for n in range(1, 400, 2):
            s_newt += 1.0 / (m * m * n * n * (m * m + n * n))
    wmean = 64.0 / math.pi ** 6 * s_newt
    d = os.path.join(w, "newtonian")
    run("duct_cessation", ["-rheology_type", "newtonian", "-initial_flow", "newtonian", "-time_final", "0.15", "-time_output_dt", "0.01",
                           "-time_rtol", "1e-6", "-time_atol", "1e-12", "-output_fields", "0", "-arrest", "kinetic_energy:1e-30"], d)
    s = summary(d)
    ser = series(d)
    rate = -math.log(ser[-1]["kinetic_energy"] / ser[-6]["kinetic_energy"]) / (ser[-1]["t"] - ser[-6]["t"]) / 2
    print("Newtonian: initial mean velocity %.7f (series %.7f); late decay rate %.5f (2 pi^2 = %.5f)" % (s["u0_mean"], wmean, rate, 2 * math.pi ** 2))
    if abs(s["u0_mean"] - wmean) > 2e-3 * wmean:
        fail("initial mean velocity expected %g within 2e-3, got %g" % (wmean, s["u0_mean"]))
    if abs(rate - 2 * math.pi ** 2) > 5e-3 * 2 * math.pi ** 2:
        fail("late decay rate expected 2 pi^2 within 0.5 %%, got %g" % rate)
    ke_never_increases(ser, "Newtonian duct")
    d = os.path.join(w, "bingham")
    spec = "mean_shear_rate:1e-3,max_shear_rate:1e-3,kinetic_energy:1e-6:relative,yielded_fraction:1e-3"
    run("duct_cessation", ["-viscous_eigenvalue", "-arrest", spec, "-output_fields", "0"], d)
    s = summary(d)
    bound = s["t_stop_bound"]
    print("Bingham Bn 0.1: bound %.6f (SLEPc %.6f), bn_mean %.4f" % (bound, s["t_stop_bound_slepc"], s["bn_mean"]))
    if abs(s["t_stop_bound_slepc"] - bound) > 1e-3 * bound:
        fail("SLEPc bound expected within 1e-3 of the analytic one")
    for n in ("mean_shear_rate", "max_shear_rate", "kinetic_energy_relative", "yielded_fraction"):
        t = s["t_arrest_" + n]
        print("  %-24s arrest at t = %.6f" % (n, t))
        if not 0.5 * bound < t < bound:
            fail("%s: arrest expected in (%g, %g), got %g" % (n, 0.5 * bound, bound, t))
    ke_never_increases(series(d), "Bingham duct")


def linear_iterative_poiseuille(w, ranks_iter=1):
    """Steady Bingham Poiseuille (m 1e2 -> 1e4, 8 x 32, Newton to 1e-12):
    LU on one rank against -linear_solver iterative (both Schur
    preconditioners) on ranks_iter ranks: diagnostics equal to 1e-8
    relative (the L2 error's difference relative to the velocity's norm)."""
    opts = ["-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2", "-output_fields", "0", "-newton_rtol", "1e-12"]
    run("poiseuille", opts, os.path.join(w, "direct"))
    ref = summary(os.path.join(w, "direct"))
    for pre in ("mass", "selfp"):
        d = os.path.join(w, "iterative_" + pre)
        run("poiseuille", opts + ["-linear_solver", "iterative", "-stokes_schur_pre", pre], d, ranks=ranks_iter)
        s = summary(d)
        print("Poiseuille, Schur pre %s on %d rank(s): %d Newton (LU %d), %d Krylov iterations" % (pre, s["ranks"], s["newton_its"], ref["newton_its"], s["lin_its"]))
        for k in ("kinetic_energy", "mean_shear_rate", "flow_rate", "err_u_l2"):
            # the error's change is bounded by that of the velocity: relative to its norm
            rel = abs(s[k] - ref[k]) / max(abs(ref["norm_u_l2" if k == "err_u_l2" else k]), 1e-300)
            print("  %-16s LU %.12e  iterative %.12e  rel diff %.2e" % (k, ref[k], s[k], rel))
            if not rel <= 1e-8:
                fail("%s (%s): iterative and LU expected equal to 1e-8 relative, got %g" % (k, pre, rel))


def linear_iterative_arrest(w, scene, opts, ranks_iter=1):
    """Arrest time of a cessation: LU on one rank against -linear_solver
    iterative on ranks_iter ranks, within 10 rtol."""
    run(scene, opts, os.path.join(w, scene + "_direct"))
    run(scene, opts + ["-linear_solver", "iterative"], os.path.join(w, scene + "_iterative"), ranks=ranks_iter)
    a, b = summary(os.path.join(w, scene + "_direct")), summary(os.path.join(w, scene + "_iterative"))
    rel = abs(a["t_arrest"] - b["t_arrest"]) / a["t_arrest"]
    print("%s: arrest LU %.8f, iterative (%d rank(s)) %.8f, rel diff %.2e (rtol %g); %d Newton, %d Krylov iterations (%.1f per Newton iteration)" % (
        scene, a["t_arrest"], b["ranks"], b["t_arrest"], rel, a["rtol"], b["newton_its"], b["lin_its"], b["lin_its"] / max(b["newton_its"], 1)))
    if not a["t_arrest"] > 0 or not rel <= 10 * a["rtol"]:
        fail("%s: arrest times differ by %g relative, expected <= 10 rtol = %g" % (scene, rel, 10 * a["rtol"]))


def linear_iterative_levelset(w, ranks_iter=1):
    """Two-phase Newtonian dam break (21 x 22 cells, level set, density and
    viscosity ratios 1e-3) to t = 0.05 s: LU on one rank against
    -linear_solver iterative (flow by the Schur fieldsplit with selfp, level
    set by ILU, block Gauss-Seidel) on ranks_iter ranks: front, axis height,
    potential and kinetic energy within max(10 rtol, 3 e_LU) relative, where
    e_LU = |LU(rtol) - LU(rtol / 10)| is LU's own time-integration error.
    Two adaptive runs whose linear solves differ at the Krylov tolerance take
    different steps and reinitialise the level set at different times, so
    they differ by the integration error, not by the Krylov tolerance:
    measured, the kinetic energy of LU moves by 7.0e-4 from rtol 1e-4 to
    1e-5 (3.7e-4 for rtol x 1.001) and the iterative run's by 1.5e-3 from
    LU's (8.3e-5 from LU at 1e-5)."""
    opts = ["-mesh_nx", "21", "-mesh_ny", "22", "-time_final", "0.05", "-output_fields", "0"]
    run("dam_break", opts, os.path.join(w, "dam_break_direct"))
    a = summary(os.path.join(w, "dam_break_direct"))
    run("dam_break", opts + ["-time_rtol", repr(a["rtol"] / 10)], os.path.join(w, "dam_break_direct_tight"))
    run("dam_break", opts + ["-linear_solver", "iterative"], os.path.join(w, "dam_break_iterative"), ranks=ranks_iter)
    r, b = summary(os.path.join(w, "dam_break_direct_tight")), summary(os.path.join(w, "dam_break_iterative"))
    print("dam_break 21 x 22 to t = 0.05: iterative on %d rank(s): %d Krylov iterations for %d solves (%.1f per solve), %d steps (LU %d)" % (
        b["ranks"], b["lin_its"], b["lin_solves"], b["lin_its"] / max(b["lin_solves"], 1), b["steps"], a["steps"]))
    for k in ("front", "height_axis", "potential_energy", "kinetic_energy"):
        rel, e_lu = abs(a[k] - b[k]) / abs(a[k]), abs(a[k] - r[k]) / abs(a[k])
        tol = max(10 * a["rtol"], 3 * e_lu)
        print("  %-17s LU %.10e  iterative %.10e  rel diff %.2e (LU's integration error %.2e, tolerance %.2e)" % (k, a[k], b[k], rel, e_lu, tol))
        if not rel <= tol:
            fail("dam_break %s: iterative and LU differ by %g relative, expected <= max(10 rtol, 3 x LU's integration error) = %g" % (k, rel, tol))


def test_linear_iterative():
    """-linear_solver iterative reproduces the direct (MUMPS LU) results.
    (1) Steady Bingham Poiseuille: equal to 1e-8 (linear_iterative_poiseuille).
    (2) Newtonian Poiseuille on 8 x 32, 16 x 64, 32 x 128 cells (2 313 to
    36 897 unknowns) with a fixed Krylov tolerance of 1e-10: Krylov
    iterations per solve at most 40 and growing by at most 25 % over the
    16-fold refinement (measured 27, 28, 29). (3) Arrest times of
    duct_cessation (anti-plane: GMRES + BoomerAMG) and of cavity_cessation
    on 8 x 8 cells (enclosed Stokes with inertia, the pressure pinned) within
    10 rtol of LU's. (4) The two-phase dam break with its level set
    (linear_iterative_levelset). (5) A Krylov solve that fails is named as
    the cause of the failed Newton solve (linear_iterative_failure). (6) The
    switches to the deflated velocity block and then to an inner velocity
    solve, forced on Bingham Poiseuille 8 x 32 (linear_iterative_escalation)."""
    w = work("linear_iterative")
    linear_iterative_poiseuille(w)
    its = []
    for ny in (32, 64, 128):
        d = os.path.join(w, "newtonian_%d" % ny)
        run("poiseuille", ["-rheology_yield_stress", "0", "-mesh_nx", str(ny // 4), "-mesh_ny", str(ny), "-output_fields", "0",
                           "-linear_solver", "iterative", "-linear_forcing", "fixed"], d)
        s = summary(d)
        its.append(s["lin_its"] / s["lin_solves"])
        print("Newtonian Poiseuille %d x %d, %d unknowns: %.1f Krylov iterations per solve" % (ny // 4, ny, s["unknowns"], its[-1]))
    if max(its) > 40 or its[-1] > 1.25 * its[0]:
        fail("Krylov iterations per solve expected <= 40 and growing by <= 25 %%, got %s" % its)
    linear_iterative_arrest(w, "duct_cessation", ["-output_fields", "0"])
    linear_iterative_arrest(w, "cavity_cessation", ["-mesh_nx", "8", "-mesh_ny", "8", "-output_fields", "0"])
    linear_iterative_levelset(w)
    linear_iterative_failure(w)
    linear_iterative_escalation(w, "8", "1e4", "20", ["deflated", "GMRES"])


def linear_iterative_escalation(w, nx, m, its, rungs):
    """Steady Bingham Poiseuille (nx x 4 nx cells, continuation from
    m = 1e2 to m): with -linear_solver iterative -linear_escalate_its its, a
    Krylov solve passes its iterations and the run climbs the rungs named
    in rungs, each announced once by a line "linear: a Krylov solve
    stopped": "deflated" (the plugs' rigid motions deflated around two
    V-cycles), then "GMRES" (an inner GMRES solve of the velocity block);
    it converges, and its diagnostics equal LU's to 1e-8 relative."""
    opts = ["-mesh_nx", nx, "-mesh_ny", str(4 * int(nx)), "-rheology_papanastasiou_m", m, "-steady_continuation_start", "1e2", "-output_fields", "0"]
    dl, di = os.path.join(w, "escalation_%s_%s_direct" % (nx, m)), os.path.join(w, "escalation_%s_%s_iterative" % (nx, m))
    run("poiseuille", opts, dl)
    p = subprocess.run([ARGS.slump, "-scene", "poiseuille", "-output_dir", di] + opts + ["-linear_solver", "iterative", "-linear_escalate_its", its], capture_output=True, text=True)
    if p.returncode != 0:
        fail("escalation (%s x %d, m %s): the iterative run failed:\n%s" % (nx, 4 * int(nx), m, p.stderr[-2000:]))
    a, b = summary(dl), summary(di)
    line = [l for l in p.stdout.splitlines() if l.startswith("linear: a Krylov solve stopped")]
    print("escalation, poiseuille %s x %d, m %s, -linear_escalate_its %s: %s; %d Newton (LU %d), %d Krylov iterations, %.1f s (LU %.1f s)" % (
        nx, 4 * int(nx), m, its, " / ".join(l[l.find("from now on"):][:60] for l in line) if line else "no switch", b["newton_its"], a["newton_its"], b["lin_its"], b["wall_time"], a["wall_time"]))
    if len(line) != len(rungs) or any(r not in l for r, l in zip(rungs, line)):
        fail("escalation: expected the switches %s announced once each, in that order, got %s" % (rungs, line))
    for k in ("kinetic_energy", "mean_shear_rate", "flow_rate", "err_u_l2"):
        rel = abs(a[k] - b[k]) / max(abs(a["norm_u_l2" if k == "err_u_l2" else k]), 1e-300)
        print("  %-16s LU %.12e  iterative %.12e  rel diff %.2e" % (k, a[k], b[k], rel))
        if not rel <= 1e-8:
            fail("escalation %s: iterative and LU expected equal to 1e-8 relative, got %g" % (k, rel))


def test_stability_linear_iterative_stiff():
    """-linear_solver iterative at Papanastasiou m = 1e6 (poiseuille
    16 x 64, 9 233 unknowns): one BoomerAMG V-cycle per application stalls
    (a solve passes the default -linear_escalate_its 1000), the run switches
    to the deflated velocity block (first rung; measured: no second switch,
    5 776 Krylov iterations, 23 s, against 5 909 and 40 s when the switch
    went to the inner GMRES solve at once) and converges to LU's solution
    (equal to 1e-8). Before the switch existed this run failed."""
    linear_iterative_escalation(work("linear_iterative_stiff"), "16", "1e6", "1000", ["deflated"])


def test_linear_schwarz_memory():
    """hypre's Schwarz smoothers on the velocity block
    (-fieldsplit_u_pc_hypre_boomeramg_smooth_type Schwarz-smoothers), Bingham
    Poiseuille 16 x 64 from m = 1e2 to 1e4 (26 Newton steps, each a new
    Jacobian and a new BoomerAMG hierarchy): the peak memory stays within
    1.3 times that of the default V-cycle run (before the velocity block's
    hypre PC was made anew at each Jacobian it grew by ~9 MB per Newton step:
    297 MB against 78 MB), and both runs give LU's diagnostics to 1e-8."""
    w = work("linear_schwarz_memory")
    opts = ["-mesh_nx", "16", "-mesh_ny", "64", "-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2", "-output_fields", "0"]
    schwarz = ["-fieldsplit_u_pc_hypre_boomeramg_smooth_type", "Schwarz-smoothers", "-fieldsplit_u_pc_hypre_boomeramg_smooth_num_levels", "2", "-linear_escalate_its", "0"]
    runs = {}
    for name, extra in (("direct", []), ("vcycle", ["-linear_solver", "iterative"]), ("schwarz", ["-linear_solver", "iterative"] + schwarz)):
        d = os.path.join(w, name)
        run("poiseuille", opts + extra, d)
        runs[name] = summary(d)
        s = runs[name]
        print("%-8s %3d Newton, %5d Krylov iterations, peak %.0f MB, %.1f s" % (name, s["newton_its"], s["lin_its"], s["peak_memory_mb"], s["wall_time"]))
    if not runs["schwarz"]["peak_memory_mb"] <= 1.3 * runs["vcycle"]["peak_memory_mb"]:
        fail("Schwarz smoothers: peak memory %.0f MB expected within 1.3 x the V-cycle run's %.0f MB" % (runs["schwarz"]["peak_memory_mb"], runs["vcycle"]["peak_memory_mb"]))
    for name in ("vcycle", "schwarz"):
        for k in ("kinetic_energy", "mean_shear_rate", "flow_rate"):
            rel = abs(runs[name][k] - runs["direct"][k]) / abs(runs["direct"][k])
            if not rel <= 1e-8:
                fail("%s: %s expected equal to LU's to 1e-8 relative, got %g" % (name, k, rel))


def test_linear_deflation():
    """-stokes_velocity_deflation 1e-4 (coarse corrections on the rigid
    modes of the stiff regions, i.e. the plugs, around BoomerAMG V-cycles)
    on Bingham Poiseuille 16 x 64 from m = 1e2 to 1e6, where the default
    V-cycle stalls at m = 1e6 and the run has to switch to an inner velocity
    solve. (1) With the default strong threshold 0.7: no switch, at most 200
    Krylov iterations per solve in every continuation stage (measured 24,
    28, 32, 57, 159). (2) With the threshold 0.25, on 1 and 2 ranks: no
    switch, at most 100 per solve and growing by at most 2.5 times from
    m = 1e2 to 1e6 (measured 39, 37, 39, 45, 74). (3) The diagnostics of
    every run equal LU's to 1e-8 relative."""
    w = work("linear_deflation")
    opts = ["-mesh_nx", "16", "-mesh_ny", "64", "-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2", "-output_fields", "0"]
    dl = os.path.join(w, "direct")
    run("poiseuille", opts, dl)
    a = summary(dl)
    for name, ranks, extra, cap, growth in (("threshold 0.7", 1, [], 200, None),
                                            ("threshold 0.25", 1, ["-fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.25"], 100, 2.5),
                                            ("threshold 0.25", 2, ["-fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.25"], 100, 2.5)):
        d = os.path.join(w, "deflation_%s_%d" % (name.split()[-1], ranks))
        cmd = ([ARGS.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)] if ranks > 1 else []) + [
            ARGS.slump, "-scene", "poiseuille", "-output_dir", d] + opts + ["-linear_solver", "iterative", "-stokes_velocity_deflation", "1e-4"] + extra
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            fail("deflation, %s, %d rank(s): the run failed:\n%s" % (name, ranks, p.stderr[-2000:]))
        if any(l.startswith("linear: a Krylov solve stopped") for l in p.stdout.splitlines()):
            fail("deflation, %s, %d rank(s): the run switched to the inner velocity solve" % (name, ranks))
        stages = []
        for l in p.stdout.splitlines():
            m = re.match(r"steady: m = (\S+)\s+Newton\s+(\d+)\s+linear\s+(\d+)", l)
            if m:
                stages.append((float(m.group(1)), int(m.group(3)) / max(int(m.group(2)), 1)))
        b = summary(d)
        print("deflation, %s, %d rank(s): Krylov per solve %s; %d Newton (LU %d), %.1f s (LU %.1f s)" % (
            name, ranks, ", ".join("m %g: %.1f" % x for x in stages), b["newton_its"], a["newton_its"], b["wall_time"], a["wall_time"]))
        per = [x[1] for x in stages]
        if len(stages) != 5 or max(per) > cap or (growth and per[-1] > growth * per[0]):
            fail("deflation, %s, %d rank(s): expected 5 stages with <= %d Krylov iterations per solve%s, got %s" % (
                name, ranks, cap, ", growing by <= %g times" % growth if growth else "", stages))
        for k in ("kinetic_energy", "mean_shear_rate", "flow_rate", "err_u_l2"):
            rel = abs(a[k] - b[k]) / max(abs(a["norm_u_l2" if k == "err_u_l2" else k]), 1e-300)
            print("  %-16s LU %.12e  deflation %.12e  rel diff %.2e" % (k, a[k], b[k], rel))
            if not rel <= 1e-8:
                fail("deflation, %s, %d rank(s), %s: expected equal to LU's to 1e-8 relative, got %g" % (name, ranks, k, rel))


def test_linear_pin_correction():
    """The Schur preconditioner's correction on the constant pressure of
    enclosed flows (-stokes_schur_pin_correction, on by default). Fixing the
    pressure at one vertex leaves the Schur complement one eigenvalue of
    size h^2 on a nearly constant pressure, which the weighted mass does not
    see. (1) Newtonian cavity on 16^2, 32^2, 64^2 cells: at most 40 Krylov
    iterations and growing by at most 15 % (measured 35, 35, 33); without
    the correction on 32^2 at least 1.25 times as many (measured 49).
    (2) Steady Bingham cavity 16^2 (m = 1e4): at most 0.6 times the Krylov
    iterations of the uncorrected preconditioner (measured 1411 against
    2920), and psi_max, the unyielded area and the kinetic energy equal to
    LU's to 1e-8 relative on 1 and 2 ranks."""
    w = work("linear_pin_correction")

    def krylov(d, ranks, opts):
        cmd = ([ARGS.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)] if ranks > 1 else []) + [
            ARGS.slump, "-scene", "cavity", "-output_dir", d, "-output_fields", "0"] + opts
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            fail("pin correction, %s: the run failed:\n%s" % (" ".join(opts), p.stderr[-2000:]))
        return summary(d)

    its = []
    for n in (16, 32, 64):
        s = krylov(os.path.join(w, "newtonian_%d" % n), 1, ["-rheology_type", "newtonian", "-mesh_nx", str(n), "-mesh_ny", str(n), "-linear_solver", "iterative"])
        its.append(s["lin_its"] / s["lin_solves"])
    off = krylov(os.path.join(w, "newtonian_32_off"), 1, ["-rheology_type", "newtonian", "-mesh_nx", "32", "-mesh_ny", "32", "-linear_solver", "iterative", "-stokes_schur_pin_correction", "0"])
    off = off["lin_its"] / off["lin_solves"]
    print("Newtonian cavity 16^2, 32^2, 64^2: %s Krylov iterations per solve; 32^2 without the correction: %.1f" % (", ".join("%.1f" % x for x in its), off))
    if max(its) > 40 or its[-1] > 1.15 * its[0]:
        fail("pin correction: expected <= 40 Krylov iterations per solve growing by <= 15 %%, got %s" % its)
    if off < 1.25 * its[1]:
        fail("pin correction: expected the uncorrected preconditioner to need >= 1.25 times the iterations on 32^2, got %.1f against %.1f" % (off, its[1]))
    opts = ["-mesh_nx", "16", "-mesh_ny", "16"]
    a = krylov(os.path.join(w, "bingham_direct"), 1, opts)
    b0 = krylov(os.path.join(w, "bingham_off"), 1, opts + ["-linear_solver", "iterative", "-stokes_schur_pin_correction", "0"])
    for ranks in (1, 2):
        b = krylov(os.path.join(w, "bingham_%d" % ranks), ranks, opts + ["-linear_solver", "iterative"])
        print("Bingham cavity 16^2, %d rank(s): %d Krylov iterations in %d Newton steps (uncorrected, 1 rank: %d in %d), %.1f s (LU %.1f s)" % (
            ranks, b["lin_its"], b["newton_its"], b0["lin_its"], b0["newton_its"], b["wall_time"], a["wall_time"]))
        if ranks == 1 and b["lin_its"] > 0.6 * b0["lin_its"]:
            fail("pin correction: expected <= 0.6 times the uncorrected Krylov iterations, got %d against %d" % (b["lin_its"], b0["lin_its"]))
        for k in ("psi_max", "unyielded_area", "kinetic_energy"):
            rel = abs(a[k] - b[k]) / max(abs(a[k]), 1e-300)
            print("  %-16s LU %.12e  iterative %.12e  rel diff %.2e" % (k, a[k], b[k], rel))
            if not rel <= 1e-8:
                fail("pin correction, %d rank(s), %s: expected equal to LU's to 1e-8 relative, got %g" % (ranks, k, rel))


def linear_iterative_failure(w):
    """Krylov solves that stop (-ksp_max_it 5) end the run with one sentence
    that blames them, names -linear_solver iterative, the reason and the
    count, and gives the remedies; no PETSc traceback: in the steady Newton
    (Bingham Poiseuille) and in IDA's steps (the Newtonian decay)."""
    cases = (("poiseuille", ("a Krylov solve of -linear_solver iterative did not (DIVERGED_ITS after 5 iterations)", "-linear_solver direct", "-fieldsplit_u_ksp_type gmres")),
             ("decay", ("IDA failed", "Krylov solves of -linear_solver iterative did not converge (the last: DIVERGED_ITS after 5 iterations)", "-linear_solver direct")))
    for scene, want in cases:
        d = os.path.join(w, "krylov_failure_" + scene)
        # without the switch to an inner velocity solve (its retry would add its own 5)
        cmd = [ARGS.slump, "-scene", scene, "-linear_solver", "iterative", "-ksp_max_it", "5", "-linear_escalate_its", "0", "-output_fields", "0", "-output_dir", d]
        p = subprocess.run(cmd, capture_output=True, text=True)
        lines = [l for l in p.stderr.splitlines() if l.strip()]
        print("Krylov failure, %s: exit %d: %s" % (scene, p.returncode, lines[0] if lines else "(no message)"))
        if p.returncode <= 0 or p.returncode > 128:
            fail("Krylov failure, %s: expected an error exit, got %d" % (scene, p.returncode))
        if len(lines) != 1 or "PETSC ERROR" in p.stderr or not all(x in lines[0] for x in want):
            fail("Krylov failure, %s: expected one sentence containing %s, got:\n%s" % (scene, want, p.stderr))


def test_linear_direct_workspace():
    """MUMPS's LU under a memory cap (an address-space limit of 700 MB, set
    for the run alone): Bingham Poiseuille 32 x 128 (36 897 unknowns), whose
    workspace with our default relaxation (+1000 %, -mat_mumps_icntl_14)
    is estimated at 591 MB. (1) With the default the first allocation fails
    (INFOG(1) = -13), one line says the factorisation is done again with
    +100 %, and the run gives the uncapped run's results (equal to 1e-12
    relative: the relaxation sizes the workspace, not the pivots). This is
    what let LU run Poiseuille 168 x 672 (1.0e6 unknowns), where +1000 %
    asked for 31 GB for 2.7 GB of factors. (2) A relaxation the user gave
    is kept: the run ends with one sentence naming the failed allocation
    (its size in GB), -mat_mumps_icntl_14 and -linear_solver iterative.
    (3) Other MUMPS failures are named with their code and option:
    -mat_mumps_icntl_23 1 (1 MB allowed) in the steady Newton solve and in
    IDA's first step, -ic_mat_mumps_icntl_23 1 in the consistent
    initialisation."""
    import resource
    w = work("linear_direct_workspace")
    cap = 700 * 1024 * 1024

    def capped():
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    base = ["-scene", "poiseuille", "-mesh_nx", "32", "-mesh_ny", "128", "-linear_solver", "direct", "-output_fields", "0", "-quiet"]
    ref = os.path.join(w, "uncapped")
    subprocess.run([ARGS.slump] + base + ["-output_dir", ref], capture_output=True, text=True, check=True)
    d = os.path.join(w, "capped")
    p = subprocess.run([ARGS.slump] + base + ["-output_dir", d], capture_output=True, text=True, preexec_fn=capped)
    if p.returncode != 0:
        fail("capped LU: expected the run to succeed after the retry, got exit %d:\n%s" % (p.returncode, p.stderr[-2000:]))
    lines = [l for l in p.stdout.splitlines() if l.startswith("linear: MUMPS's LU")]
    print("capped LU: %s" % (lines or ["(no retry line)"])[0])
    if len(lines) != 1 or "could not allocate" not in lines[0] or "100 % instead of 1000 %" not in lines[0]:
        fail("capped LU: expected one line announcing the retry with 100 % instead of 1000 %, got %s" % lines)
    a, b = summary(ref), summary(d)
    for k in ("flow_rate", "err_u_l2", "kinetic_energy"):
        if k not in a:
            continue
        rel = abs(a[k] - b[k]) / max(abs(a[k]), 1e-300)
        print("  %-16s uncapped %.12e  capped %.12e  rel diff %.2e" % (k, a[k], b[k], rel))
        if not rel <= 1e-12:
            fail("capped LU %s: expected the uncapped result to 1e-12 relative, got %g" % (k, rel))
    # (2) the user's own relaxation is not changed
    d = os.path.join(w, "capped_user")
    p = subprocess.run([ARGS.slump] + base + ["-output_dir", d, "-mat_mumps_icntl_14", "1000"], capture_output=True, text=True, preexec_fn=capped)
    err = [l for l in p.stderr.splitlines() if l.strip()]
    print("capped LU, user's relaxation: exit %d: %s" % (p.returncode, err[0] if err else "(no message)"))
    m = re.search(r"could not allocate its workspace of ([0-9.]+) GB \(INFOG\(1\) = -13 with -mat_mumps_icntl_14 1000\); use -linear_solver iterative", err[0] if err else "")
    if p.returncode <= 0 or p.returncode > 128 or len(err) != 1 or "PETSC ERROR" in p.stderr or not m or "linear: MUMPS's LU" in p.stdout:
        fail("capped LU with -mat_mumps_icntl_14 1000: expected no retry and one sentence naming the failed allocation, got exit %d:\n%s" % (p.returncode, p.stderr))
    if not 0.3 <= float(m.group(1)) <= 0.7:
        fail("capped LU: expected the failed allocation to be the estimated ~0.55 GB workspace, got %s GB" % m.group(1))
    # (3) other codes
    cases = (("poiseuille", ["-mesh_nx", "8", "-mesh_ny", "32"], "", "The steady Newton solve did not converge at m = 10000 because"),
             ("couette_cessation", ["-mesh_nx", "2", "-mesh_ny", "16"], "", "IDA failed at t = 0.: IDA_CONV_FAIL because"),
             ("cavity_cessation", ["-mesh_nx", "8", "-mesh_ny", "8"], "ic_", "The consistent-initialisation solve failed because"))
    for scene, opts, prefix, head in cases:
        d = os.path.join(w, "icntl23_" + scene)
        opt = "-%smat_mumps_icntl_23" % prefix
        p = subprocess.run([ARGS.slump, "-scene", scene, "-output_fields", "0", "-quiet", "-output_dir", d, opt, "1"] + opts, capture_output=True, text=True)
        err = [l for l in p.stderr.splitlines() if l.strip()]
        want = head + " the LU factorisation (MUMPS) needs more memory than %s allows (INFOG(1) = -19)" % opt
        print("MUMPS -19, %s: exit %d: %s" % (scene, p.returncode, err[0] if err else "(no message)"))
        if p.returncode <= 0 or p.returncode > 128 or len(err) != 1 or "PETSC ERROR" in p.stderr or want not in err[0]:
            fail("MUMPS -19, %s: expected one sentence containing %r, got exit %d:\n%s" % (scene, want, p.returncode, p.stderr))


def test_linear_iterative_parallel():
    """-linear_solver iterative on 2 ranks against LU on 1: steady Bingham
    Poiseuille equal to 1e-8, duct_cessation's arrest time and the two-phase
    dam break within 10 rtol."""
    w = work("linear_iterative_parallel")
    linear_iterative_poiseuille(w, ranks_iter=2)
    linear_iterative_arrest(w, "duct_cessation", ["-output_fields", "0"], ranks_iter=2)
    linear_iterative_levelset(w, ranks_iter=2)


def test_reproducible_parallel():
    """Two 2-rank runs of the same command give the same bytes in their
    result files, with -linear_solver iterative (whose Krylov counts react to
    any change of partition or roundoff): duct_cessation to t = 0.01 (IDA,
    BoomerAMG; steps.csv and series.csv), the steady Bingham Poiseuille
    (KINSOL, Schur fieldsplit; series.csv and yield_map.csv) and the
    two-phase dam break 21 x 22 to t = 0.01 (level set, block Gauss-Seidel;
    steps.csv, series.csv, interface.csv). Until DMSetFromOptions was told
    not to redistribute, PETSc's default partitioner replaced the METIS
    partition with one that changed from run to run, and so did the Krylov
    counts, the steps and the results (the dam break's kinetic energy at
    t = 0.05 moved within 4e-4 ... 1.5e-3 of LU's); and until the consistent
    initialisation followed -linear_solver iterative, its LU by MUMPS changed
    the dam break's roundoff (t in steps.csv, last digit) between runs.
    LU by MUMPS on 2 ranks is not tested: its roundoff may change between
    runs on a loaded machine."""
    w = work("reproducible_parallel")
    cases = (("duct_cessation", ["-time_final", "0.01"], ("steps.csv", "series.csv")),
             ("poiseuille", ["-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2"], ("series.csv", "yield_map.csv")),
             ("dam_break", ["-mesh_nx", "21", "-mesh_ny", "22", "-time_final", "0.01"], ("steps.csv", "series.csv", "interface.csv")))
    for scene, opts, files in cases:
        out = []
        for k in (1, 2):
            d = os.path.join(w, "%s_%d" % (scene, k))
            run(scene, opts + ["-linear_solver", "iterative", "-output_fields", "0"], d, ranks=2)
            out.append({f: open(os.path.join(d, f), "rb").read() for f in files})
            s = summary(d)
            print("%s on %d ranks, run %d: %d steps, %d Newton, %d Krylov iterations" % (scene, s["ranks"], k, s["steps"], s["newton_its"], s["lin_its"]))
            if s["ranks"] != 2:
                fail("expected a 2-rank run, summary says %s" % s["ranks"])
        for f in files:
            if out[0][f] != out[1][f]:
                fail("%s: %s differs between two identical 2-rank runs" % (scene, f))
            print("  %s: identical (%d bytes)" % (f, len(out[0][f])))


STOKES_LAMBDA1_UNIT_SQUARE = 52.3446911  # first Stokes (clamped-plate buckling) eigenvalue of the unit square


def test_cavity_cessation():
    """Lid-driven cavity, lid stopped at t = 0 (enclosed, pressure pinned).
    (1) Newtonian, uniform and regularised lid (the latter needs the
    divergence-free projection of the initial velocity): at late times the energy decays as exp(-2 lambda_S t) with
    lambda_S = 52.3447 the first Stokes eigenvalue of the unit square, within
    0.5 % (measured over 0.10 <= t <= 0.12, when the second mode has faded). (2) Bingham Bn = 1, m = 1e4: the kinetic energy never increases and
    stays below the Newtonian envelope E0 exp(-2 lambda_S t) (x 1.01, since
    eta >= eta_p); every criterion fires; no bound is printed (beta is not
    known for this geometry) and the run says so."""
    w = work("cavity_cessation")
    for lid in ("uniform", "regularised"):
        d = os.path.join(w, "newtonian_" + lid)
        run("cavity_cessation", ["-rheology_type", "newtonian", "-cavity_lid", lid, "-time_final", "0.12", "-time_output_dt", "0.005",
                                 "-time_rtol", "1e-5", "-time_atol", "1e-8", "-output_fields", "0", "-arrest", "kinetic_energy:1e-30"], d)
        ser = series(d)
        rate = -math.log(ser[-1]["kinetic_energy"] / ser[-5]["kinetic_energy"]) / (ser[-1]["t"] - ser[-5]["t"]) / 2
        print("Newtonian cavity, %s lid: late decay rate %.4f (lambda_S = %.4f, rel %.1e)" % (lid, rate, STOKES_LAMBDA1_UNIT_SQUARE, rate / STOKES_LAMBDA1_UNIT_SQUARE - 1))
        if abs(rate - STOKES_LAMBDA1_UNIT_SQUARE) > 5e-3 * STOKES_LAMBDA1_UNIT_SQUARE:
            fail("late decay rate expected lambda_S within 0.5 %%, got %g" % rate)
        ke_never_increases(ser, "Newtonian cavity, %s lid" % lid)
    d = os.path.join(w, "bingham")
    spec = "mean_shear_rate:1e-3,max_shear_rate:1e-3,kinetic_energy:1e-6:relative,yielded_fraction:1e-3"
    p = run("cavity_cessation", ["-viscous_eigenvalue", "-arrest", spec, "-time_output_dt", "0.002", "-output_fields", "0"], d)
    if "no stopping-time bound printed" not in p.stdout:
        fail("expected the run to say that no bound is printed")
    s = summary(d)
    ser = series(d)
    ke_never_increases(ser, "Bingham cavity")
    for r in ser:
        env = ser[0]["kinetic_energy"] * math.exp(-2 * STOKES_LAMBDA1_UNIT_SQUARE * r["t"])
        if r["kinetic_energy"] > 1.01 * env + 1e-30:
            fail("energy above the Newtonian envelope at t = %g: %g > %g" % (r["t"], r["kinetic_energy"], env))
    for n in ("mean_shear_rate", "max_shear_rate", "kinetic_energy_relative", "yielded_fraction"):
        print("  %-24s arrest at t = %.6f" % (n, s["t_arrest_" + n]))
        if not 0 < s["t_arrest_" + n] < s["t_final"]:
            fail("%s did not fire" % n)


def last_decade_hmin(outdir, t_arrest):
    """Smallest step among the accepted steps up to the arrest time whose
    kinetic energy is within a factor 10 of its value at arrest (the last
    decade of kinetic-energy decay), and how many steps that decade took."""
    st = [r for r in steps(outdir) if r["t"] <= t_arrest]
    ke_a = st[-1]["kinetic_energy"]
    win = [r for r in st if r["kinetic_energy"] <= 10 * ke_a]
    return min(r["h"] for r in win), len(win)


def test_stability_step_floor():
    """Near arrest the step size does not collapse with the line-search stage
    solver nor with the default stress-velocity Newton: Couette cessation,
    Bn = 1, IDA rtol 1e-3, atol 1e-5, 16 cells across; the smallest h in the
    last decade of kinetic-energy decay before the mean-shear-rate arrest is
    at least 1e-3 x the arrest time at m = 1e3 and at m = 1e6, and the
    m = 1e6 floor is at least a tenth of the m = 1e3 one (no 1/m scaling).
    IDA's primal modified Newton is run too and its floor printed: it falls
    like 1/m (docs/arrest.md)."""
    w = work("step_floor")
    base = ["-mesh_ny", "16", "-time_rtol", "1e-3", "-time_atol", "1e-5", "-time_final", "0.12", "-output_fields", "0"]
    solvers = {"linesearch": ["-ida_nonlinear_solver", "linesearch", "-newton_linearisation", "primal"],
               "primal": ["-newton_linearisation", "primal"],
               "stress_velocity": []}
    floors = {}
    for nls, extra in solvers.items():
        for m in (1e3, 1e6):
            d = os.path.join(w, "%s_m%g" % (nls, m))
            run("couette_cessation", base + ["-rheology_papanastasiou_m", "%g" % m] + extra, d)
            s = summary(d)
            h, n = last_decade_hmin(d, s["t_arrest"])
            floors[nls, m] = h
            print("%-16s m %-6g arrest %.6f  steps %5d  last KE decade: %d steps, smallest h %.3e (%.1e x t_arrest)" % (nls, m, s["t_arrest"], s["steps"], n, h, h / s["t_arrest"]))
            if nls != "primal" and not h >= 1e-3 * s["t_arrest"]:
                fail("%s, m = %g: smallest h %g below the floor 1e-3 x t_arrest = %g" % (nls, m, h, 1e-3 * s["t_arrest"]))
    for nls in ("linesearch", "stress_velocity"):
        if not floors[nls, 1e6] >= 0.1 * floors[nls, 1e3]:
            fail("%s floor fell from %g (m = 1e3) to %g (m = 1e6)" % (nls, floors[nls, 1e3], floors[nls, 1e6]))


def test_stiff_defaults():
    """Every cessation scene in its default configuration (IDA, default
    tolerances, the stress-velocity Newton) reaches arrest at Papanastasiou
    m = 1e6, and Couette also at m = 1e7 (before it, Couette failed with
    IDA_CONV_FAIL at t = 0.0586 and the duct's step collapsed to 1e-8).
    Each run: arrest found; nonlinear convergence failures on fewer than 5 %
    of the steps (measured: none); at most 4 Newton iterations per step
    (measured 1.05-1.12); where the scene has the exact model's arrest time
    (Couette, Poiseuille), the arrest within 1 % of it (measured 4.2e-4,
    5.1e-4 and 2.9e-4). About a minute on one core."""
    w = work("stiff_defaults")
    runs = [("couette_cessation", "1e6"), ("couette_cessation", "1e7"), ("poiseuille_cessation", "1e6"), ("duct_cessation", "1e6"), ("cavity_cessation", "1e6")]
    for scene, m in runs:
        d = os.path.join(w, "%s_m%s" % (scene, m))
        run(scene, ["-rheology_papanastasiou_m", m, "-arrest_stop", "first", "-output_fields", "0"], d)
        s = summary(d)
        per = s["newton_its"] / max(s["steps"], 1)
        exact = s.get("t_arrest_exact", -1)
        err = abs(s["t_arrest"] - exact) / exact if exact and exact > 0 else float("nan")
        print("%-22s m %-4s arrest %.6f (exact %s, error %.1e)  %5d steps  %.2f Newton/step  %d convergence failures  %d error-test failures  %.1f s"
              % (scene, m, s["t_arrest"], "%.6f" % exact if exact and exact > 0 else "-", err, s["steps"], per, s["conv_fails"], s["err_test_fails"], s["wall_time"]))
        if not s["t_arrest"] > 0:
            fail("%s at m = %s: no arrest" % (scene, m))
        if not s["conv_fails"] < 0.05 * s["steps"]:
            fail("%s at m = %s: %d convergence failures in %d steps (expected < 5 %%)" % (scene, m, s["conv_fails"], s["steps"]))
        if not per <= 4:
            fail("%s at m = %s: %.2f Newton iterations per step (expected <= 4)" % (scene, m, per))
        if exact and exact > 0 and not err <= 1e-2:
            fail("%s at m = %s: arrest %.6f differs from the exact %.6f by %.1e (expected <= 1e-2)" % (scene, m, s["t_arrest"], exact, err))


def test_stability_quasistatic_ic_stiff():
    """The quasi-static initial solve at high m: bingham_dam_break -re 0
    (Bn = 0.1, 40 x 15 cells) needs a Papanastasiou-Stokes solve from rest
    before the first step. IDACalcIC fails there at m = 1e5
    (IDA_LINESEARCH_FAIL, also from the m = 1e4 state), so slump reaches it
    by continuation in m. Checks: (1) at m = 1e3 and 1e4 the direct solve
    works (no continuation), at m = 1e5 continuation is used and succeeds;
    (2) the initial state converges in m: for the kinetic energy, the mean
    shear rate and the dissipation, the change from m = 1e4 to 1e5 is at most
    a fifth of the change from 1e3 to 1e4 (measured: 17-18 times smaller),
    and (3) the potential energy is the same for all three (the level set is
    not touched by the solve) to 1e-12 relative."""
    w = work("quasistatic_ic_stiff")
    first = {}
    for m in ("1e3", "1e4", "1e5"):
        d = os.path.join(w, "m" + m)
        p = run("bingham_dam_break", ["-re", "0", "-mesh_nx", "40", "-mesh_ny", "15", "-output_fields", "0", "-rheology_papanastasiou_m", m, "-time_final", "0.001"], d)
        cont = "reached by continuation" in p.stdout
        first[m] = series(d)[0]
        r = first[m]
        print("m = %s: continuation %-3s  t = 0: KE %.10e  mean|gdot| %.10e  dissipation %.10e  yielded %.4f" % (m, "yes" if cont else "no", r["kinetic_energy"], r["mean_shear_rate"], r["dissipation"], r["yielded_fraction"]))
        if cont != (m == "1e5"):
            fail("m = %s: continuation %s, expected %s" % (m, "used" if cont else "not used", "used" if m == "1e5" else "not used"))
    for q in ("kinetic_energy", "mean_shear_rate", "dissipation"):
        d1 = abs(first["1e4"][q] - first["1e3"][q])
        d2 = abs(first["1e5"][q] - first["1e4"][q])
        print("%s: |1e4 - 1e3| = %.3e, |1e5 - 1e4| = %.3e (ratio %.1f)" % (q, d1, d2, d1 / max(d2, 1e-300)))
        if not d1 > 0:
            fail("%s is the same at m = 1e3 and 1e4: -rheology_papanastasiou_m had no effect" % q)
        if not d2 <= d1 / 5:
            fail("%s does not converge in m: |1e5 - 1e4| = %.3e > |1e4 - 1e3| / 5 = %.3e" % (q, d2, d1 / 5))
    for m in ("1e4", "1e5"):
        if abs(first[m]["potential_energy"] - first["1e3"]["potential_energy"]) > 1e-12 * abs(first["1e3"]["potential_energy"]):
            fail("the potential energy at t = 0 changed with m (%s): the level set moved" % m)


def test_stability_steady_retry():
    """A steady Newton solve that fails is retried from softer regularisation
    values (timeint/kinsol.c, SteadySolve). Steady Bingham Poiseuille (16 x 16
    cells) from rest: (1) Papanastasiou m = 1e6 fails there (50 Newton steps,
    max|F| 2.6e-3), is retried from m = 1e4 and converges, with one
    convergence failure counted, to the solution of the explicit continuation
    from m = 1e2 (flow rate, kinetic energy, mean shear rate, velocity error:
    equal to 1e-8 relative); (2) the same for a model stiffer as its parameter
    falls (bingham_simple, eps = 1e-6: retried from 1e-4); (3) a continuation
    step that fails (1e2 to 1e6 with -steady_continuation_factor 1e4) is
    retried from the last value solved with the square root of the step
    (1e2 to 1e4); (4) with -steady_continuation_retry 0 the run stops with
    one error sentence naming the remedy, a non-zero exit and status
    not_converged; (5) a target out of reach (Bercovier eps = 1e-8) ends in
    one sentence naming the stiffest value solved, between the target and
    the first retry's 1e-6."""
    w = work("steady_retry")
    keys = ("flow_rate", "kinetic_energy", "mean_shear_rate", "err_u_l2")
    m6 = ["-rheology_papanastasiou_m", "1e6"]
    simple = ["-rheology_type", "bingham_simple", "-rheology_simple_eps", "1e-6"]
    # (name, options, the explicit continuation's options, expected output)
    cases = (("m1e6", m6, m6 + ["-steady_continuation_start", "1e2"], ["retrying from m = 10000"]),
             ("simple_eps1e-6", simple, simple + ["-steady_continuation_start", "1e-2"], ["retrying from eps = 0.0001"]),
             ("factor1e4", m6 + ["-steady_continuation_start", "1e2", "-steady_continuation_factor", "1e4"], m6 + ["-steady_continuation_start", "1e2"], ["steady: m = 100 ", "retrying from m = 10000"]))
    for name, opts, ref_opts, want in cases:
        d, dr = os.path.join(w, name), os.path.join(w, name + "_ref")
        base = ["-output_fields", "0"]
        p = subprocess.run([ARGS.slump, "-scene", "poiseuille", "-output_dir", d] + base + opts, capture_output=True, text=True)
        if p.returncode != 0:
            fail("%s: the retried solve failed (%d):\n%s%s" % (name, p.returncode, p.stdout[-2000:], p.stderr[-2000:]))
        run("poiseuille", base + ref_opts, dr)
        s, r = summary(d), summary(dr)
        print("%-15s retries %d, Newton %d (reference %d), conv_fails %d; %s" % (name, p.stdout.count("retrying from"), s["newton_its"], r["newton_its"], s["conv_fails"],
              ", ".join("%s %.10e (ref %.10e)" % (k, s[k], r[k]) for k in keys)))
        for t in want:
            if t not in p.stdout:
                fail("%s: expected %r in the output:\n%s" % (name, t, p.stdout))
        if p.stdout.count("retrying from") != 1 or s["conv_fails"] != 1 or "reached after 1 retry from softer values" not in p.stdout:
            fail("%s: expected exactly one retry and one convergence failure, got %d and %d" % (name, p.stdout.count("retrying from"), s["conv_fails"]))
        for k in keys:
            if abs(s[k] - r[k]) > 1e-8 * abs(r[k]):
                fail("%s: %s %.12e differs from the explicit continuation's %.12e by more than 1e-8 relative" % (name, k, s[k], r[k]))
    for name, opts, want in (("no_retry", ["-rheology_papanastasiou_m", "1e6", "-steady_continuation_retry", "0"], r"The steady Newton solve did not converge at m = 1e\+06; try -steady_continuation_start"),
                             ("out_of_reach", ["-rheology_type", "bercovier", "-rheology_bercovier_eps", "1e-8"], r"The steady Newton solve did not reach eps = 1e-08: after \d+ retries from softer values the stiffest value solved is eps = ([0-9.e+-]+); try -newton_max_it")):
        d = os.path.join(w, name)
        p = subprocess.run([ARGS.slump, "-scene", "poiseuille", "-output_fields", "0", "-quiet", "-output_dir", d] + opts, capture_output=True, text=True)
        err = [l for l in p.stderr.splitlines() if l.strip()]
        m = re.search(want, err[0]) if len(err) == 1 else None
        print("%s: exit %d: %s" % (name, p.returncode, err[0] if err else "(no message)"))
        if p.returncode <= 0 or p.returncode > 128 or "PETSC ERROR" in p.stderr or not m:
            fail("%s: expected one sentence matching %r and a non-zero exit, got exit %d:\n%s" % (name, want, p.returncode, p.stderr))
        if summary(d)["status"] != "not_converged":
            fail("%s: expected status not_converged in summary.csv, got %r" % (name, summary(d)["status"]))
        if name == "out_of_reach" and not 1e-8 < float(m.group(1)) <= 1e-6:
            fail("out_of_reach: the stiffest value solved, %s, is not within (1e-8, 1e-6]" % m.group(1))


# Cessation scenes for the stability sweep: Bn as each scene defines it
# (Poiseuille and duct start from the Newtonian flow so that any Bn moves).
SWEEP_SCENES = [
    ("couette_cessation", ["-mesh_ny", "16", "-time_final", "0.6"]),
    ("poiseuille_cessation", ["-initial_flow", "newtonian", "-mesh_ny", "16", "-time_final", "1.2"]),
    ("duct_cessation", ["-initial_flow", "newtonian", "-mesh_nx", "8", "-mesh_ny", "8", "-time_final", "0.6"]),
    ("cavity_cessation", ["-mesh_nx", "8", "-mesh_ny", "8", "-time_final", "0.6"]),
]


def cessation_sweep(name, ms, bns):
    """Every cessation scene, Papanastasiou m x Bn, IDA (rtol 1e-3, atol 1e-5)
    with its default stage solver, the stress-velocity Newton (until issue 31
    the sweep needed the line-search fallback): each run reaches t_end (no
    unrecoverable failure), the mean-shear-rate arrest fires before t_end,
    the kinetic energy never increases, and for m >= 1e4 the arrest lies
    below the energy bound where the scene has one."""
    w = work(name)
    print("%-20s %8s %6s %9s %9s %6s %6s %6s %7s" % ("scene", "m", "Bn", "t_arrest", "bound", "steps", "fails", "Newton", "wall s"))
    for scene, opts in SWEEP_SCENES:
        for m in ms:
            for bn in bns:
                d = os.path.join(w, "%s_m%g_bn%g" % (scene, m, bn))
                run(scene, opts + ["-rheology_papanastasiou_m", "%g" % m, "-bn", "%g" % bn, "-time_rtol", "1e-3", "-time_atol", "1e-5",
                                   "-arrest_stop", "none", "-time_output_dt", "0.01", "-output_fields", "0"], d)
                s = summary(d)
                tf = float(opts[opts.index("-time_final") + 1])
                bound = s.get("t_stop_bound", float("nan"))
                print("%-20s %8g %6g %9.6f %9.6f %6d %6d %6d %7.1f" % (scene, m, bn, s["t_arrest"], bound, s["steps"], s["conv_fails"] + s["err_test_fails"], s["newton_its"], s["wall_time"]))
                if abs(s["t_final"] - tf) > 1e-9 * tf:
                    fail("%s m %g Bn %g: stopped at t = %g before t_end = %g" % (scene, m, bn, s["t_final"], tf))
                if not 0 < s["t_arrest"] < tf:
                    fail("%s m %g Bn %g: no arrest before t_end" % (scene, m, bn))
                ke_never_increases(series(d), "%s m %g Bn %g" % (scene, m, bn))
                if m >= 1e4 and not math.isnan(bound) and not s["t_arrest"] < bound:
                    fail("%s m %g Bn %g: arrest %g above the bound %g" % (scene, m, bn, s["t_arrest"], bound))


def test_stability_cessation_sweep():
    cessation_sweep("cessation_sweep", (1e4, 1e6), (0.1, 100))


def test_stability_cessation_sweep_full():
    cessation_sweep("cessation_sweep_full", (1e2, 1e3, 1e4, 1e5, 1e6), (0.1, 1, 10, 100))


def write_gmsh_square(path, n):
    """A Gmsh 2.2 ASCII file of the unit square, n x n squares cut like
    SlumpMeshCreateRectangle, with physical lines bottom/right/top/left."""
    nodes = [(i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
    vid = lambda i, j: j * (n + 1) + i + 1
    elems = []
    for k in range(n):
        elems.append((1, 1, [vid(k, 0), vid(k + 1, 0)]))          # bottom
        elems.append((1, 2, [vid(n, k), vid(n, k + 1)]))          # right
        elems.append((1, 3, [vid(k + 1, n), vid(k, n)]))          # top
        elems.append((1, 4, [vid(0, k + 1), vid(0, k)]))          # left
    for j in range(n):
        for i in range(n):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            elems.append((2, 5, [a, b, c]))
            elems.append((2, 5, [a, c, d]))
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n")
        f.write('1 1 "bottom"\n1 2 "right"\n1 3 "top"\n1 4 "left"\n2 5 "domain"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % len(nodes))
        for k, (x, y) in enumerate(nodes):
            f.write("%d %.17g %.17g 0\n" % (k + 1, x, y))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
        for k, (typ, tag, vs) in enumerate(elems):
            f.write("%d %d 2 %d %d %s\n" % (k + 1, typ, tag, tag, " ".join(map(str, vs))))
        f.write("$EndElements\n")


def test_gmsh():
    """A Gmsh file of the same triangulation as the built-in rectangle, with
    physical names bottom/right/top/left as boundary labels, gives the same
    mms_stokes errors to 1e-8 relative, on 1 and 2 ranks."""
    w = work("gmsh")
    msh = os.path.join(w, "square.msh")
    write_gmsh_square(msh, 8)
    run("mms_stokes", ["-mesh_nx", "8", "-mesh_ny", "8", "-output_fields", "0"], os.path.join(w, "rect"))
    run("mms_stokes", ["-mesh_file", msh, "-output_fields", "0"], os.path.join(w, "msh"))
    run("mms_stokes", ["-mesh_file", msh, "-output_fields", "0"], os.path.join(w, "msh2"), ranks=2)
    a, b, c = summary(os.path.join(w, "rect")), summary(os.path.join(w, "msh")), summary(os.path.join(w, "msh2"))
    for k in ("err_u_l2", "err_p_l2"):
        print("%s: rectangle %.10e, gmsh %.10e, gmsh on 2 ranks %.10e" % (k, a[k], b[k], c[k]))
        for other in (b, c):
            if abs(a[k] - other[k]) > 1e-8 * a[k]:
                fail("%s expected %g, got %g" % (k, a[k], other[k]))


INPUT_CASES = [
    # (name, args, word that the one-sentence message must contain)
    ("unknown_scene", ["-scene", "no_such_scene"], "-scene"),
    ("iterative_unknown", ["-scene", "poiseuille", "-linear_solver", "lu"], "-linear_solver"),
    ("schur_mass_petsc_assembly", ["-scene", "poiseuille", "-linear_solver", "iterative", "-assembly", "petsc"], "-stokes_schur_pre"),
    ("unknown_rheology", ["-scene", "poiseuille", "-rheology_type", "no_such_model"], "-rheology_type"),
    ("unknown_reinit", ["-scene", "levelset_rotation", "-reinit", "no_such_method"], "-reinit"),
    ("levelset_degree", ["-scene", "levelset_rotation", "-levelset_degree", "3"], "-levelset_degree"),
    ("convective_petsc_assembly", ["-scene", "levelset_rotation", "-reinit", "convective", "-assembly", "petsc"], "-assembly"),
    ("negative_viscosity", ["-scene", "poiseuille", "-rheology_viscosity", "-1"], "-rheology_viscosity"),
    ("missing_mesh", ["-scene", "mms_stokes", "-mesh_file", "/nonexistent/mesh.msh"], "-mesh_file"),
    ("unreadable_options", ["-scene", "mms_stokes", "-options_file", "/nonexistent/opts.txt"], "-options_file"),
    ("bad_rtol", ["-scene", "decay", "-time_rtol", "2"], "-time_rtol"),
    ("bad_restart_step", ["-scene", "decay", "-ida_restart_step", "0"], "-ida_restart_step"),
    ("bad_supg_speed", ["-scene", "dam_break", "-levelset_supg_speed", "-1"], "-levelset_supg_speed"),
    ("bad_re", ["-scene", "bingham_dam_break", "-re", "-1"], "-re"),
    ("bad_convection_form", ["-scene", "dam_break", "-convection_form", "conservative"], "-convection_form"),
    ("bad_plasticity", ["-scene", "chupin_column", "-plasticity", "mohr"], "-plasticity"),
    ("bad_arrest", ["-scene", "couette_cessation", "-arrest", "speed:1e-3"], "-arrest"),
    ("bad_creep", ["-scene", "couette_cessation", "-arrest", "kinetic_energy:1:creep"], "-arrest"),
    # mistakes that ran silently with defaults (issue 32)
    ("misspelt_option", ["-scene", "couette_cessation", "-time_finall", "1"], "-time_final"),
    ("misspelt_rheology", ["-scene", "poiseuille", "-rheology_viscositty", "2"], "-rheology_viscosity"),
    ("positional_scene", ["couette_cessation"], "-scene couette_cessation"),
    ("missing_value", ["-scene", "couette_cessation", "-bn"], "-bn"),
    ("missing_value_mid", ["-scene", "couette_cessation", "-bn", "-quiet"], "-bn"),
    ("option_not_read", ["-scene", "couette_cessation", "-cavity_lid", "regularised"], "-cavity_lid"),
    ("snes_option", ["-scene", "couette_cessation", "-snes_rtol", "1e-3"], "-snes_rtol"),
    ("ts_option", ["-scene", "couette_cessation", "-ts_type", "bdf"], "-ts_type"),
    ("sweep_unread", ["-scene", "couette_cessation", "-sweep", "cavity_lid:regularised,smooth"], "cavity_lid"),
    ("sweep_unknown", ["-scene", "couette_cessation", "-sweep", "bnn:1,2"], "-bn"),
    ("sweep2_alone", ["-scene", "couette_cessation", "-sweep2", "bn:1,2"], "-sweep2"),
    ("sweep_empty_value", ["-scene", "couette_cessation", "-sweep", "bn:1,,2"], "-sweep"),
    ("sweep_no_values", ["-scene", "couette_cessation", "-sweep", "bn:"], "-sweep"),
    # bad values that reached the solver
    ("time_final_inf", ["-scene", "couette_cessation", "-time_final", "inf"], "-time_final"),
    ("bn_inf", ["-scene", "couette_cessation", "-bn", "inf"], "-bn"),
    ("bn_nan", ["-scene", "couette_cessation", "-bn", "nan"], "-bn"),
    ("bn_huge", ["-scene", "couette_cessation", "-bn", "1e300"], "-bn"),
    # the exact method: models, effects and options it does not take
    ("exact_granular", ["-scene", "bagnold", "-method", "exact"], "-method exact"),
    ("inertia_steps_zero", ["-scene", "cavity", "-re", "100", "-steady_inertia_steps", "0"], "-steady_inertia_steps"),
    ("inertia_steps_stokes", ["-scene", "poiseuille", "-steady_inertia_steps", "3"], "-steady_inertia_steps"),
    ("exact_free_surface", ["-scene", "dam_break", "-method", "exact", "-time_dt", "1e-3"], "-method exact"),
    ("exact_no_dt", ["-scene", "poiseuille_cessation", "-method", "exact"], "-time_dt"),
    ("exact_vs_integrator", ["-scene", "poiseuille_cessation", "-method", "exact", "-time_integrator", "ida", "-time_dt", "1e-3"], "-method exact"),
    ("exact_checkpoint", ["-scene", "poiseuille_cessation", "-method", "exact", "-time_dt", "1e-3", "-checkpoint_every", "5"], "-method exact"),
    ("exact_tol", ["-scene", "poiseuille", "-method", "exact", "-alg2_tol", "2"], "-alg2_tol"),
    ("axi_scene", ["-scene", "cavity", "-geometry", "axisymmetric"], "-geometry"),
    ("axi_value", ["-scene", "poiseuille", "-geometry", "axi"], "-geometry"),
    ("axi_assembly", ["-scene", "poiseuille", "-geometry", "axisymmetric", "-assembly", "petsc"], "-assembly"),
    ("cylinder_cutoff", ["-scene", "cylinder", "-cylinder_cutoff", "2.5"], "-cylinder_cutoff"),
    ("cylinder_domain", ["-scene", "cylinder", "-cylinder_domain", "free"], "-cylinder_domain"),
    ("granular_cylinder_pressure", ["-scene", "granular_cylinder", "-granular_cylinder_pressure", "-1"], "-granular_cylinder_pressure"),
    ("granular_cylinder_load", ["-scene", "granular_cylinder", "-granular_cylinder_load", "0"], "-granular_cylinder_load"),
    ("granular_cylinder_load_step", ["-scene", "granular_cylinder", "-granular_cylinder_load_step", "0"], "-granular_cylinder_load_step"),
    ("granular_cylinder_lambda", ["-scene", "granular_cylinder", "-granular_cylinder_load_lambda_r", "0"], "-granular_cylinder_load_lambda_r"),
    ("cavity_grid", ["-scene", "cavity", "-cavity_grid", "5"], "-cavity_grid"),
    ("linear_escalate_its", ["-scene", "poiseuille", "-linear_solver", "iterative", "-linear_escalate_its", "-3"], "-linear_escalate_its"),
    ("velocity_deflation", ["-scene", "poiseuille", "-linear_solver", "iterative", "-stokes_velocity_deflation", "2"], "-stokes_velocity_deflation"),
    ("logical_value", ["-scene", "cavity", "-linear_solver", "iterative", "-stokes_schur_pin_correction", "maybe"], "-stokes_schur_pin_correction"),
    ("logical_value_output", ["-scene", "decay", "-output_overwrite", "sometimes"], "-output_overwrite"),
]


def test_input():
    """Bad input: non-zero exit, exactly one line on stderr naming the option,
    no crash (no PETSc traceback), and no output directory left behind."""
    check_refused(work("input"), INPUT_CASES)


def check_refused(w, cases):
    for name, args, word in cases:
        out = os.path.join(w, name)
        cmd = [ARGS.slump] + args + ["-output_dir", out]
        p = subprocess.run(cmd, capture_output=True, text=True)
        lines = [l for l in p.stderr.splitlines() if l.strip()]
        print("%-20s exit %d: %s" % (name, p.returncode, lines[0] if lines else "(no message)"))
        if p.returncode == 0:
            fail("%s: expected a non-zero exit" % name)
        if p.returncode < 0 or p.returncode > 128:
            fail("%s: crashed (exit %d)" % (name, p.returncode))
        if len(lines) != 1 or word not in lines[0] or "PETSC ERROR" in p.stderr:
            fail("%s: expected one sentence naming %s on stderr, got:\n%s" % (name, word, p.stderr))
        if os.path.exists(out):
            fail("%s: output directory %s was created" % (name, out))


def input_fixtures(w):
    """Bad files for the input tests: garbage bytes, a text file that is not
    options, an empty and a malformed mesh file, and a directory."""
    os.makedirs(w, exist_ok=True)
    paths = {k: os.path.join(w, k) for k in ("garbage.opts", "text.opts", "empty.msh", "bad.msh", "a_directory")}
    with open(paths["garbage.opts"], "wb") as f:
        f.write(bytes(range(256)) * 4)
    with open(paths["text.opts"], "w") as f:
        f.write("# a comment\n-time_final 0.1\nthis line is not an option\n")
    open(paths["empty.msh"], "w").close()
    with open(paths["bad.msh"], "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\nthis is not a mesh\n")
    os.makedirs(paths["a_directory"], exist_ok=True)
    return paths


INPUT_FILE_CASES = [
    # (name, args with {file} placeholders, word the sentence must contain)
    ("garbage_options_file", ["-scene", "couette_cessation", "-options_file", "{garbage.opts}"], "-options_file"),
    ("text_options_file", ["-scene", "couette_cessation", "-options_file", "{text.opts}"], "-options_file"),
    ("directory_options_file", ["-scene", "couette_cessation", "-options_file", "{a_directory}"], "-options_file"),
    ("empty_mesh_file", ["-scene", "mms_stokes", "-mesh_file", "{empty.msh}"], "-mesh_file"),
    ("malformed_mesh_file", ["-scene", "mms_stokes", "-mesh_file", "{bad.msh}"], "-mesh_file"),
    ("directory_mesh_file", ["-scene", "mms_stokes", "-mesh_file", "{a_directory}"], "-mesh_file"),
]


def test_input_files():
    """Bad files (options, meshes): as test_input, one sentence and nothing written."""
    w = work("input_files")
    paths = input_fixtures(os.path.join(w, "fixtures"))
    cases = [(n, [paths[a[1:-1]] if a.startswith("{") else a for a in args], word) for n, args, word in INPUT_FILE_CASES]
    check_refused(w, cases)


def lines_whole(path, ncols):
    """Every line of a CSV file has the header's number of fields."""
    with open(path) as f:
        rows = list(csv.reader(f))
    bad = [r for r in rows if len(r) != ncols]
    if bad:
        fail("%s: %d of %d lines are not whole (%d fields expected), e.g. %s" % (path, len(bad), len(rows), ncols, bad[0]))
    return rows


def test_output_full_disk():
    """A write that fails (the file is /dev/full: no space left) ends the run
    with exit 1 and one sentence naming the file, for every output file,
    without a crash; the run's other outputs are closed (no lock left)."""
    w = work("full_disk")
    for name, scene, extra in (("series.csv", "couette_cessation", []), ("steps.csv", "couette_cessation", []),
                               ("summary.csv.part", "couette_cessation", []), ("fields.h5", "couette_cessation", []),
                               ("fields.xmf.part", "couette_cessation", []),
                               ("interface.csv", "dam_break", ["-mesh_nx", "6", "-mesh_ny", "6"])):
        out = os.path.join(w, name)
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        os.symlink("/dev/full", os.path.join(out, name))
        p = subprocess.run([ARGS.slump, "-scene", scene, "-output_dir", out, "-quiet", "-time_final", "0.02"] + extra, capture_output=True, text=True)
        ours = [l for l in p.stderr.splitlines() if l.startswith("slump: error")]
        print("%-18s exit %d: %s" % (name, p.returncode, ours[0] if ours else "(no message)"))
        if p.returncode != 1:
            fail("%s on a full disk: exit %d, expected 1\n%s" % (name, p.returncode, p.stderr[-2000:]))
        # Open MPI's I/O layer prints its own lines for fields.h5 (ompio); ours is one
        if len(ours) != 1 or name.replace(".part", "") not in ours[0] or "PETSC ERROR" in p.stderr:
            fail("%s: expected one sentence naming the file, got:\n%s" % (name, p.stderr[-2000:]))
        if os.path.exists(os.path.join(out, ".slump.lock")):
            fail("%s: the lock file was left behind" % name)


def test_output_interrupt():
    """SIGTERM in the middle of a run: the run ends after its current step
    with exit 128 + 15, steps.csv and series.csv hold only whole rows up to
    that step, summary.csv says status interrupted with the time, and no
    lock is left. SIGINT the same (exit 130). Then a run that fails (IDA
    stopped by -time_max_steps) writes its summary with status
    not_converged and the reason."""
    import signal
    import time
    w = work("interrupt")
    for sig, code in ((signal.SIGTERM, 143), (signal.SIGINT, 130)):
        out = os.path.join(w, "sig%d" % sig)
        shutil.rmtree(out, ignore_errors=True)
        p = subprocess.Popen([ARGS.slump, "-scene", "couette_cessation", "-output_dir", out, "-quiet", "-rheology_papanastasiou_m", "1e5", "-time_output_dt", "1e-4"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        steps_csv = os.path.join(out, "steps.csv")
        t0 = time.time()
        while time.time() - t0 < 60:
            if os.path.exists(steps_csv) and sum(1 for _ in open(steps_csv)) > 200:
                break
            time.sleep(0.05)
        p.send_signal(sig)
        _, err = p.communicate(timeout=120)
        print("signal %d: exit %d, %s" % (sig, p.returncode, err.strip()))
        if p.returncode != code:
            fail("signal %d: exit %d, expected %d" % (sig, p.returncode, code))
        s = summary(out)
        steps_rows = lines_whole(steps_csv, 8)
        series_rows = lines_whole(os.path.join(out, "series.csv"), 12)
        last = float(steps_rows[-1][0])
        print("  summary status %s, reason %s, t_final %.6g, %d steps (steps.csv %d rows, last t %.6g), series.csv %d rows"
              % (s["status"], s["reason"], s["t_final"], s["steps"], len(steps_rows) - 1, last, len(series_rows) - 1))
        if s["status"] != "interrupted" or "SIG" not in s["reason"]:
            fail("summary status %r, reason %r; expected interrupted by a signal" % (s["status"], s["reason"]))
        # every step the run took is a row of steps.csv, the last one at t_final
        # (summary.csv has 11 significant digits)
        if len(steps_rows) - 1 != s["steps"] or abs(last - s["t_final"]) > 1e-10 * s["t_final"]:
            fail("steps.csv has %d rows to t = %.12g; the summary %d steps to t = %.12g" % (len(steps_rows) - 1, last, s["steps"], s["t_final"]))
        # every output time before the interruption is a row of series.csv
        expect = int(s["t_final"] / 1e-4 + 1e-9) + 1
        if len(series_rows) - 1 != expect:
            fail("series.csv has %d rows; %d output times lie in [0, %.6g]" % (len(series_rows) - 1, expect, s["t_final"]))
        if os.path.exists(os.path.join(out, ".slump.lock")):
            fail("the lock file was left behind")
    out = os.path.join(w, "failed")
    p = run("couette_cessation", ["-time_max_steps", "10"], out, expect_ok=False)
    s = summary(out)
    print("failed run: exit %d, status %s, reason %s, %d steps" % (p.returncode, s["status"], s["reason"], s["steps"]))
    if p.returncode != 1 or s["status"] != "not_converged" or "-time_max_steps" not in s["reason"] or s["steps"] != 10:
        fail("a failed run should exit 1 and write status not_converged with the reason and its 10 steps")


def test_output_lock():
    """Two runs given one output directory: the second is refused (exit 1,
    one sentence naming the lock and -output_overwrite) while the first goes
    on and completes; its series.csv is the first run's alone. A lock left
    by a process that no longer exists is taken over."""
    import time
    w = work("lock")
    out = os.path.join(w, "shared")
    shutil.rmtree(out, ignore_errors=True)
    a = subprocess.Popen([ARGS.slump, "-scene", "couette_cessation", "-output_dir", out, "-quiet", "-time_final", "0.15"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while not os.path.exists(os.path.join(out, ".slump.lock")) and time.time() - t0 < 60:
        time.sleep(0.02)
    b = subprocess.run([ARGS.slump, "-scene", "couette_cessation", "-output_dir", out, "-quiet", "-bn", "2"], capture_output=True, text=True)
    a.communicate(timeout=300)
    lines = [l for l in b.stderr.splitlines() if l.strip()]
    print("second run: exit %d: %s" % (b.returncode, lines[0] if lines else ""))
    if b.returncode != 1 or len(lines) != 1 or "-output_overwrite" not in lines[0] or "in use" not in lines[0]:
        fail("the second run should be refused with one sentence:\n" + b.stderr)
    if a.returncode != 0:
        fail("the first run failed (%d)" % a.returncode)
    ser = series(out)
    times = [r["t"] for r in ser]
    if times != sorted(times) or len(times) != len(set(times)) or summary(out)["bn_option"] != 1.0:
        fail("series.csv is not the first run's alone")
    print("first run: exit 0, %d series rows, bn %g" % (len(ser), summary(out)["bn_option"]))
    with open(os.path.join(out, ".slump.lock"), "w") as f:
        f.write("999999999 %s\n" % os.uname()[1])
    p = run("couette_cessation", ["-time_final", "0.01"], out)
    if os.path.exists(os.path.join(out, ".slump.lock")):
        fail("the stale lock was not taken over and released")
    print("a stale lock (pid 999999999) is taken over")


def test_plot_arrest():
    """cases/plot_arrest.py (the command docs/arrest.md gives) on the outputs
    of the Couette and Poiseuille cessations (whose summaries hold the exact
    model's t_arrest_exact): exit 0 and a figure."""
    w = work("plot_arrest")
    for scene in ("couette_cessation", "poiseuille_cessation"):
        out = os.path.join(w, scene)
        run(scene, ["-output_fields", "0", "-arrest_stop", "first"], out)
        png = os.path.join(out, "arrest.png")
        if os.path.exists(png):
            os.remove(png)
        p = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "plot_arrest.py"), out], capture_output=True, text=True)
        print("%s: exit %d %s" % (scene, p.returncode, p.stdout.strip()[-200:]))
        if p.returncode != 0 or not os.path.exists(png) or os.path.getsize(png) < 1000:
            fail("plot_arrest.py on %s failed:\n%s" % (scene, p.stderr[-2000:]))


def h5_state(path):
    """The state vector of a checkpoint, as raw bytes (h5dump, hdf5-tools)."""
    out = path + ".state.bin"
    subprocess.run(["h5dump", "-d", "/state", "-b", "LE", "-o", out, path], check=True, capture_output=True)
    with open(out, "rb") as f:
        return f.read()


def test_restart():
    """Checkpoint/restart on Couette cessation (Bn 1, m 1e4).
    Fixed-step BDF2 (dt 2e-3, 53 steps to arrest): a run restarted from the
    checkpoint at step 40 reaches step 50 with the same state bit for bit
    (both runs' checkpoints at step 50 compared byte by byte), and the same
    arrest time, counters and final diagnostics (summary.csv strings) and
    series.csv rows after the restart. A run stopped by SIGTERM leaves a
    checkpoint where it stopped; restarted from it, it ends as the
    uninterrupted run (same strings). IDA (rtol 1e-3): restarted at step 100
    it restarts its BDF at order 1 (its history is not public), and the
    arrest time agrees within 10 rtol. Refused: a restart on another scene
    (another number of unknowns) and a missing file, one sentence each."""
    import signal
    import time
    w = work("restart")
    base = ["-output_fields", "0", "-arrest_stop", "first", "-time_integrator", "bdf2", "-time_dt", "2e-3"]
    dirs = {k: os.path.join(w, k) for k in ("a0", "a", "b", "sig", "sig_restart", "ida0", "ida_b", "wrong")}
    for d in dirs.values():
        shutil.rmtree(d, ignore_errors=True)
    run("couette_cessation", base + ["-checkpoint_every", "40"], dirs["a0"])
    run("couette_cessation", base + ["-checkpoint_every", "25"], dirs["a"])
    p = run("couette_cessation", base + ["-checkpoint_every", "5", "-restart", os.path.join(dirs["a0"], "checkpoint.h5")], dirs["b"])
    print(p.stdout.strip().splitlines()[0])
    sa, sb = h5_state(os.path.join(dirs["a"], "checkpoint.h5")), h5_state(os.path.join(dirs["b"], "checkpoint.h5"))
    print("BDF2: state at step 50: %d bytes, uninterrupted and restarted %s" % (len(sa), "identical" if sa == sb else "DIFFERENT"))
    if sa != sb or len(sa) < 1000:
        fail("the restarted BDF2 run's state at step 50 differs from the uninterrupted run's")
    keys = ("t_final", "t_arrest", "steps", "res_evals", "jac_evals", "newton_its", "lin_its", "kinetic_energy", "mean_shear_rate", "status")

    def same_run(d1, d2, what):
        r1, r2 = [next(csv.DictReader(open(os.path.join(d, "summary.csv")))) for d in (d1, d2)]
        diff = [k for k in keys if r1[k] != r2[k]]
        print("%s: t_arrest %s and %s, steps %s and %s, residual evaluations %s and %s" % (what, r1["t_arrest"], r2["t_arrest"], r1["steps"], r2["steps"], r1["res_evals"], r2["res_evals"]))
        if diff:
            fail("%s: summary columns differ: %s" % (what, ", ".join("%s %s / %s" % (k, r1[k], r2[k]) for k in diff)))
        rows1 = {r.split(",")[0]: r for r in open(os.path.join(d1, "series.csv")).read().splitlines()[1:]}
        rows2 = open(os.path.join(d2, "series.csv")).read().splitlines()[1:]
        bad = [r for r in rows2 if rows1.get(r.split(",")[0]) != r]
        if bad or not rows2:
            fail("%s: %d of %d series.csv rows after the restart differ from the uninterrupted run's, e.g. %s" % (what, len(bad), len(rows2), bad[:1]))
        print("  %d series rows after the restart identical" % len(rows2))

    same_run(dirs["a"], dirs["b"], "BDF2 restarted at step 40")
    # SIGTERM, then restart from the checkpoint it leaves (dt 5e-4: 210 steps)
    sig = base[:-1] + ["5e-4"]
    ref = os.path.join(w, "sig_ref")
    shutil.rmtree(ref, ignore_errors=True)
    run("couette_cessation", sig, ref)
    proc = subprocess.Popen([ARGS.slump, "-scene", "couette_cessation", "-output_dir", dirs["sig"], "-quiet", "-checkpoint_every", "100000"] + sig,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    steps_csv = os.path.join(dirs["sig"], "steps.csv")
    t0 = time.time()
    while time.time() - t0 < 60 and not (os.path.exists(steps_csv) and sum(1 for _ in open(steps_csv)) > 40):
        time.sleep(0.02)
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=120)
    s = summary(dirs["sig"])
    print("SIGTERM: exit %d at t = %.6g after %d steps; checkpoint %s" % (proc.returncode, s["t_final"], s["steps"], os.path.exists(os.path.join(dirs["sig"], "checkpoint.h5"))))
    if proc.returncode != 143 or s["status"] != "interrupted" or s["steps"] >= 200:
        fail("the run was not interrupted mid-way (exit %d, status %s, %d steps)" % (proc.returncode, s["status"], s["steps"]))
    run("couette_cessation", sig + ["-restart", os.path.join(dirs["sig"], "checkpoint.h5")], dirs["sig_restart"])
    same_run(ref, dirs["sig_restart"], "BDF2 interrupted by SIGTERM and restarted")
    # IDA
    ida = ["-output_fields", "0", "-arrest_stop", "first", "-time_rtol", "1e-3"]
    run("couette_cessation", ida + ["-checkpoint_every", "100"], dirs["ida0"])
    run("couette_cessation", ida + ["-restart", os.path.join(dirs["ida0"], "checkpoint.h5")], dirs["ida_b"])
    ta, tb = summary(dirs["ida0"])["t_arrest"], summary(dirs["ida_b"])["t_arrest"]
    rel = abs(tb - ta) / ta
    print("IDA restarted from its last checkpoint (every 100 steps) of %d: arrest %.8g and %.8g, relative difference %.2e (bound 10 rtol = 1e-2)" % (summary(dirs["ida0"])["steps"], ta, tb, rel))
    if not (ta > 0 and rel <= 1e-2):
        fail("IDA's restarted arrest time differs by %.3e > 10 rtol" % rel)
    # refused restarts
    check_refused(w, [("restart_other_integrator", ["-scene", "poiseuille_cessation", "-restart", os.path.join(dirs["a0"], "checkpoint.h5")], "-restart"),
                      ("restart_other_mesh", ["-scene", "couette_cessation", "-mesh_ny", "16"] + base + ["-restart", os.path.join(dirs["a0"], "checkpoint.h5")], "-restart"),
                      ("restart_missing", ["-scene", "couette_cessation", "-restart", os.path.join(w, "none.h5")], "-restart")])


def test_restart_collapse():
    """The use case of checkpoints: a granular column collapse (a = 0.5,
    cells of 0.1 h_i, IDA with the level set) checkpointed every 150 steps
    and restarted from its last checkpoint. IDA restarts at order 1 (see
    test_restart), so the two runs agree within the error control: arrest
    time within 10 rtol (rtol 1e-4 here), front and height within 1e-3
    relative, and the level set's bookkeeping carried over (the same number
    of reinitialisations, the energies of the between-step actions within
    1e-3 relative)."""
    w = work("restart_collapse")
    a, b = os.path.join(w, "a"), os.path.join(w, "b")
    opts = ["-output_fields", "0", "-aspect_ratio", "0.5", "-cell_size", "0.1", "-arrest_stop", "first"]
    run("column_collapse", opts + ["-checkpoint_every", "150"], a)
    p = run("column_collapse", opts + ["-restart", os.path.join(a, "checkpoint.h5")], b)
    sa, sb = summary(a), summary(b)
    restart_line = [l for l in p.stdout.splitlines() if l.startswith("restart from")]
    print("%s; steps %d and %d" % (restart_line[0] if restart_line else "(no restart line)", sa["steps"], sb["steps"]))
    if not restart_line:
        fail("the second run did not restart")
    rel = abs(sb["t_arrest"] - sa["t_arrest"]) / sa["t_arrest"]
    print("arrest %.8g and %.8g (relative %.2e, bound 10 rtol = 1e-3)" % (sa["t_arrest"], sb["t_arrest"], rel))
    if not (sa["t_arrest"] > 0 and rel <= 1e-3):
        fail("restarted arrest time differs by %.3e" % rel)
    for k in ("front", "height_axis", "energy_reinit", "energy_correction", "volume_correction_shift"):
        r = abs(sb[k] - sa[k]) / max(abs(sa[k]), 1e-12)
        print("  %-24s %.8g and %.8g (relative %.1e)" % (k, sa[k], sb[k], r))
        if r > 1e-3:
            fail("%s differs by %.3e relative after the restart" % (k, r))
    if sa["reinitialisations"] != sb["reinitialisations"]:
        fail("reinitialisations %g and %g" % (sa["reinitialisations"], sb["reinitialisations"]))


def sweep_rows(outdir):
    with open(os.path.join(outdir, "sweep.csv")) as f:
        r = csv.reader(f)
        header = next(r)
        rows = list(r)
    for row in rows:
        if len(row) != len(header):
            fail("sweep.csv row %s has %d fields, the header %d" % (row[:3], len(row), len(header)))
    return [dict(zip(header, row)) for row in rows]


def run_sweep(opts, outdir, ranks=1, scene="couette_cessation"):
    cmd = []
    if ranks > 1:
        cmd = [ARGS.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)]
    cmd += [ARGS.slump, "-scene", scene, "-output_dir", outdir] + opts
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        fail("sweep failed (%d): %s\n%s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-3000:], p.stderr[-3000:]))
    return p


def test_sweep_parallel():
    """A 3-value sweep on 2 ranks (2 groups of 1 rank) gives 3 rows whose
    arrest times equal those of the single runs to 1e-10 relative, and each
    row carries the exact model's arrest time with the error against it
    (Couette Bn 1, 8 cells across: within 2e-2 at m = 1e2, 3e-3 at 1e3 and
    1e4 of the exact mean-shear-rate arrest)."""
    w = work("sweep_parallel")
    base = ["-mesh_ny", "8", "-time_final", "0.15"]
    ms = ["1e2", "1e3", "1e4"]
    run_sweep(base + ["-sweep", "rheology_papanastasiou_m:" + ",".join(ms)], os.path.join(w, "sweep"), ranks=2)
    rows = sweep_rows(os.path.join(w, "sweep"))
    if len(rows) != 3:
        fail("expected 3 rows, got %d" % len(rows))
    tol = {"1e2": 2e-2, "1e3": 3e-3, "1e4": 3e-3}
    for m in ms:
        row = [r for r in rows if r["rheology_papanastasiou_m"] == m]
        if len(row) != 1 or row[0]["status"] != "ok":
            fail("no ok row for m = %s: %s" % (m, row))
        row = row[0]
        run("couette_cessation", base + ["-rheology_papanastasiou_m", m, "-output_fields", "0"], os.path.join(w, "single_" + m))
        s = summary(os.path.join(w, "single_" + m))
        t_sweep, t_single = float(row["t_arrest"]), s["t_arrest"]
        rel = abs(t_sweep - t_single) / t_single
        err, ta = float(row["arrest_error"]), float(row["t_arrest_exact"])
        print("m %s: sweep %.12e, single run %.12e, rel diff %.1e; exact model %.8f, error %.2e; %s steps, %s residual evaluations, %s s, %s MB"
              % (m, t_sweep, t_single, rel, ta, err, row["steps"], row["res_evals"], row["wall_time"], row["peak_memory_mb"]))
        if not rel <= 1e-10:
            fail("m %s: sweep and single run differ by %g relative (tolerance 1e-10)" % (m, rel))
        if abs(err - abs(t_sweep - ta) / ta) > 1e-6 * err + 1e-12:
            fail("m %s: arrest_error %g is not |t_arrest - t_arrest_exact| / t_arrest_exact" % (m, err))
        if not err <= tol[m]:
            fail("m %s: error against the exact model %g > %g" % (m, err, tol[m]))
        for k in ("steps", "res_evals", "jac_evals", "newton_its", "lin_its", "wall_time", "peak_memory_mb"):
            if not float(row[k]) > 0:
                fail("m %s: column %s is %r, expected > 0" % (m, k, row[k]))


def test_sweep_invalid():
    """A 2 x 2 sweep (-sweep x -sweep2) with an invalid value: the two runs
    with it become rows with status 'invalid' and the reason; the two others
    are complete rows, and the sweep exits 0."""
    w = work("sweep_invalid")
    p = run_sweep(["-mesh_ny", "8", "-time_final", "0.15", "-sweep", "rheology_papanastasiou_m:1e3,-5", "-sweep2", "bn:1,4"], w)
    rows = sweep_rows(w)
    if len(rows) != 4:
        fail("expected 4 rows, got %d" % len(rows))
    for r in rows:
        print("%s %s: %s %s t_arrest %s" % (r["rheology_papanastasiou_m"], r["bn"], r["status"], r["reason"], r["t_arrest"]))
        if r["rheology_papanastasiou_m"] == "-5":
            if r["status"] != "invalid" or "rheology_papanastasiou_m" not in r["reason"]:
                fail("the invalid value gives status %r, reason %r; expected 'invalid' and a reason naming the option" % (r["status"], r["reason"]))
        else:
            if r["status"] != "ok":
                fail("a valid run has status %r (%s)" % (r["status"], r["reason"]))
            for k in ("t_arrest", "t_arrest_exact", "arrest_error", "steps", "res_evals", "wall_time", "peak_memory_mb"):
                if not _isnum(r[k]):
                    fail("complete row expected; column %s is %r" % (k, r[k]))
    if "2 failed" not in p.stdout:
        fail("the sweep's last line should count 2 failed runs:\n" + p.stdout[-500:])


def test_tight_tolerances():
    """IDA from rtol 1e-2 to 1e-8 (atol 1e-9; before the first step was
    floored, rtol <= 1e-5 failed at t = 0): both rows ok, each arrest within
    2e-3 of the exact model's (8 cells across: the mesh error is 1.5e-3), and
    the two within 1e-3 of each other (Couette Bn 1, m 1e4)."""
    w = work("tight_tolerances")
    run_sweep(["-mesh_ny", "8", "-time_final", "0.15", "-arrest_stop", "first", "-time_atol", "1e-9", "-sweep", "time_rtol:1e-2,1e-8"], w)
    rows = sweep_rows(w)
    t = {}
    for r in rows:
        print("rtol %s: %s, t_arrest %s, exact %s, error %s, %s steps" % (r["time_rtol"], r["status"], r["t_arrest"], r["t_arrest_exact"], r["arrest_error"], r["steps"]))
        if r["status"] != "ok":
            fail("rtol %s: status %s (%s)" % (r["time_rtol"], r["status"], r["reason"]))
        if not float(r["arrest_error"]) <= 2e-3:
            fail("rtol %s: error against the exact model %s > 2e-3" % (r["time_rtol"], r["arrest_error"]))
        t[r["time_rtol"]] = float(r["t_arrest"])
    d = abs(t["1e-2"] - t["1e-8"]) / t["1e-8"]
    if not d <= 1e-3:
        fail("rtol 1e-2 and 1e-8 differ by %g relative (> 1e-3)" % d)


def levelset_rotation(method, extra=(), n=64, name=None):
    """One revolution of a circle (radius 0.15, n x n cells, P2 level set,
    IDA rtol 1e-3) with reinitialisation `method`."""
    w = work(name or "levelset_" + method)
    run("levelset_rotation", ["-mesh_n", str(n), "-reinit", method, "-time_rtol", "1e-3", "-output_fields", "0"] + list(extra), w)
    s = summary(w)
    print("%s: area error %.3e (max drift %.3e), |grad phi| deviation in the 3-cell band: mean %.3e max %.3e; after a reinitialisation: mean %.3e max %.3e; %d reinitialisations, %d steps, %.1f s"
          % (method, s["area_error"], s["area_drift_max"], s["grad_dev_mean"], s["grad_dev_max"], s["grad_dev_mean_reinit"], s["grad_dev_max_reinit"], s["reinitialisations"], s["steps"], s["wall_time"]))
    # the issue's bound: area error after one revolution <= 1 %
    if not abs(s["area_error"]) <= 1e-2:
        fail("%s: area error after one revolution %.3e > 1e-2" % (method, s["area_error"]))
    # the volume record (interface.csv) holds every step
    with open(os.path.join(w, "interface.csv")) as f:
        nrec = sum(1 for _ in f) - 2
    if nrec != int(s["steps"]):
        fail("%s: interface.csv has %d step rows, the run took %d steps" % (method, nrec, s["steps"]))
    return s


def test_levelset_none():
    levelset_rotation("none")


def test_levelset_redistance():
    """After a redistance |grad phi| is within 5 % of 1 in the 3-cell band
    (the issue's bound), everywhere in it (max over sub-triangles)."""
    s = levelset_rotation("redistance")
    if not s["grad_dev_max_reinit"] <= 0.05:
        fail("redistance: max | |grad phi| - 1 | in the band %.3e > 0.05" % s["grad_dev_max_reinit"])
    if not s["reinitialisations"] >= 10:
        fail("redistance: only %d reinitialisations" % s["reinitialisations"])


def test_levelset_convective():
    """Riber's coupled transport-redistancing (eq. 2.16, lagged as in his
    eq. 2.18) with the thesis' parameters, lambda = 1 and E = 2 cells: the
    area after one revolution within the issue's 1 % (measured -0.18 %).
    The profile is the filtered distance E tanh(d/E), so the band is measured
    on d = E atanh(phi/E): its mean deviation | |grad d| - 1 | in the 3-cell
    band is held to 5 % (measured 3.3 %); the largest one on a sub-triangle
    is 17 %, above the 5 % the issue asks for, and is bounded at 25 % here
    only to catch a regression. The step count guards against the stall the
    fully implicit form had (1320 steps measured)."""
    s = levelset_rotation("convective")
    if not s["grad_dev_mean"] <= 0.05:
        fail("convective: mean | |grad d| - 1 | in the band %.3e > 0.05" % s["grad_dev_mean"])
    if not s["grad_dev_max"] <= 0.25:
        fail("convective: max | |grad d| - 1 | in the band %.3e > 0.25" % s["grad_dev_max"])
    if not s["steps"] <= 3000:
        fail("convective: %d steps for one revolution (> 3000)" % s["steps"])


def test_levelset_convective_fine():
    """The convective method's band converges with the mesh: with a filter
    of E = 6 cells (-reinit_convective_width 6), the worst sub-triangle of
    the 3-cell band deviates by 7.6 % on 64 x 64 cells and 3.5 % on
    128 x 128 (measured; mean 0.9 %, area error -0.04 %, 1511 steps,
    about 10 min). Held to the issue's 5 % everywhere in the band, and the
    area to its 1 %."""
    s = levelset_rotation("convective", ["-reinit_convective_width", "6"], n=128, name="levelset_convective_fine")
    if not s["grad_dev_max"] <= 0.05:
        fail("convective (128 x 128, E = 6 cells): max | |grad d| - 1 | in the band %.3e > 0.05" % s["grad_dev_max"])
    if not s["grad_dev_mean"] <= 0.02:
        fail("convective (128 x 128, E = 6 cells): mean | |grad d| - 1 | in the band %.3e > 0.02" % s["grad_dev_mean"])


def test_levelset_hamilton_jacobi():
    s = levelset_rotation("hamilton_jacobi")
    if not s["grad_dev_max_reinit"] <= 0.05:
        fail("hamilton_jacobi: max | |grad phi| - 1 | in the band %.3e > 0.05" % s["grad_dev_max_reinit"])
    if not s["reinitialisations"] >= 10:
        fail("hamilton_jacobi: only %d reinitialisations" % s["reinitialisations"])


def test_levelset_unknowns():
    """Effects stay off unless asked: a single-phase scene carries no
    level-set unknowns (its unknowns are exactly velocity + pressure), and
    the rotation scene's are exactly the level set's nodes (the prescribed
    velocity is not an unknown): (2n+1)^2 for P2, (n+1)^2 for P1."""
    w = work("unknowns_single")
    p = run("couette_cessation", ["-time_final", "1e-3", "-output_fields", "0", "-mesh_ny", "8"], w)
    p = subprocess.run([ARGS.slump, "-scene", "couette_cessation", "-output_dir", w, "-time_final", "1e-3", "-output_fields", "0", "-mesh_ny", "8"], capture_output=True, text=True)
    if "level set" in p.stdout:
        fail("couette_cessation reports level-set unknowns:\n" + p.stdout[:2000])
    import re
    m = re.search(r"unknowns: (\d+) velocity, (\d+) pressure", p.stdout)
    if not m:
        fail("no unknowns line in:\n" + p.stdout[:2000])
    s = summary(w)
    if int(s["unknowns"]) != int(m.group(1)) + int(m.group(2)):
        fail("couette_cessation: %d unknowns, velocity + pressure = %s + %s" % (s["unknowns"], m.group(1), m.group(2)))
    print("couette_cessation: %d unknowns = %s velocity + %s pressure, no level set" % (s["unknowns"], m.group(1), m.group(2)))
    for deg, n, expect in ((2, 16, 33 * 33), (1, 16, 17 * 17)):
        w = work("unknowns_ls%d" % deg)
        run("levelset_rotation", ["-mesh_n", str(n), "-levelset_degree", str(deg), "-time_final", "0.01", "-output_fields", "0"], w)
        s = summary(w)
        if int(s["unknowns"]) != expect:
            fail("levelset_rotation P%d on %d x %d: %d unknowns, expected %d" % (deg, n, n, s["unknowns"], expect))
        print("levelset_rotation P%d, %d x %d: %d unknowns = level-set nodes" % (deg, n, n, s["unknowns"]))


def test_levelset_parallel():
    """A tenth of a turn with redistance and with Hamilton-Jacobi every 5
    steps, fixed-step BDF2 (dt 2e-3, so both runs take the same steps), on
    1 and 2 ranks: the area errors agree to 1e-8 (the geometric operations
    take their minima over ranks, so the partition does not change them).
    With IDA the two step sequences differ and so does the result. The
    convective method (no between-step action: its direction and source
    come from the last step's state, which each rank holds for its own
    cells and their halo) is compared the same way."""
    for method in ("redistance", "hamilton_jacobi", "convective"):
        a = {}
        for ranks in (1, 2):
            w = work("levelset_par_%s_%d" % (method, ranks))
            run("levelset_rotation", ["-mesh_n", "32", "-reinit", method, "-reinit_every", "5", "-time_final", "0.1", "-time_integrator", "bdf2", "-time_dt", "2e-3", "-output_fields", "0"], w, ranks=ranks)
            s = summary(w)
            a[ranks] = s
        d = abs(a[1]["area_error"] - a[2]["area_error"])
        print("%s: area error %.10e (1 rank) %.10e (2 ranks), %d / %d reinitialisations" % (method, a[1]["area_error"], a[2]["area_error"], a[1]["reinitialisations"], a[2]["reinitialisations"]))
        if (method != "convective" and a[1]["reinitialisations"] < 1) or a[1]["reinitialisations"] != a[2]["reinitialisations"]:
            fail("%s: reinitialisations %d (1 rank) and %d (2 ranks)" % (method, a[1]["reinitialisations"], a[2]["reinitialisations"]))
        if not d <= 1e-8:
            fail("%s: area errors differ by %g between 1 and 2 ranks (> 1e-8)" % (method, d))


def test_dam_break():
    """Newtonian dam-break (two-phase, box 0.42 x 0.44 m, column 0.114 m,
    rho 1000/1, eta 1/1e-3) on 21 x 22 cells to t = 0.2 s, IDA rtol 1e-3.
    Checks: (1) the material volume drifts by at most 2 % (the issue's bound;
    redistance every 20 steps with the global volume correction); (2) the
    front advances monotonically and no faster than Ritter's inviscid
    shallow-water front, x_f - r_i <= 2 sqrt(g h_i) t; (3) the energy
    balance: potential energy released = kinetic energy + energy dissipated
    in the material, to 10 % of the released energy (the rest: dissipation in
    the air, the level set's numerical diffusion and volume corrections);
    (4) interface.csv has one row per step plus the initial one."""
    w = work("dam_break")
    run("dam_break", ["-mesh_nx", "21", "-mesh_ny", "22", "-time_final", "0.2", "-time_rtol", "1e-3", "-output_fields", "0"], w)
    s = summary(w)
    with open(os.path.join(w, "interface.csv")) as f:
        ifc = list(csv.DictReader(f))
    if len(ifc) - 1 != int(s["steps"]):
        fail("interface.csv has %d step rows, the run took %d steps" % (len(ifc) - 1, s["steps"]))
    g, ri, hi = 9.81, 0.114, 0.114
    worst = 0.0
    for a, b in zip(ifc, ifc[1:]):
        if float(b["x_max"]) < float(a["x_max"]) - 1e-9:
            fail("the front receded from %s to %s at t = %s" % (a["x_max"], b["x_max"], b["t"]))
    for r in ifc[1:]:
        t, xf = float(r["t"]), float(r["x_max"])
        worst = max(worst, (xf - ri) / (2.0 * math.sqrt(g * hi) * t))
    if not worst <= 1.0:
        fail("the front outran Ritter's inviscid front: (x_f - r_i) / (2 sqrt(g h_i) t) = %.3f > 1" % worst)
    ser = series(w)
    ep0, diss = ser[0]["potential_energy"], dissipated(ser)
    released = ep0 - ser[-1]["potential_energy"]
    imbalance = (released - ser[-1]["kinetic_energy"] - diss) / released
    print("dam_break 21 x 22, t = 0.2 s: front Z = %.3f, axis height H = %.3f, volume drift max %.3e (volume error %.3e), "
          "fastest front / Ritter %.3f, energy released %.4f J/m = kinetic %.4f + dissipated %.4f (imbalance %.3f), %d steps, %.1f s"
          % (s["front_over_ri"], s["height_axis_over_hi"], s["volume_drift_max"], s["volume_error"], worst, released, ser[-1]["kinetic_energy"], diss, imbalance, s["steps"], s["wall_time"]))
    if not s["volume_drift_max"] <= 0.02:
        fail("material volume drift %.3e > 2 %%" % s["volume_drift_max"])
    if not abs(imbalance) <= 0.1:
        fail("energy imbalance %.3f of the released energy > 10 %%" % imbalance)


def martin_moyce():
    """Martin & Moyce's (1952) surge front, n^2 = 2: list of (T, Z)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "data", "martin_moyce_1952.csv")
    with open(path) as f:
        return [(float(r["T"]), float(r["Z"])) for r in csv.DictReader(l for l in f if not l.startswith("#"))]


def test_dam_break_martin_moyce():
    """Newtonian dam-break against Martin & Moyce's (1952) experiment, fig. 3,
    n^2 = 2 (cases/data/martin_moyce_1952.csv): a water column of width
    a = 2.25 in = 0.05715 m and height 2a in a box 0.5 x 0.15 m, material
    rho 1000 and eta 1e-2 Pa s (Re = rho sqrt(g a) a / eta = 4.3e3; with
    water's 1e-3 the front is the same within 1 % up to T = 2.5 but IDA stops
    at T = 2.8 on this mesh), air rho 1, eta 1e-3, slip floor, 35 x 11 cells
    (a / 5), t = 0.15 s (T = t sqrt(2 g / a) = 2.78). Checks: (1) at every
    experimental point with 0.8 <= T <= 2.78 the front Z = x_f / a lies
    within 15 % of the experiment (measured +7 % to +12 %: the computed
    front leads, as the experiment's gate takes time to lift); (2) the lead
    is a delay: shifted by the best delay dT in [0, 0.4] the computed curve
    matches the points to 3 % RMS (measured dT = 0.18, 2.2 %)."""
    martin_moyce_run("dam_break_martin_moyce", [])


def test_dam_break_convective():
    """The Martin & Moyce dam-break of test_dam_break_martin_moyce with the
    convective reinitialisation (lambda = 1 m/s, E = 2 cells, as in Riber's
    dam-break) and the global volume correction every 20 steps, the same
    checks plus the material volume drift <= 2 % (measured: front +7 % to
    +12 %, dT = 0.17, 1.8 % RMS, drift 0.64 %, 629 steps; without the
    correction the volume drifts by 9 % by T = 2.78)."""
    s = martin_moyce_run("dam_break_convective", ["-reinit", "convective"])
    if not s["volume_drift_max"] <= 0.02:
        fail("convective dam-break: volume drift %.3e > 2e-2" % s["volume_drift_max"])


def martin_moyce_run(name, extra):
    w = work(name)
    a, g, tf = 0.05715, 9.81, 0.15
    run("dam_break", ["-column_width", str(a), "-column_height", str(2 * a), "-box_length", "0.5", "-box_height", "0.15",
                      "-mesh_nx", "35", "-mesh_ny", "11", "-rheology_viscosity", "1e-2", "-time_final", str(tf),
                      "-time_rtol", "1e-3", "-output_fields", "0"] + list(extra), w)
    s = summary(w)
    with open(os.path.join(w, "interface.csv")) as f:
        ifc = [(float(r["t"]) * math.sqrt(2 * g / a), float(r["x_max"]) / a) for r in csv.DictReader(f)]

    def front(T):
        if T <= ifc[0][0]:
            return ifc[0][1]
        for (t0, z0), (t1, z1) in zip(ifc, ifc[1:]):
            if t1 >= T:
                return z0 + (z1 - z0) * (T - t0) / (t1 - t0)
        fail("the run ended at T = %.3f before T = %.3f" % (ifc[-1][0], T))

    pts = [(T, Z) for T, Z in martin_moyce() if 0.8 <= T <= ifc[-1][0]]
    if len(pts) < 4:
        fail("only %d experimental points in the run's time span (T <= %.3f)" % (len(pts), ifc[-1][0]))
    raw = [front(T) / Z - 1 for T, Z in pts]
    best = None
    for k in range(41):
        dT = 0.01 * k
        r = [front(T - dT) / Z - 1 for T, Z in pts]
        rms = math.sqrt(sum(x * x for x in r) / len(r))
        if best is None or rms < best[0]:
            best = (rms, dT)
    print("dam_break vs Martin & Moyce n^2 = 2, 35 x 11 cells: at T = %s the front Z = %s against %s (%s); best delay dT = %.2f, "
          "RMS %.4f; volume drift max %.2e, %d steps, %.1f s"
          % (", ".join("%.3f" % T for T, _ in pts), ", ".join("%.3f" % front(T) for T, _ in pts), ", ".join("%.3f" % Z for _, Z in pts),
             ", ".join("%+.3f" % x for x in raw), best[1], best[0], s["volume_drift_max"], s["steps"], s["wall_time"]))
    for (T, Z), x in zip(pts, raw):
        if not abs(x) <= 0.15:
            fail("at T = %.3f the front Z = %.3f differs from the experiment's %.3f by %+.1f %% (> 15 %%)" % (T, front(T), Z, 100 * x))
    if not best[0] <= 0.03:
        fail("with the best delay dT = %.2f the front still differs from the experiment by %.4f RMS (> 3 %%)" % (best[1], best[0]))
    return s


def test_column_collapse():
    """Granular column collapse, a = 0.5 (mu(I) with Lagree et al.'s
    parameters, Coulomb floor mu_w = 0.6, cells of 0.1 h_i), run until the
    mean shear rate of the material falls below 0.05 (root-found; the run
    stops there). Checks against REFERENCES.md: (1) the run-out
    (r_f - r_i)/r_i within 15 % of the thesis' fit 1.72 a^0.97 = 0.878, with
    r_f the zero contour's end and, separately, the end of the layer at
    least 5 % of h_i thick;
    (2) the height on the axis within 10 % of h_i (the deposit is a truncated
    cone whose top stays at h_i); (3) the arrest time lies between the
    published collapse time 3 sqrt(h_i/g) and the scene's final time 8;
    (4) the kinetic energy at arrest is below 1 % of its peak; (5) the
    material volume drifts by at most 2 %; (6) the deposit profile
    (deposit.csv) never rises by more than a hundredth of h_i downstream and
    ends within a cell of the front."""
    s, fit = collapse_to_arrest("column_collapse", 0.5, 0.1)
    if not abs(s["runout_thick_over_ri"] / fit - 1) <= 0.15:
        fail("run-out of the layer >= 5 %% h_i thick %.4f is not within 15 %% of the fit %.4f" % (s["runout_thick_over_ri"], fit))
    if not 0.9 <= s["height_axis_over_hi"] <= 1.001:
        fail("axis height %.4f h_i outside [0.9, 1.001]" % s["height_axis_over_hi"])


def collapse_to_arrest(name, a, cell, args=()):
    """Runs column_collapse at aspect ratio a on cells of `cell` h_i to
    arrest and checks what every aspect ratio shares: the scene's fit is
    1.72 a^0.97, the zero contour's run-out is within 15 % of it, the
    arrest time is in [3, 8], the kinetic energy at arrest is below 1 % of
    its peak, the volume drifts by at most 2 % and the deposit never rises
    downstream and ends within a cell of the front. Returns the summary
    and the fit."""
    w = work(name)
    run("column_collapse", ["-aspect_ratio", repr(a), "-cell_size", repr(cell), "-arrest_stop", "first", "-output_fields", "0"] + list(args), w)
    s = summary(w)
    ser = series(w)
    with open(os.path.join(w, "deposit.csv")) as f:
        dep = [(float(r["x"]), float(r["height"])) for r in csv.DictReader(f)]
    ta = s.get("t_arrest", -1.0)
    kmax = max(r["kinetic_energy"] for r in ser)
    kend = ser[-1]["kinetic_energy"]
    fit = 1.72 * a ** 0.97
    print("column_collapse a = %g, cells %g h_i (%d): run-out (r_f - r_i)/r_i = %.4f (thesis fit %.4f, %+.1f %%), layer >= 5 %% h_i thick %.4f (%+.1f %%), "
          "axis height %.4f h_i, front %.4f, arrest at t = %.3f (mean |gdot| < 0.05), KE %.3e at arrest / peak %.3e, volume drift max %.3e, %d steps, %.1f s"
          % (a, cell, s["cells"], s["runout_over_ri"], fit, 100 * (s["runout_over_ri"] / fit - 1), s["runout_thick_over_ri"], 100 * (s["runout_thick_over_ri"] / fit - 1),
             s["height_axis_over_hi"], s["front"], ta, kend, kmax, s["volume_drift_max"], s["steps"], s["wall_time"]))
    if abs(s["runout_fit_thesis"] - fit) > 1e-6:
        fail("the scene's run-out fit %g differs from 1.72 a^0.97 = %g" % (s["runout_fit_thesis"], fit))
    if not abs(s["runout_over_ri"] / fit - 1) <= 0.15:
        fail("run-out %.4f is not within 15 %% of the fit %.4f" % (s["runout_over_ri"], fit))
    if not 3.0 <= ta <= 8.0:
        fail("arrest time %g outside [3, 8]" % ta)
    if not kend <= 0.01 * kmax:
        fail("kinetic energy at arrest %.3e > 1 %% of its peak %.3e" % (kend, kmax))
    if not s["volume_drift_max"] <= 0.02:
        fail("material volume drift %.3e > 2 %%" % s["volume_drift_max"])
    check_deposit(dep, s["front"], cell)
    return s, fit


def check_deposit(dep, front, cell):
    """The deposit h(x) never rises by more than a hundredth of h_i
    downstream and ends within a cell of the front."""
    for (x0, h0), (x1, h1) in zip(dep, dep[1:]):
        if h1 > h0 + 0.01:
            fail("the deposit rises from %.4f at x = %.3f to %.4f at x = %.3f" % (h0, x0, h1, x1))
    last = max((x for x, h in dep if h > 0), default=0.0)
    if not abs(last - front) <= cell + 1e-9:
        fail("the deposit ends at x = %.3f, the front is at %.3f" % (last, front))


def test_column_collapse_tall():
    """Granular column collapse, a = 6.26 (6036 grains; otherwise the set-up
    of test_column_collapse), on cells of 0.05 h_i (the column is 3.2 cells
    wide), run to arrest (mean shear rate < 0.05). Checks: (1) the run-out
    (r_f - r_i)/r_i of the zero contour within 15 % of the thesis' fit
    1.72 a^0.97 = 10.19 (measured -2.8 %; on cells of 0.04 and 0.03 it is
    +4.8 % and +12.0 %, so this holds on three meshes but is not a converged
    number, docs/collapses.md). The layer at least 5 % of h_i thick is
    reported, not checked: the deposit is about 0.2 h_i high on the axis,
    so that layer ends 26-30 % short of the fit on all three meshes; (2) the arrest time between the
    published collapse time 3 sqrt(h_i/g) and the scene's final time 8;
    (3) the kinetic energy at arrest below 1 % of its peak; (4) the
    material volume drift at most 2 %; (5) the deposit never rises
    downstream and ends within a cell of the front."""
    collapse_to_arrest("column_collapse_tall", 6.26, 0.05)


def test_bingham_dam_break_units():
    """bingham_dam_break in the thesis' viscous units (time eta_p/(rho g h_i),
    weight 1, inertia Re): at Re = 1e-3 the flow is quasi-static, so on
    40 x 15 cells to t = 0.5 t_c (outputs every 0.05) it must (1) move on
    the viscous time scale (front beyond 1.02 h_i: in the old units,
    time sqrt(h_i/g), it had reached 1.05 only by t = 943); (2) not depend
    on Re: Re = 1e-4 gives the same front, axis height and mean shear rate
    to 1e-3 relative and the same kinetic energy over Re to 2 %; (3) turn
    the potential energy released into dissipation in the material
    (the kinetic energy is ~1e-6 of it) to 5 % (measured 4.1 % short:
    the series' dissipation leaves out the Navier floor's friction, and the
    trapezoidal rule on outputs every 0.05 t_c misses the start-up; neither
    is measured apart); (4) keep the volume within 2 %; (5) agree with the
    quasi-static variant (-re 0: no inertia, velocity and pressure algebraic,
    KINSOL line search per stage) to 1e-3 in the same three numbers and 2 %
    in the kinetic energy (its density is 1, so its kinetic energy is KE/Re),
    in fewer than a fifth of the steps."""
    w = work("bingham_dam_break_units")
    opts = ["-mesh_nx", "40", "-mesh_ny", "15", "-output_fields", "0", "-time_final", "0.5", "-time_output_dt", "0.05"]
    res = {}
    for re in ("1e-3", "1e-4", "0"):
        d = os.path.join(w, "re" + re)
        run("bingham_dam_break", opts + ["-re", re], d)
        s, ser = summary(d), series(d)
        diss = dissipated(ser)
        released = ser[0]["potential_energy"] - ser[-1]["potential_energy"]
        res[re] = dict(front=s["front"], axis=s["height_axis"], gdot=ser[-1]["mean_shear_rate"],
                       ke_re=ser[-1]["kinetic_energy"] / (float(re) if float(re) > 0 else 1.0), released=released, diss=diss,
                       drift=s["volume_drift_max"], steps=s["steps"], wall=s["wall_time"])
        print("Re = %s: front %.6f, axis %.6f, mean shear rate %.6e, KE/Re %.4e, potential energy released %.5e, "
              "dissipated %.5e, drift %.2e, %d steps, %.1f s" % (re, s["front"], s["height_axis"], res[re]["gdot"], res[re]["ke_re"],
                                                                released, diss, s["volume_drift_max"], s["steps"], s["wall_time"]))
    a = res["1e-3"]
    if not a["front"] > 1.02:
        fail("the front is at %.4f after 0.5 t_c: the column does not move on the viscous time scale" % a["front"])
    for other in ("1e-4", "0"):
        b = res[other]
        for k in ("front", "axis", "gdot"):
            if not abs(a[k] / b[k] - 1) <= 1e-3:
                fail("%s differs between Re = 1e-3 and %s: %.6e vs %.6e" % (k, other, a[k], b[k]))
        if not abs(a["ke_re"] / b["ke_re"] - 1) <= 0.02:
            fail("kinetic energy over Re differs between Re = 1e-3 and %s: %.4e vs %.4e" % (other, a["ke_re"], b["ke_re"]))
    if not res["0"]["steps"] * 5 < a["steps"]:
        fail("the quasi-static variant took %d steps, not fewer than a fifth of Re = 1e-3's %d" % (res["0"]["steps"], a["steps"]))
    for re, r in res.items():
        if not abs(r["diss"] / r["released"] - 1) <= 0.05:
            fail("Re = %s: dissipation %.5e vs potential energy released %.5e" % (re, r["diss"], r["released"]))
        if not r["drift"] <= 0.02:
            fail("Re = %s: volume drift %.3e > 2 %%" % (re, r["drift"]))


def test_bingham_dam_break_creep():
    """The quasi-static bingham_dam_break (-re 0, Bn = 0.1, 40 x 15 cells)
    to the thesis' arrest time t = 310 at Papanastasiou m = 1e3 and 1e4.
    Both must get there without an unrecoverable failure, with the material
    volume within 2 %, and with most of the material below the yield stress
    (yielded fraction < 0.1; measured 0.044 and 0.068). The material then
    creeps through the regularisation: the mean shear rate must be at least
    2.5 times lower at m = 1e4 (measured 1.224e-3 and 3.119e-4, 3.9 times).
    It must also spread less at m = 1e4 (front 2.165 and 1.943). At m = 1e4
    the deposit must lie within 15 % of the perfectly plastic lubrication
    limit in front position (2.24; measured 1.943, -13 %) and within 10 % in
    axis height (0.669; measured 0.706, +5.5 %)."""
    w = work("bingham_dam_break_creep")
    res = {}
    for m in ("1e3", "1e4"):
        d = os.path.join(w, "m" + m)
        run("bingham_dam_break", ["-re", "0", "-mesh_nx", "40", "-mesh_ny", "15", "-output_fields", "0", "-time_final", "310",
                                  "-time_output_dt", "10", "-rheology_papanastasiou_m", m], d)
        s, ser = summary(d), series(d)
        res[m] = dict(front=s["front"], axis=s["height_axis"], gdot=ser[-1]["mean_shear_rate"], yf=ser[-1]["yielded_fraction"],
                      drift=s["volume_drift_max"], t=s["t_final"])
        print("m = %s: t %.1f, front %.4f, axis %.4f, mean shear rate %.4e, yielded fraction %.4f, drift %.2e, %d steps, %.1f s"
              % (m, s["t_final"], s["front"], s["height_axis"], res[m]["gdot"], res[m]["yf"], s["volume_drift_max"], s["steps"], s["wall_time"]))
        if not abs(s["t_final"] - 310) <= 1e-6 * 310:
            fail("m = %s: the run stopped at t = %g before 310" % (m, s["t_final"]))
        if not s["volume_drift_max"] <= 0.02:
            fail("m = %s: volume drift %.3e > 2 %%" % (m, s["volume_drift_max"]))
        if not res[m]["yf"] < 0.1:
            fail("m = %s: yielded fraction %.3f at t = 310, not below 0.1" % (m, res[m]["yf"]))
    a, b = res["1e3"], res["1e4"]
    if not a["gdot"] >= 2.5 * b["gdot"]:
        fail("mean shear rate at t = 310: %.3e (m = 1e3) is not 2.5 times %.3e (m = 1e4)" % (a["gdot"], b["gdot"]))
    if not b["front"] < a["front"]:
        fail("the front spreads further at m = 1e4 (%.4f) than at 1e3 (%.4f)" % (b["front"], a["front"]))
    xf = (3.0 / (2.0 * (2.0 * 0.1) ** 0.5)) ** (2.0 / 3.0)
    h0 = (2.0 * 0.1 * xf) ** 0.5
    if not abs(b["front"] / xf - 1) <= 0.15:
        fail("m = 1e4: front %.4f not within 15 %% of the plastic limit %.4f" % (b["front"], xf))
    if not abs(b["axis"] / h0 - 1) <= 0.10:
        fail("m = 1e4: axis height %.4f not within 10 %% of the plastic limit %.4f" % (b["axis"], h0))


def test_stability_column_collapse_air():
    """Hard ratios over a collapse: column_collapse a = 0.5 with the ambient
    viscosity lowered to 1e-6 (1e-6 of the rheology's floor-free viscosity
    scale mu_s p/gdot_min ~ 10 near the floor, 1e-2 of eta_min) and the
    density ratio 1e-3, cells of 0.1 h_i. It must run to arrest (mean shear
    rate < 0.05, root-found, t in [3, 8]) without an unrecoverable failure,
    keep the material volume within 2 %, and land within 15 % of the thesis'
    run-out fit, like the default air."""
    w = work("stability_column_collapse_air")
    run("column_collapse", ["-cell_size", "0.1", "-ambient_viscosity", "1e-6", "-arrest_stop", "first", "-output_fields", "0"], w)
    s = summary(w)
    fit = 1.72 * 0.5 ** 0.97
    ta = s.get("t_arrest", -1.0)
    print("column_collapse a = 0.5, air viscosity 1e-6, density 1e-3: arrest at t = %.3f, run-out %.4f (fit %.4f), axis height %.4f, "
          "volume drift max %.3e, %d steps, %d error-test and %d convergence failures, %.1f s"
          % (ta, s["runout_over_ri"], fit, s["height_axis_over_hi"], s["volume_drift_max"], s["steps"], s["err_test_fails"], s["conv_fails"], s["wall_time"]))
    if not 3.0 <= ta <= 8.0:
        fail("arrest time %g outside [3, 8]" % ta)
    if not s["volume_drift_max"] <= 0.02:
        fail("material volume drift %.3e > 2 %%" % s["volume_drift_max"])
    if not abs(s["runout_over_ri"] / fit - 1) <= 0.15:
        fail("run-out %.4f is not within 15 %% of the fit %.4f" % (s["runout_over_ri"], fit))


def test_column_chute():
    """Granular chute (mu(I) column of aspect ratio 1 released from
    h_r = 0.25 h_i, cells of 0.1 h_i, box 6 h_i long, outputs every 0.05):
    the run starts at the impact, t0 = sqrt(2 h_r/g), with the material
    falling at sqrt(2 g h_r). Checks: (1) the first output is at t0 and the
    kinetic energy just after the impact (after the consistent
    initialisation's projection) lies strictly between 0 and the free-fall
    value (1/2) r_i h_i v^2, with the potential energy that of the column on
    the floor, 1/2 r_i h_i^2, to 1 %; (2) the run arrests (mean shear rate
    < 0.05, root-found) after t0 and within t0 + 8; (3) the fall helps the
    spreading (the thesis' observation): the run-out exceeds the collapse
    fit from rest at the same a, 1.72 a^0.97, and stays inside the box;
    (4) energy balance from the impact on: kinetic energy after impact +
    potential energy released = kinetic energy + dissipation in the
    material, to 10 % of the energy budget; (5) volume drift <= 2 %; (6) with
    -release_height 0 the scene is column_collapse (with the chute's
    reinitialisation every 10 steps): the same front, kinetic energy and step
    count at t = 1 (1e-10 relative)."""
    w = work("column_chute")
    d1 = os.path.join(w, "drop")
    box = ["-cell_size", "0.1", "-box_length", "6", "-output_fields", "0"]
    run("column_chute", box + ["-release_height", "0.25", "-time_output_dt", "0.05", "-arrest_stop", "first"], d1)
    s = summary(d1)
    ser = series(d1)
    t0, v = math.sqrt(0.5), math.sqrt(0.5)
    ke_before = 0.5 * 1.0 * 1.0 * v * v
    ke0, ep0 = ser[0]["kinetic_energy"], ser[0]["potential_energy"]
    diss = dissipated(ser)
    budget = ke0 + ep0 - ser[-1]["potential_energy"]
    imbalance = (budget - ser[-1]["kinetic_energy"] - diss) / budget
    fit = 1.72
    print("column_chute a = 1, h_r = 0.25, 60 x 13 cells: impact at t0 = %.4f, KE %.4f before -> %.4f after the impact, PE %.4f; arrest at t = %.3f; "
          "run-out %.4f (collapse fit from rest %.2f); energy budget %.4f = KE %.2e + dissipated %.4f (imbalance %.3f); volume drift %.2e; %d steps, %.1f s"
          % (ser[0]["t"], ke_before, ke0, ep0, s["t_arrest"], s["runout_over_ri"], fit, budget, ser[-1]["kinetic_energy"], diss, imbalance, s["volume_drift_max"], s["steps"], s["wall_time"]))
    if abs(ser[0]["t"] - t0) > 1e-9 or abs(s["t_impact"] - t0) > 1e-9 or abs(s["impact_velocity"] - v) > 1e-9:
        fail("impact time/velocity: first output at %g, t_impact %g, v %g (expected %g, %g)" % (ser[0]["t"], s["t_impact"], s["impact_velocity"], t0, v))
    if not 0 < ke0 < ke_before:
        fail("kinetic energy after the impact %g not in (0, %g)" % (ke0, ke_before))
    if abs(ep0 / 0.5 - 1) > 0.01:
        fail("potential energy at the impact %g, expected 0.5" % ep0)
    if not t0 < s["t_arrest"] <= t0 + 8:
        fail("arrest time %g outside (%g, %g]" % (s["t_arrest"], t0, t0 + 8))
    if not fit < s["runout_over_ri"] < 6 - 1 - 0.1:
        fail("run-out %g not between the collapse fit %g and the box end" % (s["runout_over_ri"], fit))
    if not abs(imbalance) <= 0.1:
        fail("energy imbalance %.3f > 10 %%" % imbalance)
    if not s["volume_drift_max"] <= 0.02:
        fail("material volume drift %.3e > 2 %%" % s["volume_drift_max"])
    dc = os.path.join(w, "collapse")
    dz = os.path.join(w, "zero")
    run("column_collapse", box + ["-aspect_ratio", "1", "-time_final", "1", "-reinit_every", "10"], dc)
    run("column_chute", box + ["-release_height", "0", "-time_final", "1"], dz)
    sc, sz = summary(dc), summary(dz)
    for k in ("front", "kinetic_energy", "steps"):
        if abs(sc[k] - sz[k]) > 1e-10 * max(1.0, abs(sc[k])):
            fail("-release_height 0 differs from column_collapse in %s: %r vs %r" % (k, sz[k], sc[k]))


def test_chupin_walls():
    """(slow, about 6 minutes) The Drucker-Prager column of Chupin, Dubois &
    Phan, 0.20 x 0.14 m, tan 24 deg grains, on the rough (tan 24 deg) and the
    smooth (tan 17 deg) floor, each run to arrest (mean shear rate < 0.2 1/s,
    root-found). Checks: (1) both arrest within the scene's 2 s; (2) the
    smooth floor spreads further than the rough one (the end of the layer at
    least 5 % of h_i thick: the zero contour ends in a sub-cell film); (3) on each, the
    deposit's mean slope between 10 % and 90 % of the axis height is below
    the grains' friction tan 24 deg (a Drucker-Prager heap at rest cannot be
    steeper) and positive; (4) volume drift <= 2 %. The slides give no
    numbers, so this checks the physics' ordering, not an agreement."""
    out = {}
    for wall in ("rough", "smooth"):
        d = work("chupin_" + wall)
        run("chupin_column", ["-wall", wall, "-arrest_stop", "first", "-output_fields", "0"], d)
        s = summary(d)
        with open(os.path.join(d, "deposit.csv")) as f:
            dep = [(float(r["x"]), float(r["height"])) for r in csv.DictReader(f)]
        h0 = dep[0][1]
        x90 = next(x for x, h in dep if h <= 0.9 * h0)
        x10 = next(x for x, h in dep if h <= 0.1 * h0)
        slope = 0.8 * h0 / (x10 - x90)
        out[wall] = (s, slope)
        print("chupin_column 0.20 x 0.14 m, %s floor: arrest at t = %.3f s, front %.4f m (layer >= 5 %% h_i thick: %.4f m), axis height %.4f m, mean slope %.3f (tan 24 deg = %.3f), "
              "volume drift %.2e, %d steps, %.1f s" % (wall, s["t_arrest"], s["front"], s["front_thick"], s["height_axis"], slope, math.tan(math.radians(24)), s["volume_drift_max"], s["steps"], s["wall_time"]))
        if not 0 < s["t_arrest"] <= 2.0:
            fail("%s floor: no arrest within 2 s (t_arrest %g)" % (wall, s["t_arrest"]))
        if not 0 < slope < math.tan(math.radians(24)):
            fail("%s floor: deposit slope %.3f not in (0, tan 24 deg)" % (wall, slope))
        if not s["volume_drift_max"] <= 0.02:
            fail("%s floor: volume drift %.3e > 2 %%" % (wall, s["volume_drift_max"]))
    if not out["smooth"][0]["front_thick"] > out["rough"][0]["front_thick"]:
        fail("the smooth floor's front %.4f does not pass the rough floor's %.4f" % (out["smooth"][0]["front_thick"], out["rough"][0]["front_thick"]))


def test_chupin_lithostatic():
    """The lithostatic (PL) column of Chupin, Dubois & Phan, yield stress
    mu_f rho g (H - y), 0.20 x 0.14 m, on cells of 0.028 m (about 2 min). With
    H fixed at the initial height (pl_fixed) the yield stress at
    the base of the column, mu_f rho g h_i, holds it: the front stays within
    1 % of r_i and the kinetic energy below 1e-3 J/m. With H the current
    surface height above each point, handed to the kernels after every step
    (pl), the material beside the column carries no overburden and the
    column fails at its foot: the front advances by more than 0.04 m by
    t = 0.5 s. Run on to t = 1 s, pl must slow down: the kinetic energy at
    t = 1 s below half its value at t = 0.5 s, and its energy budget to
    t = 1 s must close to 10 % once the potential energy that the
    redistancing and the volume correction added (interface.csv, summary.csv)
    is counted. The dissipation is the run's own total over its steps
    (series.csv "dissipated": material, air and the floor's Coulomb
    friction); its parts integrated over the outputs must be positive and
    add up to it within 3 %. Measured: imbalance -8.2 % with the added
    energy (-11.2 % with the material's dissipation over the outputs
    alone), +97 % without it; the floor took 0.125 J/m, the air 2.4e-3.
    interface.csv and summary.csv must agree on the added energy, and 2
    ranks must give 1 rank's tallies and energy dissipated (material, air,
    floor) to 1e-8 (to t = 0.5 s). (Before the scene took the
    skew convective form, the nearly inviscid air gained energy until IDA
    failed at t = 0.85 s.) Volume
    drift <= 2 % in all. The pl run to t = 0.5 s on 2 ranks (the surface is
    gathered from both) takes the same steps and gives the same front and
    kinetic energy to 1e-8 (to t = 1 s the step sequences part: 2720 steps on
    1 rank, 2709 on 2, kinetic energy 8.1e-2 and 8.6e-2). This checks that
    the surface feed reaches the yield stress and changes the dynamics, not an agreement with the slides (figures only)."""
    out = {}
    for plast, tf in (("pl_fixed", "0.5"), ("pl", "0.5"), ("pl_long", "1.0")):
        d = work("chupin_" + plast)
        run("chupin_column", ["-plasticity", plast[:2] if plast == "pl_long" else plast, "-cell_size", "0.028", "-time_final", tf, "-output_fields", "0"], d)
        s = summary(d)
        s["ke_half"] = [r["kinetic_energy"] for r in series(d) if abs(r["t"] - 0.5) < 1e-9][0]
        s["dir"] = d
        out[plast] = s
        print("chupin_column -plasticity %s, cells 0.028 m: front %.4f m at t = %s s (r_i 0.20), axis height %.4f m, kinetic energy %.3e J/m (%.3e at t = 0.5 s), volume drift %.2e, %d steps, %.1f s"
              % (plast, s["front"], tf, s["height_axis"], s["kinetic_energy"], s["ke_half"], s["volume_drift_max"], s["steps"], s["wall_time"]))
        if not s["volume_drift_max"] <= 0.02:
            fail("%s: volume drift %.3e > 2 %%" % (plast, s["volume_drift_max"]))
    f = out["pl_fixed"]
    if not (f["front"] <= 0.202 and f["kinetic_energy"] < 1e-3):
        fail("pl_fixed: the column moved (front %.4f m > 0.202 m or kinetic energy %.3e >= 1e-3 J/m)" % (f["front"], f["kinetic_energy"]))
    if not out["pl"]["front"] > 0.24:
        fail("pl: the front %.4f m did not advance by 0.04 m from r_i = 0.20 m" % out["pl"]["front"])
    p = out["pl_long"]
    if not p["kinetic_energy"] < 0.5 * p["ke_half"]:
        fail("pl: the kinetic energy at t = 1 s, %.3e J/m, is not below half its value at t = 0.5 s, %.3e" % (p["kinetic_energy"], p["ke_half"]))
    b = energy_budget(p["dir"])
    print("pl to t = 1 s: released %.4f J/m, dissipated %.4f (over the outputs: material %.4f, air %.3e, floor %.4f), kinetic %.4f, added by the redistancing %.4f and by the volume correction %.4f; imbalance %+.3f with them, %+.3f without"
          % (b["released"], b["dissipated"], b["material"], b["ambient"], b["wall"], b["kinetic"], b["reinit"], b["correction"], b["imbalance"], (b["dissipated"] + b["kinetic"] - b["released"]) / b["released"]))
    parts = b["material"] + b["ambient"] + b["wall"]
    if not (b["wall"] > 0 and b["ambient"] >= 0):
        fail("pl: the floor's friction dissipated %.3e J/m and the air %.3e (both must be positive)" % (b["wall"], b["ambient"]))
    if not abs(b["dissipated"] - parts) <= 0.03 * b["dissipated"]:
        fail("pl: the dissipation summed over the steps, %.4f J/m, and its parts integrated over the outputs, %.4f, differ by more than 3 %%" % (b["dissipated"], parts))
    if abs(b["reinit"] + b["correction"] - p["energy_reinit"] - p["energy_correction"]) > 1e-9 * abs(b["added"]):
        fail("pl: the energy added in interface.csv (%.6e) differs from summary.csv's (%.6e)" % (b["added"], p["energy_reinit"] + p["energy_correction"]))
    if not abs(b["imbalance"]) <= 0.10:
        fail("pl: with the energy the between-step actions added, the budget is off by %+.3f of the energy put in (> 10 %%)" % b["imbalance"])
    d = work("chupin_pl_np2")
    run("chupin_column", ["-plasticity", "pl", "-cell_size", "0.028", "-time_final", "0.5", "-output_fields", "0"], d, ranks=2)
    s1, s2 = out["pl"], summary(d)
    print("pl on 2 ranks: %d steps (1 rank: %d), front %.10f (%.10f), kinetic energy %.10e (%.10e)" % (s2["steps"], s1["steps"], s2["front"], s1["front"], s2["kinetic_energy"], s1["kinetic_energy"]))
    if s2["steps"] != s1["steps"] or abs(s2["front"] - s1["front"]) > 1e-8 * s1["front"] or abs(s2["kinetic_energy"] - s1["kinetic_energy"]) > 1e-8 * s1["kinetic_energy"]:
        fail("pl: 2 ranks differ from 1 rank")
    last1, last2 = series(s1["dir"])[-1], series(d)[-1]
    for k in ("dissipated", "dissipation_wall", "dissipation_ambient"):
        s1[k], s2[k] = last1[k], last2[k]
    for k in ("energy_reinit", "energy_correction", "dissipated", "dissipation_wall", "dissipation_ambient"):
        print("pl %s: %.10e on 2 ranks, %.10e on 1" % (k, s2[k], s1[k]))
        if abs(s2[k] - s1[k]) > 1e-8 * abs(s1[k]):
            fail("pl: %s differs between 2 ranks and 1 rank" % k)


def test_chupin_lithostatic_arrest():
    """The lithostatic (pl) column on the scene's own mesh (cells of h_i/10,
    54 x 13) runs to arrest by the mean-shear-rate criterion (0.2 1/s):
    arrest before t = 2 s, volume drift <= 2 %, a front past 0.30 m, and an
    energy budget that closes: the energy put in, the potential energy
    released plus what the redistancing and the volume correction added,
    equals the energy dissipated (material, air, floor friction; summed
    over the steps) plus the kinetic energy left to 10 % of the energy put
    in. Measured: arrest at 0.907 s, 6.005 J/m released, 0.797 J/m added,
    6.652 J/m dissipated (floor 0.247, air 0.006), imbalance -2.2 % (-5.8 %
    before the floor and the air were counted). About 7 to 15 minutes:
    label slow."""
    d = work("chupin_pl_arrest")
    run("chupin_column", ["-plasticity", "pl", "-time_final", "2.0", "-arrest_stop", "first", "-output_fields", "0"], d)
    s, b = summary(d), energy_budget(d)
    imb = b["imbalance"]
    print("chupin_column -plasticity pl, 54 x 13: arrest at t = %.4f, front %.4f m, axis height %.4f m, volume drift %.2e, energy released %.3f J/m, added %.3f, dissipated %.3f, kinetic %.2e, imbalance %+.3f, %d steps, %.0f s"
          % (s["t_arrest"], s["front"], s["height_axis"], s["volume_drift_max"], b["released"], b["added"], b["dissipated"], b["kinetic"], imb, s["steps"], s["wall_time"]))
    if not 0 < s["t_arrest"] < 2.0:
        fail("pl: no arrest before t = 2 s")
    if not s["volume_drift_max"] <= 0.02:
        fail("pl: volume drift %.3e > 2 %%" % s["volume_drift_max"])
    if not s["front"] > 0.30:
        fail("pl: front %.4f m not past 0.30 m" % s["front"])
    if not abs(imb) <= 0.10:
        fail("pl: energy imbalance %+.3f of the energy put in > 10 %%" % imb)


def test_plot_collapse_compare():
    """cases/plot_collapse.py --compare on two hand-made runs of a unit
    column (r_i = h_i = 1): deposits h = 1 - x/2 on [0, 2] and 1 - x/3 on
    [0, 3], sampled on different grids. Their difference is x/6 up to x = 2
    and 1 - x/3 beyond, so the largest |dh| is 1/3 (at x = 2) and the L1
    difference 1/3 + 1/6 = 1/2 of the first deposit's area 1; the thick
    fronts (h >= 5 % h_i) are the last such samples, 1.5 and 2.25. Both
    are asserted to 1e-4. Also: a --compare directory without a deposit, or
    with another column, stops the script with one error line, a non-zero
    exit and nothing written."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "plot_collapse.py")
    base = work("plot_collapse_compare")

    def fake_run(name, xs, slope, width=1.0):
        d = os.path.join(base, name)
        os.makedirs(d)
        with open(os.path.join(d, "summary.csv"), "w") as f:
            f.write("scene,cells,column_width,column_height,t_final\nbingham_dam_break,10,%r,1.0,5\n" % width)
        with open(os.path.join(d, "interface.csv"), "w") as f:
            f.write("t,x_max,height_at_0\n0,1,1\n5,%r,1\n" % xs[-1])
        with open(os.path.join(d, "series.csv"), "w") as f:
            f.write("t,kinetic_energy,potential_energy,dissipation\n0,0,0.5,0\n5,0,0.4,0.02\n")
        with open(os.path.join(d, "deposit.csv"), "w") as f:
            f.write("x,height\n" + "".join("%r,%r\n" % (x, max(0.0, 1 - x / slope)) for x in xs))
        return d

    a = fake_run("a", [0.5 * k for k in range(5)], 2.0)
    b = fake_run("b", [0.75 * k for k in range(5)], 3.0)
    p = subprocess.run([sys.executable, script, a, "--label", "A", "--compare", b, "--compare-label", "B"], capture_output=True, text=True)
    if p.returncode != 0:
        fail("plot_collapse.py --compare failed: %s%s" % (p.stdout, p.stderr))
    print(p.stdout.strip())
    line = [l for l in p.stdout.splitlines() if l.startswith("B, t = 5 ")]
    if not line:
        fail("no comparison line for B in: %s" % p.stdout)
    words = line[0].replace(",", " ").replace(";", " ").split()
    got = {"axis": float(words[words.index("height") + 1]), "front": float(words[words.index("h_i)") + 1]),
           "max": float(words[words.index("|dh|") + 1]), "l1": float(words[words.index("L1") + 1])}
    for k, v in (("axis", 1.0), ("front", 2.25), ("max", 1.0 / 3.0), ("l1", 0.5)):
        if not abs(got[k] - v) <= 1e-4:
            fail("plot_collapse.py --compare: %s = %g, expected %g" % (k, got[k], v))
    if not os.path.exists(os.path.join(a, "deposit_compare_0.dat")) or not os.path.exists(os.path.join(a, "deposit.png")):
        fail("plot_collapse.py --compare wrote no deposit_compare_0.dat or deposit.png")
    c = fake_run("c", [0.5 * k for k in range(5)], 2.0, width=2.0)
    os.remove(os.path.join(b, "deposit.csv"))
    for other, what in ((b, "no deposit.csv"), (c, "its column is")):
        p = subprocess.run([sys.executable, script, c if other is b else a, "--compare", other], capture_output=True, text=True)
        err = p.stderr.strip().splitlines()
        if p.returncode == 0 or len(err) != 1 or "--compare" not in err[0] or what not in err[0]:
            fail("plot_collapse.py --compare %s: expected one error line naming --compare (%s), got exit %d: %s" % (other, what, p.returncode, p.stderr))
    if os.path.exists(os.path.join(c, "front.dat")):
        fail("plot_collapse.py wrote front.dat before rejecting --compare")


def compare_ranks(name, scene, opts, keys, tol):
    """Run a scene on 1 and 2 ranks and compare the summary values `keys` to
    the relative tolerance `tol`."""
    w = work(name)
    run(scene, opts, os.path.join(w, "p1"))
    run(scene, opts, os.path.join(w, "p2"), ranks=2)
    s1, s2 = summary(os.path.join(w, "p1")), summary(os.path.join(w, "p2"))
    if s2["ranks"] != 2:
        fail("expected a 2-rank run, summary says %s" % s2["ranks"])
    for k in keys:
        rel = abs(s1[k] - s2[k]) / max(abs(s1[k]), 1e-300)
        print("%-26s 1 rank %.12e  2 ranks %.12e  rel diff %.1e" % (k, s1[k], s2[k], rel))
        if not rel <= tol:
            fail("%s: 1 and 2 ranks expected equal to %g relative, got %g" % (k, tol, rel))


def test_axisymmetric_mms():
    """The axisymmetric operator with every hoop term active: a manufactured
    axisymmetric Stokes flow (mms_stokes -geometry axisymmetric, stream
    function r^2 cos(pi r) sin(pi z), u_r/r != 0) on 8, 16, 32 cells a side.
    Taylor-Hood orders in the r-weighted L2 norm: velocity >= 2.9 (measured
    3.01, 3.00), pressure >= 1.9 (measured 2.64, 2.30)."""
    eu, ep, ou, op, _ = mms_orders("axisymmetric_mms", ["-geometry", "axisymmetric"])
    print("velocity L2 errors %s orders %s; pressure L2 errors %s orders %s" % (eu, ou, ep, op))
    if min(ou) < 2.9 or min(op) < 1.9:
        fail("axisymmetric MMS: orders expected >= 2.9 (velocity) and >= 1.9 (pressure), got %s and %s" % (ou, op))


def test_axisymmetric_pipe():
    """The axisymmetric geometry (-geometry axisymmetric: hoop strain u_r/r,
    weight r in every integral) on the pipe of radius 1 (poiseuille, r = y).
    (1) Newtonian: the parabola G (R^2 - r^2)/(4 eta) lies in P2, so the
    solution is exact to 1e-10 relative on 8 cells across, and the flow rate
    per radian int u r dr is R^4 G/(16 eta) = 1/16 to 1e-10.
    (2) Bingham (Papanastasiou m = 1e5), plug radius r0 = 2 tau0/G = 0.3
    (Buckingham-Reiner): relative L2 errors (r-weighted) on 8, 16, 32 cells
    across fall at an observed order >= 2 from 8 to 16 (measured 2.6) and to
    <= 1e-4 on 32 (measured 3.6e-5, where m's own error is near); the flow
    rate within 1e-4 of Buckingham-Reiner's (measured 8e-6); the plug radius
    from the yielded volume within one cell of 0.3.
    (3) The exact method (-method exact, ALG2 with the hoop entry of the
    strain rate at the quadrature points), 32 cells: relative L2 error and
    flow rate within 1e-4 (measured 3.2e-5 and 1.1e-5).
    (4) Herschel-Bulkley n = 0.5, 32 cells: relative L2 error <= 1e-3 and the
    flow rate within 1e-3 of the exact profile's."""
    w = work("axisymmetric_pipe")
    d = os.path.join(w, "newtonian")
    run("poiseuille", ["-geometry", "axisymmetric", "-rheology_type", "newtonian", "-mesh_ny", "8", "-output_fields", "0"], d)
    s = summary(d)
    rel, q = s["err_u_l2"] / s["norm_u_l2"], s["flow_rate"]
    print("Newtonian pipe: relative L2 error %.2e, flow rate %.15f (exact 1/16)" % (rel, q))
    if not rel <= 1e-10 or not abs(q - 1.0 / 16) <= 1e-10 / 16:
        fail("Newtonian pipe expected exact to 1e-10: error %g, flow rate %.15g" % (rel, q))
    errs = []
    for n in (8, 16, 32):
        d = os.path.join(w, "bingham%d" % n)
        run("poiseuille", ["-geometry", "axisymmetric", "-rheology_papanastasiou_m", "1e5", "-mesh_ny", str(n), "-output_fields", "0"], d)
        s = summary(d)
        e = s["err_u_l2"] / s["norm_u_l2"]
        errs.append(e)
        dq = abs(s["flow_rate"] / s["flow_rate_exact"] - 1)
        print("Bingham pipe, %2d cells: relative L2 error %.3e, flow rate %.7f (exact %.7f, rel %.1e), plug radius %.4f (exact %.4f)"
              % (n, e, s["flow_rate"], s["flow_rate_exact"], dq, s["plug_radius"], s["plug_radius_exact"]))
        if n == 32:
            if not e <= 1e-4:
                fail("Bingham pipe on 32 cells: relative error expected <= 1e-4, got %g" % e)
            if not dq <= 1e-4:
                fail("Bingham pipe flow rate expected within 1e-4 of Buckingham-Reiner, got %g" % dq)
        if not abs(s["plug_radius"] - s["plug_radius_exact"]) <= 1.0 / n:
            fail("plug radius on %d cells expected within one cell of %g, got %g" % (n, s["plug_radius_exact"], s["plug_radius"]))
    o = order(errs[0], errs[1])
    print("observed order 8 -> 16: %.2f" % o)
    if not o >= 2.0:
        fail("Bingham pipe: observed order expected >= 2, got %g" % o)
    d = os.path.join(w, "exact")
    run("poiseuille", ["-geometry", "axisymmetric", "-method", "exact", "-mesh_ny", "32", "-output_fields", "0"], d)
    s = summary(d)
    e, dq = s["err_u_l2"] / s["norm_u_l2"], abs(s["flow_rate"] / s["flow_rate_exact"] - 1)
    print("Bingham pipe, exact method (ALG2), 32 cells: relative L2 error %.3e, flow rate rel %.1e" % (e, dq))
    if not e <= 1e-4 or not dq <= 1e-4:
        fail("exact method on the pipe: error %g and flow-rate difference %g expected <= 1e-4" % (e, dq))
    d = os.path.join(w, "hb")
    run("poiseuille", ["-geometry", "axisymmetric", "-rheology_type", "hb_papanastasiou", "-rheology_hb_n", "0.5", "-rheology_papanastasiou_m", "1e6", "-steady_continuation_start", "1e2", "-mesh_ny", "32", "-output_fields", "0"], d)
    s = summary(d)
    e, dq = s["err_u_l2"] / s["norm_u_l2"], abs(s["flow_rate"] / s["flow_rate_exact"] - 1)
    print("Herschel-Bulkley n = 0.5 pipe: relative L2 error %.3e, flow rate rel %.1e" % (e, dq))
    if not e <= 1e-3 or not dq <= 1e-3:
        fail("Herschel-Bulkley pipe: error %g and flow-rate difference %g expected <= 1e-3" % (e, dq))


def test_axisymmetric_decay():
    """The decay of a Newtonian pipe flow (decay -geometry axisymmetric):
    u = J0(j1 r) exp(-j1^2 nu t), j1 = 2.40483, is an exact solution of the
    axisymmetric equations. Fixed-step BDF2 at dt 4e-3, 2e-3, 1e-3: observed
    order >= 1.9 (r-weighted relative L2 error at t = 0.1; measured 2.00),
    and adaptive IDA at rtol 1e-4 within 10 x rtol."""
    w = work("axisymmetric_decay")
    err = []
    for dt in (4e-3, 2e-3, 1e-3):
        d = os.path.join(w, "bdf2_%g" % dt)
        run("decay", ["-geometry", "axisymmetric", "-time_integrator", "bdf2", "-time_dt", str(dt), "-output_fields", "0"], d)
        s = summary(d)
        err.append(s["err_u_l2"] / s["norm_u_l2"])
    o = [order(err[i], err[i + 1]) for i in range(2)]
    print("pipe decay, BDF2: relative errors %s, orders %s" % (err, o))
    if min(o) < 1.9:
        fail("pipe decay: BDF2 order expected >= 1.9, got %s" % o)
    d = os.path.join(w, "ida")
    run("decay", ["-geometry", "axisymmetric", "-time_rtol", "1e-4", "-time_atol", "1e-7", "-output_fields", "0"], d)
    s = summary(d)
    e = s["err_u_l2"] / s["norm_u_l2"]
    print("pipe decay, IDA rtol 1e-4: relative error %.3e (%.1f x rtol)" % (e, e / 1e-4))
    if not e <= 1e-3:
        fail("pipe decay, IDA: error expected <= 10 x rtol, got %g" % e)


def test_axisymmetric_cessation():
    """Bingham pipe cessation (poiseuille_cessation -geometry axisymmetric,
    Bn = r0/R = 0.5, 16 cells across the radius): the exact method (ALG2 per
    backward-Euler step) brackets the finite stopping time; the brackets at
    dt 1e-3 and 5e-4 overlap and are one step wide (measured (0.069, 0.070]
    and (0.069, 0.0695]). The regularised run (Papanastasiou m = 1e4, IDA)
    crosses the arrest threshold (mean shear rate 1e-3) just before the
    flow stops: between 0.97 x the exact lower bound and the exact upper
    bound (measured 0.06841, 1 % before 0.069). The first eigenvalue of the
    viscous operator on the mesh (SLEPc, -viscous_eigenvalue) is the pipe's
    j1^2 = 5.78319 to 1e-5 (measured 3e-7), and the energy bound
    T <= ln(1 + l1 ||u0||/(tau0 2 sqrt(pi)))/l1 lies above the exact stop,
    within 20 % (measured 0.0769 against 0.0695)."""
    w = work("axisymmetric_cessation")
    br = {}
    for dt in (1e-3, 5e-4):
        d = os.path.join(w, "exact_%g" % dt)
        run("poiseuille_cessation", ["-geometry", "axisymmetric", "-method", "exact", "-time_dt", str(dt), "-output_fields", "0"], d)
        s = summary(d)
        br[dt] = (s["t_stop_lower"], s["t_stop_upper"])
        print("exact, dt %g: stop in (%.5f, %.5f]" % (dt, br[dt][0], br[dt][1]))
        if not abs(br[dt][1] - br[dt][0] - dt) <= 1e-9:
            fail("dt %g: the stopping bracket is not one step wide: %s" % (dt, br[dt]))
    if not (br[5e-4][0] < br[1e-3][1] and br[1e-3][0] < br[5e-4][1]):
        fail("the stopping brackets at dt 1e-3 and 5e-4 do not overlap: %s, %s" % (br[1e-3], br[5e-4]))
    d = os.path.join(w, "regularised")
    run("poiseuille_cessation", ["-geometry", "axisymmetric", "-viscous_eigenvalue", "-output_fields", "0"], d)
    s = summary(d)
    ta = s["t_arrest"]
    lo, hi = br[5e-4]
    j1sq = 2.404825557695773 ** 2
    print("regularised m = 1e4: arrest (mean shear rate < 1e-3) at %.5f; exact stop in (%.5f, %.5f]" % (ta, lo, hi))
    print("lambda1 (SLEPc, r-weighted vector Laplacian) %.8f, j1^2 = %.8f; energy bound %.5f (SLEPc's lambda1: %.5f)" % (s["lambda1"], j1sq, s["t_stop_bound"], s["t_stop_bound_slepc"]))
    if not 0.97 * lo <= ta <= hi:
        fail("regularised arrest %g outside [0.97 x %g, %g]" % (ta, lo, hi))
    if not abs(s["lambda1"] / j1sq - 1) <= 1e-5:
        fail("lambda1 %g expected within 1e-5 of j1^2 = %g" % (s["lambda1"], j1sq))
    if not hi <= s["t_stop_bound"] <= 1.2 * hi:
        fail("energy bound %g expected between the exact stop %g and 1.2 x it" % (s["t_stop_bound"], hi))


def test_axisymmetric_parallel():
    """The Bingham pipe on 1 and 2 ranks: the same flow rate, energy, shear
    rates and error to 1e-8 relative."""
    compare_ranks("axisymmetric_parallel", "poiseuille", ["-geometry", "axisymmetric", "-rheology_papanastasiou_m", "1e4", "-output_fields", "0", "-newton_rtol", "1e-12"],
                  ("flow_rate", "kinetic_energy", "mean_shear_rate", "max_shear_rate", "err_u_l2", "plug_radius"), 1e-8)


def test_column_collapse_axisymmetric():
    """The mu(I) column collapse as a cylinder about the axis x = 0
    (column_collapse -geometry axisymmetric), a = 0.5, cells of 0.1 h_i, with
    the parameters of the thesis' 3-D collapses (Jop et al.: mu_s 0.38,
    I0 0.279; Lagree et al.'s delta_mu 0.28 and grains as in 2-D), run to
    arrest. Checks: (1) the run-out of the layer at least 5 % of h_i thick
    within 20 % of the thesis' 3-D fit 1.2 a = 0.6 (eq. 4.20) and of Lube et
    al.'s (2004) experiments 1.24 a = 0.62 (measured 0.656 at arrest, t = 5.34:
    +9 %, +6 %);
    (2) the arrest time in [3, 8]; (3) the kinetic energy at arrest below 1 %
    of its peak; (4) the volume per radian drifts by at most 2 %; (5) the
    energy budget per radian (released + added by the reinitialisations and
    corrections = dissipated + kinetic) closes to 5 % (measured -3 %). The
    height on the axis is printed, not checked: it sinks to 0.886 h_i
    where the experiments keep the top of a truncated cone at h_i
    (docs/axisymmetric.md)."""
    w = work("column_collapse_axisymmetric")
    run("column_collapse", ["-geometry", "axisymmetric", "-aspect_ratio", "0.5", "-cell_size", "0.1", "-rheology_mui_mu_s", "0.38", "-rheology_mui_I0", "0.279",
                            "-arrest_stop", "first", "-output_fields", "0"], w)
    s, ser, b = summary(w), series(w), energy_budget(w)
    ta, kmax, kend = s.get("t_arrest", -1.0), max(r["kinetic_energy"] for r in ser), ser[-1]["kinetic_energy"]
    print("axisymmetric a = 0.5: run-out %.4f (zero contour), %.4f (layer >= 5 %% h_i), thesis 3-D fit %.3f, Lube 2004 %.3f; axis height %.4f h_i; "
          "arrest at t = %.3f, KE %.2e / peak %.2e; volume drift %.2e; energy imbalance %+.3f; %d steps, %.0f s"
          % (s["runout_over_ri"], s["runout_thick_over_ri"], s["runout_fit_thesis"], s["runout_fit_lube2004"], s["height_axis_over_hi"], ta, kend, kmax,
             s["volume_drift_max"], b["imbalance"], s["steps"], s["wall_time"]))
    for ref in ("runout_fit_thesis", "runout_fit_lube2004"):
        if not abs(s["runout_thick_over_ri"] / s[ref] - 1) <= 0.2:
            fail("run-out %.4f not within 20 %% of %s = %.4f" % (s["runout_thick_over_ri"], ref, s[ref]))
    if not 3 <= ta <= 8:
        fail("arrest time %g outside [3, 8]" % ta)
    if not kend <= 0.01 * kmax:
        fail("kinetic energy at arrest %g above 1 %% of its peak %g" % (kend, kmax))
    if not abs(s["volume_drift_max"]) <= 0.02:
        fail("volume drift %g above 2 %%" % s["volume_drift_max"])
    if not abs(b["imbalance"]) <= 0.05:
        fail("energy imbalance %g above 5 %%" % b["imbalance"])


def test_collapse_axisymmetric_parallel():
    """The axisymmetric mu(I) collapse on 1 and 2 ranks, fixed-step BDF2
    (dt 5e-3, to t = 0.3, cells of 0.2 h_i, so both take the same steps):
    front, axis height, energies and shear rate agree to 1e-7 relative."""
    compare_ranks("collapse_axisymmetric_parallel", "column_collapse", ["-geometry", "axisymmetric", "-cell_size", "0.2", "-time_final", "0.3", "-time_integrator", "bdf2",
                                                                         "-time_dt", "5e-3", "-output_fields", "0"],
                  ("front", "kinetic_energy", "potential_energy", "height_axis", "mean_shear_rate"), 1e-7)


def test_exact_steady():
    """The exact method (-method exact: ALG2 on the mesh, no regularisation).
    (1) Plane Poiseuille, Bn 0.3, 32 cells across: relative L2 velocity error
    <= 3e-4 (measured 2.1e-4; the regularised m = 1e4 run gives 1.4e-4 on
    this mesh) and the plug half-width from the yielded quadrature points
    within h/4 of the exact 0.3 (h = 1/16).
    (2) Duct (Mosolov problem), 16 x 16: at Bn 0.1 the flow rate agrees with
    the regularised one at m = 1e5 to 1e-4 relative (measured 6e-6); the
    exact flow threshold Bn_c = 0.26508 is bracketed without creep: at Bn 0.28
    the velocity is zero (|Q| <= 1e-12 Q_newtonian, no yielded point) where
    the regularised model creeps, and at Bn 0.25 the duct flows (Q/Q_n >
    1e-3, yielded fraction > 0.2)."""
    w = work("exact_steady")
    d = os.path.join(w, "poiseuille")
    run("poiseuille", ["-method", "exact", "-output_fields", "0"], d)
    s = summary(d)
    rel = s["err_u_l2"] / s["norm_u_l2"]
    print("poiseuille exact: L2 error %.3e, plug half-width %.4f (exact %.4f), %d ALG2 iterations" % (rel, s["plug_half_width"], s["plug_half_width_exact"], s["newton_its"]))
    if s["regularisation"] != "exact" or s["integrator"] != "steady_exact":
        fail("summary should name the exact method, got %s / %s" % (s["regularisation"], s["integrator"]))
    if not rel <= 3e-4:
        fail("poiseuille exact: relative L2 velocity error expected <= 3e-4, got %g" % rel)
    if not abs(s["plug_half_width"] - 0.3) <= 1.0 / 64:
        fail("poiseuille exact: plug half-width expected within h/4 of 0.3, got %g" % s["plug_half_width"])
    res = {}
    for bn in (0.1, 0.25, 0.28):
        d = os.path.join(w, "duct%g" % bn)
        run("duct", ["-bn", str(bn), "-method", "exact", "-output_fields", "0"], d)
        res[bn] = summary(d)
    d = os.path.join(w, "duct_reg")
    run("duct", ["-bn", "0.1", "-rheology_papanastasiou_m", "1e5", "-steady_continuation_start", "1e2", "-output_fields", "0"], d)
    reg = summary(d)
    qn = reg["flow_rate_newtonian"]
    rel = abs(res[0.1]["flow_rate"] - reg["flow_rate"]) / reg["flow_rate"]
    print("duct Bn 0.1: exact Q %.7e, regularised (m 1e5) Q %.7e, rel diff %.1e; plug area exact %.4f, regularised %.4f" % (res[0.1]["flow_rate"], reg["flow_rate"], rel, res[0.1]["plug_area"], reg["plug_area"]))
    if not rel <= 1e-4:
        fail("duct Bn 0.1: exact and regularised flow rates expected within 1e-4, got %g" % rel)
    for bn in (0.25, 0.28):
        print("duct Bn %.2f exact: Q/Q_n %.3e, yielded fraction %.4f" % (bn, res[bn]["flow_rate"] / qn, res[bn]["yielded_fraction_exact"]))
    if not (abs(res[0.28]["flow_rate"]) <= 1e-12 * qn and res[0.28]["yielded_fraction_exact"] == 0.0):
        fail("duct Bn 0.28 > Bn_c: the exact method should give rest, got Q %g, yielded %g" % (res[0.28]["flow_rate"], res[0.28]["yielded_fraction_exact"]))
    if not (res[0.25]["flow_rate"] / qn > 1e-3 and res[0.25]["yielded_fraction_exact"] > 0.2):
        fail("duct Bn 0.25 < Bn_c: the exact method should flow, got Q/Qn %g, yielded %g" % (res[0.25]["flow_rate"] / qn, res[0.25]["yielded_fraction_exact"]))


def test_exact_cessation():
    """The exact method in time (backward Euler + ALG2 per step) on the
    Poiseuille cessation (Bn 0.5): the flow stops in finite time, and the
    stopping interval (t_n, t_{n+1}] found with dt = 4e-3 and 2e-3 lies
    within one step of the 1-D reference's stopping time t_stop_exact; the
    mean-shear-rate arrest time converges to the reference's at first order
    (observed order >= 0.8; measured errors 1.1e-3 and 5.7e-4)."""
    w = work("exact_cessation")
    errs = []
    for dt in (4e-3, 2e-3):
        d = os.path.join(w, "dt%g" % dt)
        run("poiseuille_cessation", ["-method", "exact", "-time_dt", str(dt), "-output_fields", "0"], d)
        s = summary(d)
        lo, hi, ts = s["t_stop_lower"], s["t_stop_upper"], s["t_stop_exact"]
        e = abs(s["t_arrest"] - s["t_arrest_exact"])
        errs.append(e)
        print("dt %g: stopped in (%.4f, %.4f], reference %.6f; arrest %.6f, reference %.6f (error %.2e)" % (dt, lo, hi, ts, s["t_arrest"], s["t_arrest_exact"], e))
        if s["integrator"] != "exact":
            fail("summary should name the exact integrator, got %s" % s["integrator"])
        if not (lo > 0 and hi - lo <= dt * (1 + 1e-9) and lo - dt <= ts <= hi + dt):
            fail("dt %g: stopping interval (%g, %g] not within a step of the reference %g" % (dt, lo, hi, ts))
    p = math.log(errs[0] / errs[1]) / math.log(2.0)
    print("observed order of the arrest time: %.2f" % p)
    if not p >= 0.8:
        fail("arrest time: observed order expected >= 0.8 (backward Euler), got %.2f" % p)


def test_exact_parallel():
    """The exact method on 2 ranks: the steady duct at Bn 0.1 gives the
    1-rank flow rate and yielded fraction to 1e-6 relative (ALG2 stops at
    its tolerance 1e-6; the partition changes only round-off)."""
    compare_ranks("exact_parallel", "duct", ["-bn", "0.1", "-method", "exact", "-output_fields", "0"], ("flow_rate", "yielded_fraction_exact", "kinetic_energy"), 1e-6)


# Vola, Boscardin & Latche (J. Comput. Phys. 187, 2003), Fig. 2a: the
# stream-function maximum of the creeping Bingham cavity against their yield
# stress, as digitised by the Basilisk authors (basilisk.fr, sandbox/popinet,
# file vola2003-2a). Their yield stress is sqrt(2) times ours (Basilisk's
# lid-bingham.c converts the same way); points read off a plot.
VOLA_2A = [(1.96842, 0.0824803), (5.03455, 0.0687008), (19.8627, 0.0456693)]


def test_cavity():
    """Steady lid-driven cavity (32 x 32 cells, uniform lid).
    (1) Newtonian Stokes flow: psi_max = 0.1000 within 0.5 % (measured
    0.100068; 0.100325 in Basilisk's 128 x 128 regression output) at
    (0.5, 0.765) within 0.01, and psi on the lid (which the divergence
    constraint makes 0) below 3e-3 (measured 2.1e-3, halving with h).
    (2) Bingham, Papanastasiou m = 1e4 (continuation from 1e1): psi_max
    within 2.5 % of Vola et al.'s Fig. 2a at three yield stresses (measured
    +0.2 to +0.6 %), falling with Bn while the unyielded area grows and the
    vortex centre rises."""
    w = work("cavity")
    d = os.path.join(w, "stokes")
    run("cavity", ["-bn", "0", "-output_fields", "0"], d)
    s = summary(d)
    print("Stokes cavity: psi_max %.6f at (%.4f, %.4f), psi on the lid %.2e" % (s["psi_max"], s["psi_x"], s["psi_y"], s["psi_top"]))
    if not abs(s["psi_max"] - 0.1) <= 5e-4:
        fail("Stokes cavity: psi_max expected 0.1000 within 0.5 %%, got %g" % s["psi_max"])
    if not (abs(s["psi_x"] - 0.5) <= 0.01 and abs(s["psi_y"] - 0.765) <= 0.01):
        fail("Stokes cavity: vortex centre expected at (0.5, 0.765), got (%g, %g)" % (s["psi_x"], s["psi_y"]))
    if not s["psi_top"] <= 3e-3:
        fail("Stokes cavity: psi on the lid expected <= 3e-3, got %g" % s["psi_top"])
    if not os.path.exists(os.path.join(d, "cavity_grid.csv")):
        fail("cavity_grid.csv not written")
    # Re = 100 (inertia and convection): Ghia, Ghia & Shin (1982), primary
    # vortex psi = 0.103423 at (0.6172, 0.7344)
    d = os.path.join(w, "re100")
    run("cavity", ["-bn", "0", "-re", "100", "-output_fields", "0"], d)
    s = summary(d)
    print("Re 100: psi_max %.6f at (%.4f, %.4f); Ghia et al. 0.103423 at (0.6172, 0.7344)" % (s["psi_max"], s["psi_x"], s["psi_y"]))
    if not (abs(s["psi_max"] - 0.103423) <= 5e-3 * 0.103423 and abs(s["psi_x"] - 0.6172) <= 0.01 and abs(s["psi_y"] - 0.7344) <= 0.01):
        fail("Re 100: primary vortex expected within 0.5 %% and 0.01 of Ghia et al.'s, got %g at (%g, %g)" % (s["psi_max"], s["psi_x"], s["psi_y"]))
    prev = None
    for tv, ref in VOLA_2A:
        bn = tv / math.sqrt(2.0)
        d = os.path.join(w, "bn%.4f" % bn)
        run("cavity", ["-bn", repr(bn), "-steady_continuation_start", "1e1", "-output_fields", "0"], d)
        s = summary(d)
        rel = (s["psi_max"] - ref) / ref
        print("Bn %.4f (Vola %.4f): psi_max %.6f, Vola %.6f (%+.2f %%); centre (%.3f, %.3f); unyielded area %.4f" % (bn, tv, s["psi_max"], ref, 100 * rel, s["psi_x"], s["psi_y"], s["unyielded_area"]))
        if not abs(rel) <= 0.025:
            fail("Bn %g: psi_max %g not within 2.5 %% of Vola et al.'s %g" % (bn, s["psi_max"], ref))
        if prev is not None and not (s["psi_max"] < prev["psi_max"] and s["unyielded_area"] > prev["unyielded_area"] and s["psi_y"] > prev["psi_y"]):
            fail("Bn %g: psi_max must fall, the unyielded area grow and the vortex rise with Bn" % bn)
        prev = s


def test_cavity_exact():
    """The cavity by the exact method (ALG2) at Vola et al.'s yield stress
    1.96842 (Bn 1.392): psi_max within 2.5 % of their Fig. 2a, and within
    1 % of the regularised run at m = 1e4, whose unyielded area is larger
    (the regularised criterion ||tau|| <= tau0 also holds in a creeping
    layer around the exact plug)."""
    w = work("cavity_exact")
    tv, ref = VOLA_2A[0]
    bn = repr(tv / math.sqrt(2.0))
    d = os.path.join(w, "exact")
    run("cavity", ["-bn", bn, "-method", "exact", "-output_fields", "0"], d)
    e = summary(d)
    d = os.path.join(w, "regularised")
    run("cavity", ["-bn", bn, "-steady_continuation_start", "1e1", "-output_fields", "0"], d)
    r = summary(d)
    print("exact: psi_max %.6f at (%.4f, %.4f), unyielded area %.4f, %d ALG2 iterations" % (e["psi_max"], e["psi_x"], e["psi_y"], e["unyielded_area"], e["newton_its"]))
    print("m 1e4: psi_max %.6f at (%.4f, %.4f), unyielded area %.4f; Vola %.6f" % (r["psi_max"], r["psi_x"], r["psi_y"], r["unyielded_area"], ref))
    if not abs(e["psi_max"] - ref) <= 0.025 * ref:
        fail("exact: psi_max %g not within 2.5 %% of Vola et al.'s %g" % (e["psi_max"], ref))
    if not abs(e["psi_max"] - r["psi_max"]) <= 0.01 * e["psi_max"]:
        fail("exact and regularised psi_max expected within 1 %%, got %g and %g" % (e["psi_max"], r["psi_max"]))
    if not (0 < e["unyielded_area"] < r["unyielded_area"]):
        fail("exact unyielded area expected positive and below the regularised one, got %g and %g" % (e["unyielded_area"], r["unyielded_area"]))


def test_cavity_inertia_exact():
    """The exact method with inertia and convection (ALG2 whose u-step is
    the steady Navier-Stokes problem, one Newton or chord step per
    iteration): the cavity at Re 1000, Bn 2 on 32 x 32 cells.
    (1) The regularised run (m = 1e4, the integral error of m = 1e4 is
    O(1/m) at Re 0: 3.4e-6 on psi_max, docs/exact.md) gives the same
    psi_max within 1e-4 relative (measured 1e-6) and the same vortex centre
    within 1e-3 (measured equal to 6 digits); its unyielded area is larger
    (measured 0.0484 against 0.0363).
    (2) Inertia is there: the vortex centre lies below the Re 0 centre
    (y 0.575 against 0.815 for the exact Re 0 run at Bn 2) and downstream
    of the mid-line (x 0.56 > 0.5, where Stokes flow puts it by symmetry).
    (3) 2 ranks on 16 x 16 cells give the 1-rank psi_max and kinetic energy
    to 1e-6 (ALG2's tolerance)."""
    w = work("cavity_inertia_exact")
    base = ["-re", "1000", "-bn", "2", "-output_fields", "0", "-output_yield_map", "0"]
    d = os.path.join(w, "exact")
    run("cavity", base + ["-method", "exact"], d)
    e = summary(d)
    d = os.path.join(w, "regularised")
    run("cavity", base, d)
    r = summary(d)
    print("exact: psi_max %.7f at (%.5f, %.5f), unyielded area %.4f, %d ALG2 iterations, %d factorisations, %.1f s" % (e["psi_max"], e["psi_x"], e["psi_y"], e["unyielded_area"], e["newton_its"], e["jac_evals"], e["wall_time"]))
    print("m 1e4: psi_max %.7f at (%.5f, %.5f), unyielded area %.4f, %.1f s" % (r["psi_max"], r["psi_x"], r["psi_y"], r["unyielded_area"], r["wall_time"]))
    rel = abs(e["psi_max"] - r["psi_max"]) / e["psi_max"]
    if not rel <= 1e-4:
        fail("exact and regularised psi_max expected within 1e-4 relative at Re 1000, got %g and %g (%.1e)" % (e["psi_max"], r["psi_max"], rel))
    if not (abs(e["psi_x"] - r["psi_x"]) <= 1e-3 and abs(e["psi_y"] - r["psi_y"]) <= 1e-3):
        fail("vortex centres expected within 1e-3, got (%g, %g) and (%g, %g)" % (e["psi_x"], e["psi_y"], r["psi_x"], r["psi_y"]))
    if not (0 < e["unyielded_area"] < r["unyielded_area"]):
        fail("exact unyielded area expected positive and below the regularised one, got %g and %g" % (e["unyielded_area"], r["unyielded_area"]))
    if not (e["psi_y"] < 0.7 and e["psi_x"] > 0.52):
        fail("at Re 1000 the vortex centre expected below y 0.7 and right of x 0.52, got (%g, %g)" % (e["psi_x"], e["psi_y"]))
    compare_ranks("cavity_inertia_exact_parallel", "cavity", base + ["-method", "exact", "-mesh_nx", "16", "-mesh_ny", "16"], ("psi_max", "kinetic_energy"), 1e-6)


# Botella & Peyret (Comput. Fluids 27, 1998), Table 1, Re 1000: the
# primary vortex of the Newtonian cavity by a Chebyshev method, mirrored to
# our lid moving in +x.
BOTELLA_PEYRET_RE1000 = (0.1189366, 0.5308, 0.5652)


def test_cavity_navier_stokes():
    """The steady Navier-Stokes cavity at Re 1000 (Newtonian), reached by a
    continuation in the Reynolds number (-steady_inertia_steps 4: the
    density 250, 500, 750, 1000; in one step Newton's method from rest did
    not converge on 64 x 64). Against Botella & Peyret's spectral benchmark
    psi_max 0.1189366 at (0.5308, 0.5652): on 64 x 64 cells psi_max within
    0.2 % (measured +0.05 %) and the centre within 2e-3 (measured 1e-4);
    the error falls by at least 4 from 32 x 32 (measured +0.84 % -> +0.05 %)."""
    w = work("cavity_navier_stokes")
    ref, xr, yr = BOTELLA_PEYRET_RE1000
    errs = []
    for n in ("32", "64"):
        d = os.path.join(w, n)
        run("cavity", ["-re", "1000", "-rheology_type", "newtonian", "-steady_inertia_steps", "4", "-mesh_nx", n, "-mesh_ny", n, "-output_fields", "0"], d)
        s = summary(d)
        e = (s["psi_max"] - ref) / ref
        errs.append(abs(e))
        print("%s x %s: psi_max %.7f at (%.5f, %.5f), %+.2e against Botella & Peyret's %.7f at (%.4f, %.4f); %d Newton" % (n, n, s["psi_max"], s["psi_x"], s["psi_y"], e, ref, xr, yr, s["newton_its"]))
    if not errs[1] <= 2e-3:
        fail("psi_max on 64 x 64 expected within 0.2 %% of %g, got %.2e" % (ref, errs[1]))
    if not (abs(s["psi_x"] - xr) <= 2e-3 and abs(s["psi_y"] - yr) <= 2e-3):
        fail("vortex centre on 64 x 64 expected within 2e-3 of (%g, %g), got (%g, %g)" % (xr, yr, s["psi_x"], s["psi_y"]))
    if not errs[1] * 4 <= errs[0]:
        fail("psi_max error expected to fall by >= 4 from 32 to 64 cells, got %.2e -> %.2e" % tuple(errs))


def test_four_ranks_parallel():
    """More ranks than this machine's 2 cores (oversubscribed, correctness
    only): -linear_solver iterative on 4 ranks with the METIS partition
    against 1 rank.
    (1) duct_cessation 16 x 16 (IDA, GMRES + BoomerAMG): the same number
    of steps and the arrest time within 1e-6 relative (measured equal to
    11 digits; the Krylov counts differ, 2529 and 2605).
    (2) Steady Poiseuille 8 x 32, m = 1e4 (KINSOL, Schur fieldsplit):
    kinetic energy and mean shear rate within 1e-8 relative (Krylov
    tolerance 1e-10; measured equal to 11 digits)."""
    w = work("four_ranks_parallel")
    cases = (("duct_cessation", ["-mesh_nx", "16", "-mesh_ny", "16"], (("t_arrest", 1e-6), ("steps", 0.0))),
             ("poiseuille", ["-mesh_nx", "8", "-mesh_ny", "32", "-rheology_papanastasiou_m", "1e4", "-steady_continuation_start", "1e2"], (("kinetic_energy", 1e-8), ("mean_shear_rate", 1e-8))))
    for scene, opts, keys in cases:
        res = []
        for n in (1, 4):
            d = os.path.join(w, "%s_%d" % (scene, n))
            run(scene, opts + ["-linear_solver", "iterative", "-output_fields", "0"], d, ranks=n)
            res.append(summary(d))
        if res[1]["ranks"] != 4:
            fail("expected a 4-rank run, summary says %s" % res[1]["ranks"])
        for k, tol in keys:
            rel = abs(res[0][k] - res[1][k]) / max(abs(res[0][k]), 1e-300)
            print("%-15s %-16s 1 rank %.12e  4 ranks %.12e  rel diff %.1e (Krylov %d and %d)" % (scene, k, res[0][k], res[1][k], rel, res[0]["lin_its"], res[1]["lin_its"]))
            if not rel <= tol:
                fail("%s %s: 1 and 4 ranks expected equal to %g relative, got %g" % (scene, k, tol, rel))


def test_cavity_parallel():
    """The cavity on 2 ranks (the velocity sampled across ranks): psi_max,
    its centre and the unyielded area equal the 1-rank values to 1e-8."""
    compare_ranks("cavity_parallel", "cavity", ["-bn", "2", "-steady_continuation_start", "1e1", "-output_fields", "0", "-newton_rtol", "1e-12"],
                  ("psi_max", "psi_x", "psi_y", "unyielded_area", "kinetic_energy"), 1e-8)


def test_cylinder():
    """Creeping flow past a cylinder between walls, blockage 1/2, on the
    shipped Gmsh mesh (cases/data/cylinder.msh, 3051 triangles).
    (1) Newtonian: the drag coefficient K = F/(eta U) within 0.2 % of the
    benchmark 132.358 (Alves, Pinho & Oliveira 2001; measured 132.243, and
    132.327, 132.350 on the meshes of s = 0.5, 0.25), the same for two
    cut-off radii to 1e-8 (the consistent reaction does not depend on it),
    and the mean velocity U = 1 at the outlet and through the gap above the
    cylinder within 1e-3 (mass conservation).
    (2) Bingham (Papanastasiou m = 1e4): K grows with Bn (Bn 1: 163.4,
    Bn 10: 434.5)."""
    w = work("cylinder")
    ks = []
    for cut in ("1.2", "1.8"):
        d = os.path.join(w, "newtonian_%s" % cut)
        run("cylinder", ["-rheology_type", "newtonian", "-cylinder_cutoff", cut, "-output_fields", "0"], d)
        s = summary(d)
        ks.append(s["drag_coefficient"])
        print("Newtonian, cut-off %s R: K = %.6f (benchmark 132.358); mean velocity outlet %.6f, gap %.6f" % (cut, s["drag_coefficient"], s["outlet_mean_velocity"], s["gap_mean_velocity"]))
        if not (abs(s["outlet_mean_velocity"] - 1) <= 1e-3 and abs(s["gap_mean_velocity"] - 1) <= 1e-3):
            fail("mean velocities expected 1 within 1e-3, got %g and %g" % (s["outlet_mean_velocity"], s["gap_mean_velocity"]))
    if not abs(ks[0] - 132.358) <= 0.002 * 132.358:
        fail("Newtonian K expected within 0.2 %% of 132.358, got %g" % ks[0])
    if not abs(ks[0] - ks[1]) <= 1e-8 * ks[0]:
        fail("K should not depend on the cut-off: %g and %g" % tuple(ks))
    prev = ks[0]
    for bn in ("1", "10"):
        d = os.path.join(w, "bn" + bn)
        run("cylinder", ["-bn", bn, "-steady_continuation_start", "1e1", "-output_fields", "0", "-output_yield_map", "0"], d)
        s = summary(d)
        print("Bn %s: K = %.4f" % (bn, s["drag_coefficient"]))
        if not s["drag_coefficient"] > prev * 1.1:
            fail("K expected to grow with Bn: %g after %g" % (s["drag_coefficient"], prev))
        prev = s["drag_coefficient"]


def test_cylinder_exact():
    """The cylinder at Bn 1 by the exact method (ALG2): its drag agrees with
    the regularised run (m = 1e4) to 1e-4 relative (measured 163.423 and
    163.422), and the unyielded zones (the channel's central plug up- and
    downstream, |x| > 3 R; no plug at the poles at this Bn) cover 5 to 40 %
    of the domain (measured 16.5 %)."""
    w = work("cylinder_exact")
    d = os.path.join(w, "exact")
    run("cylinder", ["-bn", "1", "-method", "exact", "-output_fields", "0"], d)
    e = summary(d)
    d = os.path.join(w, "regularised")
    run("cylinder", ["-bn", "1", "-steady_continuation_start", "1e1", "-output_fields", "0"], d)
    r = summary(d)
    rel = abs(e["drag_coefficient"] - r["drag_coefficient"]) / e["drag_coefficient"]
    print("Bn 1: K exact %.5f, regularised %.5f (rel diff %.1e); unyielded fraction (exact) %.4f" % (e["drag_coefficient"], r["drag_coefficient"], rel, 1 - e["yielded_fraction_exact"]))
    if not rel <= 1e-4:
        fail("exact and regularised drag expected within 1e-4, got %g" % rel)
    if not 0.05 <= 1 - e["yielded_fraction_exact"] <= 0.4:
        fail("unyielded fraction expected in [0.05, 0.4], got %g" % (1 - e["yielded_fraction_exact"]))


def test_cylinder_unbounded():
    """The Bingham cylinder in a uniform stream (-cylinder_domain unbounded,
    box 90 R x 60 R, cases/data/cylinder_unbounded.msh, 3486 triangles),
    Papanastasiou m = 1e4, Oldroyd numbers Od = tau0 D/(eta U) = 100, 1000,
    1e4. The plastic drag coefficient Cd* = F/(tau0 D) tends, as Od grows,
    to the limit load of a rough cylinder in a perfectly plastic medium,
    2 pi + 4 sqrt 2 = 11.9389 (Randolph & Houlsby 1984; Tokpavi, Magnin & Jay
    2008 recover it). Checked: Cd* decreases with Od and stays above the
    limit (the upper-bound theorem: the viscous part only adds dissipation);
    Od 1e4 within 2 % of it (measured 12.1015, +1.4 %); the Aitken
    extrapolation of the three values within 1.5 % (measured 12.069,
    +1.1 %; on the mesh of s = 0.5, 13846 triangles: 12.0453 at Od 1e4 and
    11.986 extrapolated, +0.4 %); m = 1e5 changes Cd* at Od 1000 by less
    than 1e-4 relative (measured 1.5e-5)."""
    w = work("cylinder_unbounded")
    limit = 2 * math.pi + 4 * math.sqrt(2)
    cds = []
    for od, extra in (("100", []), ("1000", []), ("1e4", ["-steady_continuation_factor", "3", "-newton_max_it", "100"])):
        d = os.path.join(w, "od" + od)
        run("cylinder", ["-cylinder_domain", "unbounded", "-bn", "%g" % (float(od) / 2), "-steady_continuation_start", "1e1", "-output_fields", "0", "-output_yield_map", "0"] + extra, d)
        s = summary(d)
        if not abs(s["oldroyd"] - float(od)) <= 1e-9 * float(od):
            fail("Oldroyd number expected %s, summary says %g" % (od, s["oldroyd"]))
        if not abs(s["drag_plastic_limit"] - limit) <= 1e-9 * limit:
            fail("drag_plastic_limit expected %.12g, got %.12g" % (limit, s["drag_plastic_limit"]))
        cds.append(s["drag_plastic"])
        print("Od %s: Cd* = %.5f (%+.2f %% of the plastic limit %.5f)" % (od, cds[-1], 100 * (cds[-1] / limit - 1), limit))
    for a, b in zip(cds, cds[1:]):
        if not b < a:
            fail("Cd* expected to decrease with Od: %s" % cds)
    if not min(cds) > limit:
        fail("Cd* expected above the plastic limit load %g (upper bound), got %s" % (limit, cds))
    if not cds[-1] <= 1.02 * limit:
        fail("Cd* at Od 1e4 expected within 2 %% of %g, got %g" % (limit, cds[-1]))
    ext = (cds[0] * cds[2] - cds[1] ** 2) / (cds[0] + cds[2] - 2 * cds[1])
    print("extrapolated Cd*(Od -> infinity) = %.4f (%+.2f %%)" % (ext, 100 * (ext / limit - 1)))
    if not abs(ext / limit - 1) <= 0.015:
        fail("extrapolated Cd* expected within 1.5 %% of %g, got %g" % (limit, ext))
    d = os.path.join(w, "od1000_m1e5")
    run("cylinder", ["-cylinder_domain", "unbounded", "-bn", "500", "-rheology_papanastasiou_m", "1e5", "-steady_continuation_start", "1e1", "-output_fields", "0", "-output_yield_map", "0"], d)
    c5 = summary(d)["drag_plastic"]
    rel = abs(c5 - cds[1]) / cds[1]
    print("Od 1000: Cd* m = 1e4 %.6f, m = 1e5 %.6f (rel diff %.1e)" % (cds[1], c5, rel))
    if not rel <= 1e-4:
        fail("Cd* at m = 1e4 and 1e5 expected within 1e-4, got %g" % rel)


def test_granular_cylinder():
    """The mu(I) chute flow over a cylinder of Chauchat & Medale (2014, sec.
    4.2) in the plane (granular_cylinder: channel 20 D x 30 D, D = 10 d, rough
    walls, confining pressure p_ext at both ends, mui_cm with mu_s 0.4,
    dmu 0.25, I0 0.3, inertia on; cases/data/granular_cylinder.msh).
    (1) The creeping regime below the onset is the regularisation's: at load
    F = 0.03 the mean velocity scales with lambda_r (1e-3 against 1e-4:
    ratio 10 within 1 %, measured 9.992) while the drag does not (within
    0.5 %, measured 0.11 %).
    (2) At their F = 0.054 the material flows: the Froude number is at least
    100 times the creeping one at the same lambda_r (measured 0.597 against
    0.00111), and the flow rates through both ends agree to 1e-9.
    (3) The similarity of mu(I): p_ext -> 10 p_ext with lambda_r -> sqrt(10)
    lambda_r and the pressure regularisation -> 10 d leaves F_D/(p_ext D),
    the Froude number and the cylinder's share of the weight unchanged to
    1e-6 and multiplies the flow rate by sqrt(10) to 1e-6.
    (4) At fixed lambda_r = 1e-4, F_D/(p_ext D) at p_ext = 1000 is within
    1 % of its value at 100 (measured 6.1116 and 6.0996): the drag is linear
    in the confining pressure, the collapse of their Fig. 12."""
    w = work("granular_cylinder")

    def gc(name, opts):
        d = os.path.join(w, name)
        run("granular_cylinder", opts + ["-output_fields", "0", "-output_yield_map", "0"], d)
        return summary(d)

    c3 = gc("creep_lr1e-3", ["-granular_cylinder_load", "0.03", "-rheology_mui_lambda_r", "1e-3"])
    c4 = gc("creep_lr1e-4", ["-granular_cylinder_load", "0.03"])
    ru = c3["mean_velocity"] / c4["mean_velocity"]
    rd = abs(c3["drag_over_pressure"] / c4["drag_over_pressure"] - 1)
    print("F 0.03: U %.6g (lambda_r 1e-3), %.6g (1e-4), ratio %.4f; F_D/(p D) %.5f and %.5f (rel diff %.1e)" % (c3["mean_velocity"], c4["mean_velocity"], ru, c3["drag_over_pressure"], c4["drag_over_pressure"], rd))
    if not abs(ru / 10 - 1) <= 0.01:
        fail("creeping velocity expected proportional to lambda_r (ratio 10 within 1 %%), got %g" % ru)
    if not rd <= 0.005:
        fail("creeping drag expected independent of lambda_r within 0.5 %%, got %g" % rd)
    a = gc("p100", [])
    print("F 0.054, p 100: U %.6g, Fr %.6g, F_D/(p D) %.6f, weight share %.4f, Q %.6g" % (a["mean_velocity"], a["froude"], a["drag_over_pressure"], a["drag_weight_fraction"], a["flow_rate"]))
    if not a["froude"] >= 100 * c4["froude"]:
        fail("F 0.054 expected flowing (Fr >= 100 x the creeping %g), got %g" % (c4["froude"], a["froude"]))
    if not a["flow_rate_ends_difference"] <= 1e-9 * a["flow_rate"]:
        fail("flow rates through both ends expected equal to 1e-9, differ by %g" % a["flow_rate_ends_difference"])
    b = gc("p1000_similar", ["-granular_cylinder_pressure", "1000", "-rheology_mui_lambda_r", repr(1e-4 * math.sqrt(10)), "-rheology_pressure_reg", "1e-3"])
    for k in ("drag_over_pressure", "froude", "drag_weight_fraction"):
        rel = abs(b[k] / a[k] - 1)
        print("similarity: %-20s p 100 %.9g  p 1000 %.9g  rel diff %.1e" % (k, a[k], b[k], rel))
        if not rel <= 1e-6:
            fail("similarity: %s expected unchanged to 1e-6, got %g" % (k, rel))
    rq = b["flow_rate"] / a["flow_rate"] / math.sqrt(10)
    print("similarity: Q(1000)/Q(100)/sqrt(10) = %.9f" % rq)
    if not abs(rq - 1) <= 1e-6:
        fail("similarity: flow rate expected to scale with sqrt(10) to 1e-6, got %g" % rq)
    c = gc("p1000", ["-granular_cylinder_pressure", "1000"])
    rel = abs(c["drag_over_pressure"] / a["drag_over_pressure"] - 1)
    print("fixed lambda_r 1e-4: F_D/(p D) %.5f (p 100), %.5f (p 1000), rel diff %.1e; Fr %.4f and %.4f" % (a["drag_over_pressure"], c["drag_over_pressure"], rel, a["froude"], c["froude"]))
    if not rel <= 0.01:
        fail("F_D/(p D) expected within 1 %% at p 100 and 1000, got %g" % rel)


def test_granular_cylinder_parallel():
    """granular_cylinder on 2 ranks (METIS partition), creeping regime at
    F = 0.03: flow rate and drag equal the 1-rank values to 1e-8."""
    compare_ranks("granular_cylinder_parallel", "granular_cylinder", ["-granular_cylinder_load", "0.03", "-output_fields", "0", "-output_yield_map", "0"], ("flow_rate", "drag"), 1e-8)


def test_cylinder_parallel():
    """The cylinder on 2 ranks (METIS partition of the Gmsh mesh): the
    Newtonian drag coefficient equals the 1-rank value to 1e-9."""
    compare_ranks("cylinder_parallel", "cylinder", ["-rheology_type", "newtonian", "-output_fields", "0"], ("drag_coefficient", "kinetic_energy"), 1e-9)
    # the unbounded domain at Od 100 (Bingham, m = 1e4, continuation from m = 10)
    compare_ranks("cylinder_parallel_unbounded", "cylinder", ["-cylinder_domain", "unbounded", "-bn", "50", "-steady_continuation_start", "1e1", "-output_fields", "0", "-output_yield_map", "0"], ("drag_plastic", "kinetic_energy"), 1e-8)


def test_expansion():
    """Planar 1:2 sudden expansion on the shipped Gmsh mesh.
    (1) Newtonian: the flow 20 h downstream is the developed parabola of
    mean velocity U/2 (relative L2 difference <= 1e-6; P2 holds it exactly,
    measured 1e-15), with mean velocity 0.5 within 1e-4.
    (2) Bingham (Papanastasiou m = 1e4): the developed Bingham profile
    downstream within 2 % (measured 0.5 % at Bn 1, 0.8 % at Bn 5), mass
    conserved to 1e-3, and the corner's stagnant area (|u| < 1e-3 U in
    0 <= x <= 4h, h <= y <= 2h) growing with Bn: Newtonian 0.093, Bn 1
    0.346, Bn 5 0.481 (the dead zone fills the corner)."""
    w = work("expansion")
    d = os.path.join(w, "newtonian")
    run("expansion", ["-rheology_type", "newtonian", "-output_fields", "0"], d)
    s = summary(d)
    print("Newtonian: downstream profile error %.2e, mean %.6f, corner stagnant area %.4f" % (s["downstream_profile_error"], s["downstream_mean_velocity"], s["corner_stagnant_area"]))
    if not (s["downstream_profile_error"] <= 1e-6 and abs(s["downstream_mean_velocity"] - 0.5) <= 1e-4):
        fail("Newtonian: developed flow downstream expected exact, got error %g, mean %g" % (s["downstream_profile_error"], s["downstream_mean_velocity"]))
    prev = s["corner_stagnant_area"]
    for bn in ("1", "5"):
        d = os.path.join(w, "bn" + bn)
        run("expansion", ["-bn", bn, "-steady_continuation_start", "1e1", "-output_fields", "0", "-output_yield_map", "0"], d)
        s = summary(d)
        print("Bn %s: downstream profile error %.2e (plug half-width up/down %.3f / %.3f), mean %.5f, corner stagnant area %.4f" % (bn, s["downstream_profile_error"], s["upstream_plug_exact"], s["downstream_plug_exact"], s["downstream_mean_velocity"], s["corner_stagnant_area"]))
        if not (s["downstream_profile_error"] <= 0.02 and abs(s["downstream_mean_velocity"] - 0.5) <= 1e-3):
            fail("Bn %s: developed Bingham flow downstream expected within 2 %%, got %g (mean %g)" % (bn, s["downstream_profile_error"], s["downstream_mean_velocity"]))
        if not s["corner_stagnant_area"] > prev:
            fail("Bn %s: the corner's stagnant area should grow with Bn: %g after %g" % (bn, s["corner_stagnant_area"], prev))
        prev = s["corner_stagnant_area"]


def test_expansion_parallel():
    """The expansion (Newtonian) on 2 ranks: the downstream mean velocity
    and the corner's stagnant area equal the 1-rank values to 1e-9."""
    compare_ranks("expansion_parallel", "expansion", ["-rheology_type", "newtonian", "-output_fields", "0"], ("downstream_mean_velocity", "corner_stagnant_area", "kinetic_energy"), 1e-9)


TESTS = {k[5:]: v for k, v in globals().items() if k.startswith("test_")}

if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("test", choices=sorted(TESTS))
    ap.add_argument("--slump", required=True)
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--work", required=True)
    ARGS = ap.parse_args()
    os.makedirs(ARGS.work, exist_ok=True)
    TESTS[ARGS.test]()
    print("PASS %s" % ARGS.test)
