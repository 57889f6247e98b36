/* Fixed-step BDF2 (BDF1 for the first step), each step a KINSOL solve of
 * F(t_{n+1}, y, alpha y + beta) = 0 with the same residual, Jacobian and
 * linear solver as IDA: the reference against which adaptivity is measured.
 * Output times and the arrest time use the quadratic interpolant through
 * the last three states; the arrest time is located on it by the Illinois
 * (modified regula falsi) method. */
#include "timeintimpl.h"

/* Y = Lagrange interpolant at t through (ta, A), (tb, B), (tc, C); A may be NULL (linear). */
static PetscErrorCode Interpolate(PetscReal t, PetscReal ta, Vec A, PetscReal tb, Vec B, PetscReal tc, Vec C, Vec Y)
{
  PetscFunctionBeginUser;
  if (!A) {
    const PetscReal s = (t - tb) / (tc - tb);
    PetscCall(VecAXPBYPCZ(Y, 1.0 - s, s, 0.0, B, C));
  } else {
    const PetscReal la = (t - tb) * (t - tc) / ((ta - tb) * (ta - tc));
    const PetscReal lb = (t - ta) * (t - tc) / ((tb - ta) * (tb - tc));
    const PetscReal lc = (t - ta) * (t - tb) / ((tc - ta) * (tc - tb));
    PetscCall(VecAXPBYPCZ(Y, la, lb, 0.0, A, B));
    PetscCall(VecAXPY(Y, lc, C));
  }
  PetscFunctionReturn(0);
}

/* Criterion k's falling root on [tn, tn1] (g: ga > 0 at tn, gb <= 0 at
   tn1), located on the interpolant through (tn - dt, Yprev), (tn, Yn),
   (tn1, X) (linear without Yprev) by the Illinois method; Y: work. */
PetscErrorCode SlumpIntegratorLocateArrest(SlumpIntegrator ti, PetscInt k, PetscReal tn, PetscReal ga, PetscReal tn1, PetscReal gb, PetscReal dt, Vec Yprev, Vec Yn, Vec X, Vec Y, PetscReal *troot)
{
  PetscReal a = tn, b = tn1, c = b, gall[16];
  PetscInt  side = 0;
  PetscFunctionBeginUser;
  for (PetscInt it = 0; it < 60 && PetscAbsReal(b - a) > 1e-12 * dt; ++it) {
    PetscReal gc;
    c = (a * gb - b * ga) / (gb - ga);
    PetscCall(Interpolate(c, tn - dt, Yprev, tn, Yn, tn1, X, Y));
    PetscCall(SlumpIntegratorArrestFunctions(ti, c, Y, gall));
    gc = gall[k];
    if (PetscAbsReal(gc) < 1e-14 * PetscAbsReal(ti->arrest[k].threshold)) break;
    if ((gc > 0) == (ga > 0)) {
      a  = c;
      ga = gc;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b  = c;
      gb = gc;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  *troot = c;
  PetscFunctionReturn(0);
}

/* The outputs due up to tn1, on the same interpolant. */
PetscErrorCode SlumpIntegratorOutputsUpTo(SlumpIntegrator ti, PetscReal tn, PetscReal tn1, PetscReal dt, PetscReal *next_out, PetscInt *kout, Vec Yprev, Vec Yn, Vec X, Vec Y)
{
  PetscFunctionBeginUser;
  while (*next_out <= tn1 * (1 + 1e-12) && *next_out <= ti->tfinal * (1 + 1e-12)) {
    if (PetscAbsReal(*next_out - tn1) <= 1e-9 * dt) PetscCall(VecCopy(X, Y));
    else PetscCall(Interpolate(*next_out, tn - dt, Yprev, tn, Yn, tn1, X, Y));
    if (ti->outmon) PetscCall(ti->outmon(ti, *next_out, Y, ti->outctx));
    *next_out = ti->t0 + (++(*kout)) * ti->dtout;
  }
  PetscFunctionReturn(0);
}

/* The nonlinear solver's counts of this solve added to those a restart
   started from (base). */
static PetscErrorCode SolverCounts(SlumpIntegrator ti, SlumpImplicitSolver s, const SlumpStats *base)
{
  SlumpStats st;
  PetscFunctionBeginUser;
  PetscCall(SlumpImplicitSolverGetStats(s, &st));
  ti->stats.newton_its = base->newton_its + st.newton_its;
  ti->stats.lin_its    = base->lin_its + st.lin_its;
  ti->stats.lin_solves = base->lin_solves + st.lin_solves;
  ti->stats.conv_fails = base->conv_fails + st.conv_fails;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSolve_BDF2(SlumpIntegrator ti, Vec X)
{
  MPI_Comm            comm;
  SlumpImplicitSolver s;
  Vec                 Yprev, Yn, beta, Y;
  PetscInt            N, kout = 1;
  PetscReal           dt, next_out, gprev[16], g1[16];
  PetscInt            n0 = 0;
  PetscBool           have_prev = PETSC_FALSE, stop = PETSC_FALSE;
  SlumpStats          ckbase; /* the counters a restart starts from */
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(PetscMemzero(&ckbase, sizeof(ckbase)));
  N  = (PetscInt)PetscCeilReal((ti->tfinal - ti->t0) / ti->dt - 1e-9);
  dt = (ti->tfinal - ti->t0) / N;
  {
    PetscBool sv;
    PetscCall(SlumpLinearisationSetUp(ti->prob, comm, &sv));
    PetscCall(SlumpImplicitSolverCreate(ti->prob, X, &s));
    /* full Newton steps with the stress-velocity tangent: its direction is
       not a descent direction of KINSOL's merit function |F|^2, and on
       couette_cessation (dt 5e-3) the line search failed where full steps
       took 269 residual evaluations (1514 with the line search at dt
       2.5e-3). Steady solves keep the line search (stability_poiseuille_plug90:
       at most 12 iterations per continuation step with it, 21 without) */
    PetscCall(SlumpImplicitSolverSetDefaultLineSearch(s, sv ? PETSC_FALSE : PETSC_TRUE));
    PetscCall(SlumpIntegratorRestoreDual(ti));
  }
  PetscCall(VecDuplicate(X, &Yprev));
  PetscCall(VecDuplicate(X, &Yn));
  PetscCall(VecDuplicate(X, &beta));
  PetscCall(VecDuplicate(X, &Y));
  if (ti->restarted) {
    /* from a checkpoint at step n0: the same two states, outputs and arrest
       functions as the uninterrupted run had after that step */
    n0        = ti->stats.steps;
    have_prev = ti->ck_have_prev;
    kout      = ti->ck_kout;
    if (have_prev) PetscCall(VecCopy(ti->ck_history, Yprev));
    for (PetscInt k = 0; k < ti->narrest; ++k) gprev[k] = ti->ck_gprev[k];
    ckbase = ti->stats;
  } else {
    if (ti->outmon) PetscCall(ti->outmon(ti, ti->t0, X, ti->outctx));
    PetscCall(SlumpIntegratorResolveArrest(ti, ti->t0, X));
    if (ti->narrest) PetscCall(SlumpIntegratorArrestFunctions(ti, ti->t0, X, gprev));
  }
  next_out = ti->t0 + kout * ti->dtout;
  for (PetscInt n = n0; n < N; ++n) {
    const PetscReal tn = ti->t0 + n * dt, tn1 = ti->t0 + (n + 1) * dt;
    PetscReal       alpha;
    PetscBool       conv;
    PetscInt        nits, lits;
    PetscCall(VecCopy(X, Yn));
    if (n == 0 || !have_prev) { /* Yprev: the state at t_{n-1} (checkpointed) */
      alpha = 1.0 / dt;
      PetscCall(VecAXPBY(beta, -1.0 / dt, 0.0, Yn));
    } else {
      alpha = 1.5 / dt;
      PetscCall(VecAXPBYPCZ(beta, -2.0 / dt, 0.5 / dt, 0.0, Yn, Yprev));
    }
    PetscCall(SlumpImplicitSolverSolve(s, tn1, alpha, beta, X, &conv, &nits, &lits));
    if (!conv) {
      SlumpLinearFailures lf;
      PetscCall(SlumpImplicitSolverGetLinearFailures(s, &lf));
      PetscCheck(!lf.n || !lf.direct, comm, PETSC_ERR_NOT_CONVERGED, "Fixed-step BDF2: Newton did not converge at t = %g because %s", (double)tn1, lf.what);
      PetscCheck(!lf.n, comm, PETSC_ERR_NOT_CONVERGED, "Fixed-step BDF2: Newton did not converge at t = %g because a Krylov solve of -linear_solver iterative did not (%s after %" PetscInt_FMT " iterations); use -linear_solver direct or a stronger preconditioner (see docs/performance.md)", (double)tn1, KSPConvergedReasons[lf.reason], lf.its);
    }
    PetscCheck(conv, comm, PETSC_ERR_NOT_CONVERGED, "Fixed-step BDF2: Newton did not converge at t = %g; reduce -time_dt, raise -newton_max_it, or use -newton_linearisation stress_velocity", (double)tn1);
    {
      SlumpStepRecord r = {tn1, dt, (n == 0 || !have_prev) ? 1 : 2, nits, lits, 0, 0, X};
      ti->stats.steps++;
      ti->stats.h_min = dt;
      ti->stats.h_max = dt;
      ti->h_last      = dt;
      ti->order_last  = r.order;
      ti->t           = tn1;
      if (ti->stepmon) PetscCall(ti->stepmon(ti, &r, ti->stepctx));
    }
    /* arrest: falling sign change of g_k = diagnostic_k - threshold_k on [tn, tn1],
       located on the quadratic interpolant by the Illinois method */
    if (ti->narrest) {
      PetscCall(SlumpIntegratorArrestFunctions(ti, tn1, X, g1));
      for (PetscInt k = 0; k < ti->narrest; ++k) {
        if (ti->arrest[k].t_arrest < 0 && gprev[k] > 0 && g1[k] <= 0) {
          PetscReal c;
          PetscCall(SlumpIntegratorLocateArrest(ti, k, tn, gprev[k], tn1, g1[k], dt, have_prev ? Yprev : NULL, Yn, X, Y, &c));
          if (SlumpIntegratorArrestRecord(ti, k, c)) stop = PETSC_TRUE;
        }
        gprev[k] = g1[k];
      }
    }
    PetscCall(SlumpIntegratorOutputsUpTo(ti, tn, tn1, dt, &next_out, &kout, have_prev ? Yprev : NULL, Yn, X, Y));
    PetscCall(VecCopy(Yn, Yprev));
    have_prev = PETSC_TRUE;
    if (stop) break;
    {
      /* between steps (level-set reinitialisation): restart with BDF1 */
      PetscBool changed;
      PetscCall(SlumpProblemPostStep(ti->prob, ti->stats.steps, tn1, X, &changed));
      if (changed) {
        have_prev = PETSC_FALSE;
        PetscCall(SlumpProblemDualReset(ti->prob));
        ti->stats.restarts++;
      }
    }
    if (ti->ckdir[0]) {
      PetscCall(SolverCounts(ti, s, &ckbase));
      PetscCall(SlumpIntegratorCheckpointMaybe(ti, X, Yprev, have_prev, kout, gprev));
    }
    if (ti->stop_requested) break;
  }
  PetscCall(SolverCounts(ti, s, &ckbase));
  PetscCall(SlumpImplicitSolverDestroy(&s));
  PetscCall(VecDestroy(&Yprev));
  PetscCall(VecDestroy(&Yn));
  PetscCall(VecDestroy(&beta));
  PetscCall(VecDestroy(&Y));
  PetscFunctionReturn(0);
}
