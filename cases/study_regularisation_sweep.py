#!/usr/bin/env python3
"""Study 1 of docs/sweeps.md: the arrest time against the regularisation,
against the exact (unregularised) model, for Couette and Poiseuille
cessation at Bn = 0.1, 1, 10; Papanastasiou m = 1e1 .. 1e6 and
Bercovier-Engelman eps = 1e-1 .. 1e-6. Each (scene, model) is one
`slump -sweep ... -sweep2 bn:...` under mpirun; the rows go to
docs/studies/regsweep_<scene>_<model>.csv and the figures to
docs/regsweep_*.png.

usage: python3 cases/study_regularisation_sweep.py [--slump build/slump] [--ranks 2] [--docs out/docs]
"""
import argparse
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = {"papanastasiou": ("rheology_papanastasiou_m", "1e1,1e2,1e3,1e4,1e5,1e6"),
          "bercovier": ("rheology_bercovier_eps", "1e-1,1e-2,1e-3,1e-4,1e-5,1e-6")}
SCENES = {"couette_cessation": ["-time_final", "1"],
          "poiseuille_cessation": ["-initial_flow", "newtonian", "-time_final", "2"]}
COMMON = ["-arrest_stop", "first", "-mesh_ny", "16", "-time_rtol", "1e-4", "-time_atol", "1e-8"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--slump", default=os.path.join(HERE, "..", "build", "slump"))
    ap.add_argument("--mpiexec", default="mpirun")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--docs", default="out/docs", help="where CSV files (DOCS/studies) and figures go; docs for the documentation's")
    ap.add_argument("--work", default="out/study_regsweep")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.docs, "studies"), exist_ok=True)
    csvs = {}
    for scene, extra in SCENES.items():
        for model, (opt, values) in MODELS.items():
            out = os.path.join(a.work, "%s_%s" % (scene, model))
            cmd = [a.mpiexec, "--oversubscribe", "--allow-run-as-root", "-n", str(a.ranks), a.slump, "-scene", scene, "-rheology_type", model,
                   "-sweep", "%s:%s" % (opt, values), "-sweep2", "bn:0.1,1,10", "-output_dir", out] + COMMON + extra
            print(" ".join(cmd), flush=True)
            p = subprocess.run(cmd, text=True)
            if p.returncode:
                sys.exit("sweep failed")
            dst = os.path.join(a.docs, "studies", "regsweep_%s_%s.csv" % (scene, model))
            shutil.copy(os.path.join(out, "sweep.csv"), dst)
            csvs[(scene, model)] = dst
    plot = [sys.executable, os.path.join(HERE, "plot_sweep.py")]
    for scene in SCENES:
        m, e = csvs[(scene, "papanastasiou")], csvs[(scene, "bercovier")]
        subprocess.run(plot + ["arrest", m + ":Papanastasiou (x = m)", e + ":Bercovier-Engelman (x = 1/eps)", "--x", "stiffness", "--panel", "bn",
                               "--xlabel", "m or 1/eps", "--title", scene.replace("_", " ") + ": arrest time (mean shear rate < 1e-3)",
                               "--out", os.path.join(a.docs, "regsweep_arrest_%s.png" % scene)], check=True)
    for model, (opt, _) in MODELS.items():
        files = [csvs[(s, model)] + ":" + s.split("_")[0] for s in SCENES]
        subprocess.run(plot + ["error"] + files + ["--x", "stiffness", "--curve", "bn", "--xlabel", "1/eps" if model == "bercovier" else "m"]
                       + ["--title", "%s: error against the exact model and cost" % model, "--out", os.path.join(a.docs, "regsweep_error_%s.png" % model)], check=True)


if __name__ == "__main__":
    main()
