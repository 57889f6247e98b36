/* Our own cell loop for affine triangles: gather -> pointwise kernels ->
 * scatter, with basis values and reference gradients tabulated once.
 *
 * It calls the very pointwise functions registered in the PetscDS (so the
 * rheology and effects kernels are the same as for PETSc's assembly), but
 * contracts them with the basis in a few tight loops, exploiting that each
 * vector basis function has a single non-zero component. Measured on this
 * machine it is an order of magnitude faster than PETSc 3.18's generic
 * PetscFEIntegrateJacobian (see docs/performance.md). Natural boundary
 * terms still go through DMPlexComputeBdResidualSingle. */
#include "slumpimpl.h"

#define MAXNB 32 /* basis functions per cell, all fields */
#define MAXQ  64

static PetscLogEvent SLUMP_Residual = 0, SLUMP_Jacobian = 0, SLUMP_Integral = 0;

static PetscErrorCode RegisterEvents(void)
{
  PetscClassId cls;
  PetscFunctionBeginUser;
  if (SLUMP_Residual) PetscFunctionReturn(0);
  PetscCall(PetscClassIdRegister("slump", &cls));
  PetscCall(PetscLogEventRegister("SlumpResidual", cls, &SLUMP_Residual));
  PetscCall(PetscLogEventRegister("SlumpJacobian", cls, &SLUMP_Jacobian));
  PetscCall(PetscLogEventRegister("SlumpIntegral", cls, &SLUMP_Integral));
  PetscFunctionReturn(0);
}

struct _n_SlumpAssembly {
  PetscInt        dim, Nf, Nq, Nb[SLUMP_MAX_FIELDS], Nc[SLUMP_MAX_FIELDS], off[SLUMP_MAX_FIELDS], NbTot, cStart, cEnd;
  PetscInt        comp[MAXNB];          /* component of each basis function (vector field) */
  PetscReal       w[MAXQ], xi[MAXQ * 3];
  PetscReal       phi[MAXQ * MAXNB];    /* value of basis b (its non-zero component) at q */
  PetscReal       dphi[MAXQ * MAXNB * 3]; /* reference gradient */
  /* the kernels' layout: planar, that of the fields; axisymmetric (axis >= 0,
     the radial coordinate x[axis]), three-dimensional (kdim = 3): the
     velocity has a third (hoop) component, always 0, and its gradient the
     entry (2,2) = u_r / r; scalar fields have a zero third derivative */
  PetscInt        axis, kdim, kNc[SLUMP_MAX_FIELDS];
  PetscInt        uOff[SLUMP_MAX_FIELDS + 1], uOff_x[SLUMP_MAX_FIELDS + 1];
  /* per cell, computed once (the mesh does not move) */
  PetscInt        ncell;
  PetscReal      *geom;  /* v0[dim], J[dim*dim], invJ[dim*dim], detJ */
  PetscInt       *lidx;  /* closure -> local vector index */
  PetscInt       *gidx;  /* closure -> global row (negative: constrained) */
};

#define GEOMSIZE(dim) ((dim) + 2 * (dim) * (dim) + 1)

static PetscErrorCode CacheCells(SlumpProblem prob, SlumpAssembly a)
{
  PetscSection s, gs;
  Vec          L;
  PetscScalar *la;
  PetscInt     n, dim = a->dim, N = a->NbTot;
  PetscFunctionBeginUser;
  a->ncell = a->cEnd - a->cStart;
  PetscCall(PetscMalloc3(a->ncell * GEOMSIZE(dim), &a->geom, a->ncell * N, &a->lidx, a->ncell * N, &a->gidx));
  PetscCall(DMGetLocalSection(prob->dm, &s));
  PetscCall(DMGetGlobalSection(prob->dm, &gs));
  /* local indices: the closure of a vector holding its own indices */
  PetscCall(DMCreateLocalVector(prob->dm, &L));
  PetscCall(VecGetLocalSize(L, &n));
  PetscCall(VecGetArray(L, &la));
  for (PetscInt i = 0; i < n; ++i) la[i] = (PetscScalar)i;
  PetscCall(VecRestoreArray(L, &la));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    const PetscInt cell = a->cStart + c;
    PetscReal     *g    = &a->geom[c * GEOMSIZE(dim)];
    PetscScalar    buf[MAXNB], *bv = buf;
    PetscInt       csize = MAXNB, nidx, *idx = NULL;
    PetscCall(DMPlexComputeCellGeometryAffineFEM(prob->dm, cell, g, g + dim, g + dim + dim * dim, g + dim + 2 * dim * dim));
    PetscCall(DMPlexVecGetClosure(prob->dm, s, L, cell, &csize, &bv));
    PetscCheck(csize == N, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Closure size %" PetscInt_FMT " differs from the basis size %" PetscInt_FMT, csize, N);
    for (PetscInt b = 0; b < N; ++b) a->lidx[c * N + b] = (PetscInt)PetscRealPart(bv[b]);
    PetscCall(DMPlexGetClosureIndices(prob->dm, s, gs, cell, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    PetscCheck(nidx == N, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Closure index count %" PetscInt_FMT " differs from the basis size %" PetscInt_FMT, nidx, N);
    for (PetscInt b = 0; b < N; ++b) a->gidx[c * N + b] = idx[b];
    PetscCall(DMPlexRestoreClosureIndices(prob->dm, s, gs, cell, PETSC_TRUE, &nidx, &idx, NULL, NULL));
  }
  PetscCall(VecDestroy(&L));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpAssemblyCreate(SlumpProblem prob)
{
  SlumpAssembly   a;
  PetscQuadrature quad;
  const PetscReal *pts, *wts;
  PetscInt        qdim, qNc;
  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PetscNew(&a));
  PetscCall(DMGetDimension(prob->dm, &a->dim));
  PetscCall(DMGetNumFields(prob->dm, &a->Nf));
  PetscCall(DMPlexGetHeightStratum(prob->dm, 0, &a->cStart, &a->cEnd));
  for (PetscInt f = 0; f < a->Nf; ++f) {
    PetscFE         fe;
    PetscTabulation T;
    PetscCall(DMGetField(prob->dm, f, NULL, (PetscObject *)&fe));
    if (f == 0) {
      PetscCall(PetscFEGetQuadrature(fe, &quad));
      PetscCall(PetscQuadratureGetData(quad, &qdim, &qNc, &a->Nq, &pts, &wts));
      PetscCheck(a->Nq <= MAXQ, PETSC_COMM_SELF, PETSC_ERR_SUP, "Too many quadrature points (%" PetscInt_FMT "); lower -quadrature_order", a->Nq);
      for (PetscInt q = 0; q < a->Nq; ++q) {
        a->w[q] = wts[q];
        for (PetscInt d = 0; d < a->dim; ++d) a->xi[q * a->dim + d] = pts[q * a->dim + d];
      }
    }
    PetscCall(PetscFEGetDimension(fe, &a->Nb[f]));
    PetscCall(PetscFEGetNumComponents(fe, &a->Nc[f]));
    a->off[f] = f ? a->off[f - 1] + a->Nb[f - 1] : 0;
    PetscCheck(a->off[f] + a->Nb[f] <= MAXNB, PETSC_COMM_SELF, PETSC_ERR_SUP, "Too many basis functions per cell");
    PetscCall(PetscFECreateTabulation(fe, 1, a->Nq, a->xi, 1, &T));
    for (PetscInt b = 0; b < a->Nb[f]; ++b) {
      const PetscInt B = a->off[f] + b;
      PetscReal      best = -1;
      /* the component this basis function lives in */
      for (PetscInt c = 0; c < a->Nc[f]; ++c) {
        PetscReal s = 0;
        for (PetscInt q = 0; q < a->Nq; ++q) {
          s += PetscAbsReal(T->T[0][(q * a->Nb[f] + b) * a->Nc[f] + c]);
          for (PetscInt d = 0; d < a->dim; ++d) s += PetscAbsReal(T->T[1][((q * a->Nb[f] + b) * a->Nc[f] + c) * a->dim + d]);
        }
        if (s > best) {
          best       = s;
          a->comp[B] = c;
        }
      }
      for (PetscInt q = 0; q < a->Nq; ++q) {
        const PetscInt c = a->comp[B];
        a->phi[q * MAXNB + B] = T->T[0][(q * a->Nb[f] + b) * a->Nc[f] + c];
        for (PetscInt d = 0; d < a->dim; ++d) a->dphi[(q * MAXNB + B) * 3 + d] = T->T[1][((q * a->Nb[f] + b) * a->Nc[f] + c) * a->dim + d];
      }
    }
    PetscCall(PetscTabulationDestroy(&T));
  }
  a->NbTot = a->off[a->Nf - 1] + a->Nb[a->Nf - 1];
  a->axis  = prob->axis;
  PetscCheck(a->axis < 0 || (a->dim == 2 && a->Nc[0] == 2), prob->comm, PETSC_ERR_SUP, "The axisymmetric formulation needs a 2-D mesh and the plane (velocity-pressure) formulation");
  a->kdim = a->axis >= 0 ? 3 : a->dim;
  for (PetscInt f = 0; f < a->Nf; ++f) a->kNc[f] = (a->axis >= 0 && f == 0) ? 3 : a->Nc[f];
  for (PetscInt f = 0, o = 0, ox = 0; f < a->Nf; ++f) {
    a->uOff[f]   = o;
    a->uOff_x[f] = ox;
    o += a->kNc[f];
    ox += a->kNc[f] * a->kdim;
    a->uOff[f + 1]   = o;
    a->uOff_x[f + 1] = ox;
  }
  PetscCall(CacheCells(prob, a));
  prob->assembly = a;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpAssemblyDestroy(SlumpAssembly *a)
{
  PetscFunctionBeginUser;
  if (*a) PetscCall(PetscFree3((*a)->geom, (*a)->lidx, (*a)->gidx));
  PetscCall(PetscFree(*a));
  PetscFunctionReturn(0);
}

/* Per-cell geometry and the fields (u, u_t, u_x) at every quadrature point. */
typedef struct {
  PetscReal   detJ, x[MAXQ * 3], G[MAXQ * MAXNB * 3]; /* physical gradients */
  PetscScalar u[MAXQ * 8], ut[MAXQ * 8], ux[MAXQ * 24];
  PetscScalar ul[MAXQ * 8], ulx[MAXQ * 24]; /* the lagged state (auxiliary fields) */
} CellData;

static inline void EvaluateCell(SlumpAssembly a, PetscInt c, const PetscScalar *xa, const PetscScalar *ta, const PetscScalar *la, CellData *cd)
{
  const PetscInt   dim = a->dim, kd = a->kdim, ntot = a->uOff[a->Nf], N = a->NbTot, *li = &a->lidx[c * N];
  const PetscReal *g = &a->geom[c * GEOMSIZE(dim)], *v0 = g, *J = g + dim, *invJ = g + dim + dim * dim;
  PetscScalar      xv[MAXNB], tv[MAXNB], lv[MAXNB];
  cd->detJ = g[dim + 2 * dim * dim];
  for (PetscInt b = 0; b < N; ++b) {
    xv[b] = xa[li[b]];
    tv[b] = ta ? ta[li[b]] : 0.0;
    lv[b] = la ? la[li[b]] : 0.0;
  }
  for (PetscInt q = 0; q < a->Nq; ++q) {
    PetscScalar *u = &cd->u[q * 8], *ut = &cd->ut[q * 8], *ux = &cd->ux[q * 24];
    for (PetscInt d = 0; d < dim; ++d) {
      cd->x[q * 3 + d] = v0[d];
      for (PetscInt e = 0; e < dim; ++e) cd->x[q * 3 + d] += J[d * dim + e] * (a->xi[q * dim + e] + 1.0);
    }
    PetscScalar *ul = &cd->ul[q * 8], *ulx = &cd->ulx[q * 24];
    for (PetscInt i = 0; i < ntot; ++i) u[i] = ut[i] = ul[i] = 0.0;
    for (PetscInt i = 0; i < ntot * kd; ++i) ux[i] = ulx[i] = 0.0;
    for (PetscInt f = 0; f < a->Nf; ++f) {
      for (PetscInt b = 0; b < a->Nb[f]; ++b) {
        const PetscInt   B = a->off[f] + b, c = a->comp[B];
        const PetscReal *rg = &a->dphi[(q * MAXNB + B) * 3], ph = a->phi[q * MAXNB + B];
        PetscReal       *G  = &cd->G[(q * MAXNB + B) * 3];
        for (PetscInt d = 0; d < dim; ++d) {
          G[d] = 0.0;
          for (PetscInt e = 0; e < dim; ++e) G[d] += rg[e] * invJ[e * dim + d];
        }
        u[a->uOff[f] + c] += ph * xv[B];
        ut[a->uOff[f] + c] += ph * tv[B];
        for (PetscInt d = 0; d < dim; ++d) ux[a->uOff_x[f] + c * kd + d] += G[d] * xv[B];
        if (la) {
          ul[a->uOff[f] + c] += ph * lv[B];
          for (PetscInt d = 0; d < dim; ++d) ulx[a->uOff_x[f] + c * kd + d] += G[d] * lv[B];
        }
      }
    }
    if (a->axis >= 0) { /* the hoop strain u_r / r (quadrature points lie off the axis) */
      const PetscReal r = cd->x[q * 3 + a->axis];
      ux[a->uOff_x[0] + 8] = u[a->uOff[0] + a->axis] / r;
      if (la) ulx[a->uOff_x[0] + 8] = ul[a->uOff[0] + a->axis] / r;
    }
  }
}

/* The factor of the quadrature weight at point q of the cell in cd: 1, or
   the radius (axisymmetric: integrals per radian of the solid of revolution). */
static inline PetscReal RadialWeight(SlumpAssembly a, const CellData *cd, PetscInt q)
{
  return a->axis >= 0 ? cd->x[q * 3 + a->axis] : 1.0;
}

/* The radius at quadrature point q of local cell c (axisymmetric), from the
   cached geometry; 1 in the plane. */
static inline PetscReal QuadRadius(SlumpAssembly a, PetscInt c, PetscInt q)
{
  const PetscInt   dim = a->dim, ax = a->axis;
  const PetscReal *g = &a->geom[c * GEOMSIZE(dim)], *v0 = g, *J = g + dim;
  PetscReal        r;
  if (ax < 0) return 1.0;
  r = v0[ax];
  for (PetscInt e = 0; e < dim; ++e) r += J[ax * dim + e] * (a->xi[q * dim + e] + 1.0);
  return r;
}

PetscErrorCode SlumpAssembleResidual(SlumpProblem prob, PetscReal t, Vec locX, Vec locXdot, Vec locF)
{
  SlumpAssembly      a = prob->assembly;
  PetscDS            ds;
  PetscSection       s;
  PetscPointFunc     f0[SLUMP_MAX_FIELDS], f1[SLUMP_MAX_FIELDS];
  const PetscScalar *constants;
  PetscInt           nc, dim = a->dim, kd = a->kdim;
  CellData          *cd;
  PetscFunctionBeginUser;
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(DMGetLocalSection(prob->dm, &s));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  for (PetscInt f = 0; f < a->Nf; ++f) PetscCall(PetscDSGetResidual(ds, f, &f0[f], &f1[f]));
  PetscCall(PetscLogEventBegin(SLUMP_Residual, 0, 0, 0, 0));
  PetscCall(PetscMalloc1(1, &cd));
  const PetscScalar *xa, *ta = NULL, *la = NULL;
  PetscScalar       *fa;
  const PetscInt     NfA = prob->lagSet ? a->Nf : 0;
  const PetscInt    *aO = NfA ? a->uOff : NULL, *aOx = NfA ? a->uOff_x : NULL;
  PetscCall(VecGetArrayRead(locX, &xa));
  if (locXdot) PetscCall(VecGetArrayRead(locXdot, &ta));
  if (NfA) PetscCall(VecGetArrayRead(prob->locLag, &la));
  PetscCall(VecGetArray(locF, &fa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    PetscScalar ev[MAXNB];
    EvaluateCell(a, c, xa, ta, la, cd);
    PetscCall(PetscArrayzero(ev, a->NbTot));
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscReal wq = a->w[q] * cd->detJ * RadialWeight(a, cd, q), ir = a->axis >= 0 ? 1.0 / cd->x[q * 3 + a->axis] : 0.0;
      for (PetscInt f = 0; f < a->Nf; ++f) {
        PetscScalar r0[3] = {0, 0, 0}, r1[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        const PetscScalar *ul = NfA ? &cd->ul[q * 8] : NULL, *ulx = NfA ? &cd->ulx[q * 24] : NULL;
        if (f0[f]) f0[f](kd, a->Nf, NfA, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], aO, aOx, ul, NULL, ulx, t, &cd->x[q * 3], nc, constants, r0);
        if (f1[f]) f1[f](kd, a->Nf, NfA, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], aO, aOx, ul, NULL, ulx, t, &cd->x[q * 3], nc, constants, r1);
        for (PetscInt b = 0; b < a->Nb[f]; ++b) {
          const PetscInt   B = a->off[f] + b, c = a->comp[B];
          const PetscReal *G = &cd->G[(q * MAXNB + B) * 3];
          PetscScalar      v = r0[c] * a->phi[q * MAXNB + B];
          for (PetscInt d = 0; d < dim; ++d) v += r1[c * kd + d] * G[d];
          if (f == 0 && c == a->axis) v += r1[8] * a->phi[q * MAXNB + B] * ir; /* hoop: tau_tt v_r / r */
          ev[B] += wq * v;
        }
      }
    }
    for (PetscInt b = 0; b < a->NbTot; ++b) fa[a->lidx[c * a->NbTot + b]] += ev[b];
  }
  PetscCall(VecRestoreArray(locF, &fa));
  if (NfA) PetscCall(VecRestoreArrayRead(prob->locLag, &la));
  if (locXdot) PetscCall(VecRestoreArrayRead(locXdot, &ta));
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  /* natural boundary terms (tractions) */
  {
    PetscInt nb;
    PetscCall(PetscDSGetNumBoundary(ds, &nb));
    for (PetscInt b = 0; b < nb; ++b) {
      PetscWeakForm           wf;
      DMBoundaryConditionType type;
      DMLabel                 label;
      PetscInt                nv, field;
      const PetscInt         *values;
      PetscCall(PetscDSGetBoundary(ds, b, &wf, &type, NULL, &label, &nv, &values, &field, NULL, NULL, NULL, NULL, NULL));
      if (type != DM_BC_NATURAL) continue;
      for (PetscInt v = 0; v < nv; ++v) {
        PetscFormKey key;
        key.label = label;
        key.value = values[v];
        key.field = field;
        key.part  = 0;
        PetscCall(DMPlexComputeBdResidualSingle(prob->dm, t, wf, key, locX, locXdot, locF));
      }
    }
  }
  PetscCall(PetscLogEventEnd(SLUMP_Residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpAssembleJacobian(SlumpProblem prob, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, Mat Jac)
{
  PetscDS       ds;
  PetscPointJac g[SLUMP_MAX_FIELDS][SLUMP_MAX_FIELDS][4];
  PetscFunctionBeginUser;
  PetscCall(DMGetDS(prob->dm, &ds));
  for (PetscInt f = 0; f < prob->assembly->Nf; ++f)
    for (PetscInt h = 0; h < prob->assembly->Nf; ++h) PetscCall(PetscDSGetJacobian(ds, f, h, &g[f][h][0], &g[f][h][1], &g[f][h][2], &g[f][h][3]));
  PetscCall(SlumpAssembleJacobianWith(prob, t, locX, locXdot, shift, g, Jac));
  if (prob->wallFriction) {
    /* solution-dependent natural terms (wall friction): PETSc's face loop */
    PetscInt nb;
    PetscCall(PetscDSGetNumBoundary(ds, &nb));
    for (PetscInt b = 0; b < nb; ++b) {
      PetscWeakForm           wf;
      DMBoundaryConditionType type;
      DMLabel                 label;
      PetscInt                nv, field;
      const PetscInt         *values;
      PetscCall(PetscDSGetBoundary(ds, b, &wf, &type, NULL, &label, &nv, &values, &field, NULL, NULL, NULL, NULL, NULL));
      if (type != DM_BC_NATURAL) continue;
      PetscCall(DMPlexComputeBdJacobianSingle(prob->dm, t, wf, label, nv, values, field, locX, locXdot, shift, Jac, Jac));
    }
    PetscCall(MatAssemblyBegin(Jac, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Jac, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/* The same with an explicit table of kernels g[test field][trial field][g0..g3]
   (NULL: none), e.g. the Laplacian and mass matrix of the eigenproblem. */
PetscErrorCode SlumpAssembleJacobianWith(SlumpProblem prob, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, PetscPointJac g[SLUMP_MAX_FIELDS][SLUMP_MAX_FIELDS][4], Mat Jac)
{
  SlumpAssembly      a = prob->assembly;
  PetscDS            ds;
  const PetscScalar *constants;
  PetscInt           nc, dim = a->dim, kd = a->kdim;
  CellData          *cd;
  PetscFunctionBeginUser;
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscLogEventBegin(SLUMP_Jacobian, 0, 0, 0, 0));
  PetscCall(MatZeroEntries(Jac));
  PetscCall(PetscMalloc1(1, &cd));
  const PetscScalar *xa, *ta = NULL, *la = NULL;
  const PetscInt     NfA = prob->lagSet ? a->Nf : 0;
  const PetscInt    *aO = NfA ? a->uOff : NULL, *aOx = NfA ? a->uOff_x : NULL;
  /* stress-velocity Newton: the plastic stress at each quadrature point goes
     to the kernels as a_t (SlumpRheologyPointwise) */
  const PetscScalar *S = (prob->dualOn && prob->dualInSolve) ? prob->dual : NULL;
  PetscCall(VecGetArrayRead(locX, &xa));
  if (locXdot) PetscCall(VecGetArrayRead(locXdot, &ta));
  if (NfA) PetscCall(VecGetArrayRead(prob->locLag, &la));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    PetscScalar    em[MAXNB * MAXNB];
    const PetscInt N = a->NbTot;
    EvaluateCell(a, c, xa, ta, la, cd);
    PetscCall(PetscArrayzero(em, N * N));
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscReal wq = a->w[q] * cd->detJ * RadialWeight(a, cd, q), ir = a->axis >= 0 ? 1.0 / cd->x[q * 3 + a->axis] : 0.0;
      for (PetscInt f = 0; f < a->Nf; ++f)
        for (PetscInt h = 0; h < a->Nf; ++h) {
          PetscScalar    G0[9], G1[27], G2[27], G3[81];
          const PetscInt NcI = a->kNc[f], NcJ = a->kNc[h];
          PetscBool      has[4];
          PetscScalar   *gg[4] = {G0, G1, G2, G3};
          for (PetscInt k = 0; k < 4; ++k) {
            has[k] = g[f][h][k] ? PETSC_TRUE : PETSC_FALSE;
            if (has[k]) {
              const PetscInt n = NcI * NcJ * (k == 0 ? 1 : (k == 3 ? kd * kd : kd));
              PetscCall(PetscArrayzero(gg[k], n));
              g[f][h][k](kd, a->Nf, NfA, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], aO, aOx, NfA ? &cd->ul[q * 8] : NULL, S ? &S[(c * a->Nq + q) * prob->dualNs] : NULL, NfA ? &cd->ulx[q * 24] : NULL, t, shift, &cd->x[q * 3], nc, constants, gg[k]);
            }
          }
          if (!has[0] && !has[1] && !has[2] && !has[3]) continue;
          for (PetscInt i = 0; i < a->Nb[f]; ++i) {
            const PetscInt   Ii = a->off[f] + i, fc = a->comp[Ii];
            const PetscReal  pi = a->phi[q * MAXNB + Ii], *Gi = &cd->G[(q * MAXNB + Ii) * 3];
            /* axisymmetric: a radial velocity test function also has the
               gradient entry (2,2) = v_r / r, of the hoop component 2 */
            const PetscReal  hi = (f == 0 && fc == a->axis) ? pi * ir : 0.0;
            PetscScalar      A[3], B[3][3];
            /* contract the test function once: row i against any trial of component gc
               is (A[gc]) phi_j + B[gc] . grad phi_j */
            for (PetscInt gc = 0; gc < NcJ; ++gc) {
              const PetscInt k = fc * NcJ + gc, kh = 2 * NcJ + gc;
              A[gc]            = has[0] ? G0[k] * pi : 0.0;
              if (has[2]) {
                for (PetscInt d = 0; d < dim; ++d) A[gc] += G2[k * kd + d] * Gi[d];
                if (hi != 0.0) A[gc] += G2[kh * kd + 2] * hi;
              }
              for (PetscInt e = 0; e < kd; ++e) {
                B[gc][e] = has[1] ? G1[k * kd + e] * pi : 0.0;
                if (has[3]) {
                  for (PetscInt d = 0; d < dim; ++d) B[gc][e] += G3[(k * kd + d) * kd + e] * Gi[d];
                  if (hi != 0.0) B[gc][e] += G3[(kh * kd + 2) * kd + e] * hi;
                }
              }
            }
            PetscScalar *row = &em[Ii * N + a->off[h]];
            for (PetscInt j = 0; j < a->Nb[h]; ++j) {
              const PetscInt   Jj = a->off[h] + j, gc = a->comp[Jj];
              const PetscReal *Gj = &cd->G[(q * MAXNB + Jj) * 3];
              PetscScalar      v  = A[gc] * a->phi[q * MAXNB + Jj];
              for (PetscInt e = 0; e < dim; ++e) v += B[gc][e] * Gj[e];
              if (h == 0 && gc == a->axis) v += B[2][2] * a->phi[q * MAXNB + Jj] * ir; /* the trial's hoop entry */
              row[j] += wq * v;
            }
          }
        }
    }
    PetscCall(MatSetValues(Jac, N, &a->gidx[c * N], N, &a->gidx[c * N], em, ADD_VALUES));
  }
  if (NfA) PetscCall(VecRestoreArrayRead(prob->locLag, &la));
  if (locXdot) PetscCall(VecRestoreArrayRead(locXdot, &ta));
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  PetscCall(MatAssemblyBegin(Jac, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jac, MAT_FINAL_ASSEMBLY));
  /* the yielded set this Jacobian was built with */
  if (S) PetscCall(PetscArraycpy(prob->dualYieldJ, prob->dualYield, a->ncell * a->Nq));
  PetscCall(PetscLogEventEnd(SLUMP_Jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The Schur-complement preconditioner of the velocity-pressure Jacobian
   [A B^T; B 0]: S = -B A^{-1} B^T is approximated cell by cell by
     Sp = - int q p / (eta_q + m_q |K|),
   eta_q the viscosity the velocity block sees at the quadrature point (the
   mean of the diagonal entries of its g3 kernel, eta (1 + delta_cd) for
   tau = eta (grad u + grad u^T)), m_q the mass per unit volume of its g0
   (shift rho: inertia), |K| the cell area. Viscous-dominated (eta >> m |K|)
   this is the viscosity-weighted pressure mass matrix, spectrally equivalent
   to S whatever the variation of eta (Grinevich & Olshanskii 2009); the
   m |K| term is a local stand-in for the pressure Laplacian / (rho cj) of
   Cahouet and Chabard when the time step is small. */
PetscErrorCode SlumpAssembleSchurMass(SlumpProblem prob, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, Mat Sp)
{
  SlumpAssembly      a = prob->assembly;
  PetscDS            ds;
  PetscPointJac      g0, g1, g2, g3;
  const PetscScalar *constants, *xa, *ta = NULL, *la = NULL;
  PetscInt           nc, dim = a->dim, kd = a->kdim;
  const PetscInt     Nbp = a->Nb[1], offp = a->off[1], NcU = a->kNc[0];
  CellData          *cd;
  PetscFunctionBeginUser;
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscDSGetJacobian(ds, 0, 0, &g0, &g1, &g2, &g3));
  PetscCheck(g3, prob->comm, PETSC_ERR_SUP, "The Schur preconditioner needs a viscous velocity block");
  if (!prob->pidx) {
    PetscSection ls, gs;
    PetscCall(DMGetLocalSection(prob->dmP, &ls));
    PetscCall(DMGetGlobalSection(prob->dmP, &gs));
    PetscCall(PetscMalloc1(a->ncell * Nbp, &prob->pidx));
    for (PetscInt c = 0; c < a->ncell; ++c) {
      PetscInt nidx, *idx = NULL;
      PetscCall(DMPlexGetClosureIndices(prob->dmP, ls, gs, a->cStart + c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
      PetscCheck(nidx == Nbp, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Pressure closure size %" PetscInt_FMT " differs from %" PetscInt_FMT, nidx, Nbp);
      for (PetscInt b = 0; b < Nbp; ++b) prob->pidx[c * Nbp + b] = idx[b];
      PetscCall(DMPlexRestoreClosureIndices(prob->dmP, ls, gs, a->cStart + c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    }
  }
  PetscCall(PetscLogEventBegin(SLUMP_Jacobian, 0, 0, 0, 0));
  PetscCall(MatZeroEntries(Sp));
  PetscCall(PetscMalloc1(1, &cd));
  const PetscInt     NfA = prob->lagSet ? a->Nf : 0;
  const PetscInt    *aO = NfA ? a->uOff : NULL, *aOx = NfA ? a->uOff_x : NULL;
  const PetscScalar *S  = (prob->dualOn && prob->dualInSolve) ? prob->dual : NULL;
  PetscCall(VecGetArrayRead(locX, &xa));
  if (locXdot) PetscCall(VecGetArrayRead(locXdot, &ta));
  if (NfA) PetscCall(VecGetArrayRead(prob->locLag, &la));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    PetscScalar em[MAXNB * MAXNB];
    PetscCall(PetscArrayzero(em, Nbp * Nbp));
    EvaluateCell(a, c, xa, ta, la, cd);
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscReal wq = a->w[q] * cd->detJ * RadialWeight(a, cd, q);
      PetscScalar     G0[9], G3[81];
      PetscReal       eta = 0.0, m = 0.0, wt;
      PetscCall(PetscArrayzero(G3, NcU * NcU * kd * kd));
      g3(kd, a->Nf, NfA, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], aO, aOx, NfA ? &cd->ul[q * 8] : NULL, S ? &S[(c * a->Nq + q) * prob->dualNs] : NULL, NfA ? &cd->ulx[q * 24] : NULL, t, shift, &cd->x[q * 3], nc, constants, G3);
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt d = 0; d < dim; ++d) eta += PetscRealPart(G3[((k * NcU + k) * kd + d) * kd + d]);
      eta /= (PetscReal)(dim * dim + dim);
      if (g0) {
        PetscCall(PetscArrayzero(G0, NcU * NcU));
        g0(kd, a->Nf, NfA, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], aO, aOx, NfA ? &cd->ul[q * 8] : NULL, S ? &S[(c * a->Nq + q) * prob->dualNs] : NULL, NfA ? &cd->ulx[q * 24] : NULL, t, shift, &cd->x[q * 3], nc, constants, G0);
        for (PetscInt k = 0; k < dim; ++k) m += PetscRealPart(G0[k * NcU + k]);
        m = PetscMax(m / dim, 0.0);
      }
      wt = -wq / (PetscMax(eta, PETSC_SMALL) + 2.0 * cd->detJ * m);
      for (PetscInt i = 0; i < Nbp; ++i) {
        const PetscReal pi = a->phi[q * MAXNB + offp + i] * wt;
        for (PetscInt j = 0; j < Nbp; ++j) em[i * Nbp + j] += pi * a->phi[q * MAXNB + offp + j];
      }
    }
    PetscCall(MatSetValues(Sp, Nbp, &prob->pidx[c * Nbp], Nbp, &prob->pidx[c * Nbp], em, ADD_VALUES));
  }
  if (NfA) PetscCall(VecRestoreArrayRead(prob->locLag, &la));
  if (locXdot) PetscCall(VecRestoreArrayRead(locXdot, &ta));
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  PetscCall(MatAssemblyBegin(Sp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Sp, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(SLUMP_Jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The plastic stress S at every (cell, quadrature point): consistent with
   locX (locdX NULL), or updated from the linearisation point locX with the
   Newton correction locdX (zero on constrained dofs). */
PetscErrorCode SlumpAssembleDual(SlumpProblem prob, PetscReal t, Vec locX, Vec locdX, PetscScalar *S, PetscBool *yielded)
{
  SlumpAssembly          a = prob->assembly;
  PetscDS                ds;
  const PetscScalar     *constants, *xa, *da = NULL;
  PetscInt               nc;
  CellData              *cd;
  SlumpRheologyPointwise pw;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  if (!pw.dual) PetscFunctionReturn(0);
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscMalloc1(1, &cd));
  PetscCall(VecGetArrayRead(locX, &xa));
  if (locdX) PetscCall(VecGetArrayRead(locdX, &da));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    EvaluateCell(a, c, xa, NULL, da, cd); /* the correction's values and gradients in ul, ulx */
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscBool y = pw.dual(a->kdim, a->Nf, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ux[q * 24], da ? &cd->ul[q * 8] : NULL, da ? &cd->ulx[q * 24] : NULL, &cd->x[q * 3], constants, &S[(c * a->Nq + q) * prob->dualNs]);
      if (yielded) yielded[c * a->Nq + q] = y;
    }
  }
  if (locdX) PetscCall(VecRestoreArrayRead(locdX, &da));
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpAssemblyGetSizes(SlumpProblem prob, PetscInt *ncell, PetscInt *nq, PetscInt *dim)
{
  PetscFunctionBeginUser;
  *ncell = prob->assembly->ncell;
  *nq    = prob->assembly->Nq;
  *dim   = prob->assembly->kdim; /* the kernels' (3 when axisymmetric) */
  PetscFunctionReturn(0);
}

/* Integrals of n objective functions (each returning one value) over the
   domain, from a local solution with boundary values inserted (collective). */
PetscErrorCode SlumpAssembleIntegrals(SlumpProblem prob, PetscReal t, Vec locX, PetscInt n, PetscPointFunc obj[], PetscReal result[])
{
  SlumpAssembly      a = prob->assembly;
  PetscDS            ds;
  PetscSection       s;
  const PetscScalar *constants;
  PetscInt           nc;
  CellData          *cd;
  PetscFunctionBeginUser;
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(DMGetLocalSection(prob->dm, &s));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscLogEventBegin(SLUMP_Integral, 0, 0, 0, 0));
  PetscCall(PetscArrayzero(result, n));
  PetscCall(PetscMalloc1(1, &cd));
  const PetscScalar *xa;
  PetscCall(VecGetArrayRead(locX, &xa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    EvaluateCell(a, c, xa, NULL, NULL, cd);
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscReal wq = a->w[q] * cd->detJ * RadialWeight(a, cd, q);
      for (PetscInt k = 0; k < n; ++k) {
        PetscScalar v = 0.0;
        obj[k](a->kdim, a->Nf, 0, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], NULL, NULL, NULL, NULL, NULL, t, &cd->x[q * 3], nc, constants, &v);
        result[k] += wq * PetscRealPart(v);
      }
    }
  }
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  PetscCall(PetscLogEventEnd(SLUMP_Integral, 0, 0, 0, 0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, result, (PetscMPIInt)n, MPIU_REAL, MPIU_SUM, prob->comm));
  PetscFunctionReturn(0);
}

/* The L2 distance of fields 0 (velocity) and 1 (pressure) of locX from the
   functions fn[0], fn[1] (NULL: skip, err -1), with the quadrature of the
   cell loop and its weight (the radius, axisymmetric; collective). */
PetscErrorCode SlumpAssembleL2Diff(SlumpProblem prob, PetscReal t, Vec locX, SlumpPointFn fn[2], void *ctx, PetscReal err[2])
{
  SlumpAssembly      a = prob->assembly;
  const PetscScalar *xa;
  CellData          *cd;
  PetscReal          e[2] = {0.0, 0.0};
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(1, &cd));
  PetscCall(VecGetArrayRead(locX, &xa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    EvaluateCell(a, c, xa, NULL, NULL, cd);
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscReal wq = a->w[q] * cd->detJ * RadialWeight(a, cd, q);
      for (PetscInt f = 0; f < 2 && f < a->Nf; ++f) {
        PetscScalar v[3] = {0, 0, 0};
        if (!fn[f]) continue;
        PetscCall(fn[f](a->dim, t, &cd->x[q * 3], a->Nc[f], v, ctx));
        for (PetscInt k = 0; k < a->Nc[f]; ++k) e[f] += wq * PetscSqr(PetscRealPart(cd->u[q * 8 + a->uOff[f] + k] - v[k]));
      }
    }
  }
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(PetscFree(cd));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPIU_SUM, prob->comm));
  for (PetscInt f = 0; f < 2; ++f) err[f] = fn[f] ? PetscSqrtReal(e[f]) : -1.0;
  PetscFunctionReturn(0);
}

/* Over the faces of `label`: comp < 0: the flux int u . n (outward normal);
   comp >= 0: int u_comp; func given: int func, a PetscBdPointFunc handed
   every field's values (no gradients, t = 0) and the kernels' constants.
   Also returns the length. 3-point Gauss on each edge, the fields
   evaluated in the face's cell (collective). */
PetscErrorCode SlumpAssembleBoundaryIntegral(SlumpProblem prob, Vec locX, const char labelname[], PetscInt comp, PetscBdPointFunc func, PetscReal *integral, PetscReal *length)
{
  SlumpAssembly      a = prob->assembly;
  DMLabel            label;
  IS                 valIS;
  PetscFE            fe;
  PetscDS            ds;
  const PetscScalar *xa, *constants;
  PetscInt           nc;
  PetscReal          Q[2] = {0.0, 0.0};
  const PetscReal    gp[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  PetscInt           fStart, fEnd, dim = a->dim, N = a->NbTot;
  PetscFunctionBeginUser;
  PetscCheck(dim == 2, PETSC_COMM_SELF, PETSC_ERR_SUP, "Boundary flux is implemented in 2D");
  PetscCall(DMGetLabel(prob->dm, labelname, &label));
  PetscCall(DMGetField(prob->dm, 0, NULL, (PetscObject *)&fe));
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(DMPlexGetHeightStratum(prob->dm, 1, &fStart, &fEnd));
  PetscCall(VecGetArrayRead(locX, &xa));
  PetscCall(DMLabelGetValueIS(label, &valIS));
  {
    const PetscInt *vals;
    PetscInt        nv;
    PetscCall(ISGetLocalSize(valIS, &nv));
    PetscCall(ISGetIndices(valIS, &vals));
    for (PetscInt v = 0; v < nv; ++v) {
      IS              ptIS;
      const PetscInt *pts;
      PetscInt        np;
      PetscCall(DMLabelGetStratumIS(label, vals[v], &ptIS));
      if (!ptIS) continue;
      PetscCall(ISGetLocalSize(ptIS, &np));
      PetscCall(ISGetIndices(ptIS, &pts));
      for (PetscInt i = 0; i < np; ++i) {
        const PetscInt  face = pts[i], *supp, *cone;
        PetscInt        ns, c;
        PetscReal       xf[2][2], cc[3], area, nrm[2], len;
        if (face < fStart || face >= fEnd) continue;
        PetscCall(DMPlexGetSupportSize(prob->dm, face, &ns));
        if (ns != 1) continue;
        PetscCall(DMPlexGetSupport(prob->dm, face, &supp));
        c = supp[0] - a->cStart;
        if (c < 0 || c >= a->ncell) continue;
        PetscCall(DMPlexGetCone(prob->dm, face, &cone));
        for (PetscInt k = 0; k < 2; ++k) {
          PetscReal vol, cen[3];
          PetscCall(DMPlexComputeCellGeometryFVM(prob->dm, cone[k], &vol, cen, NULL));
          xf[k][0] = cen[0];
          xf[k][1] = cen[1];
        }
        PetscCall(DMPlexComputeCellGeometryFVM(prob->dm, supp[0], &area, cc, NULL));
        len    = PetscSqrtReal(PetscSqr(xf[1][0] - xf[0][0]) + PetscSqr(xf[1][1] - xf[0][1]));
        nrm[0] = (xf[1][1] - xf[0][1]) / len;
        nrm[1] = -(xf[1][0] - xf[0][0]) / len;
        if (nrm[0] * (0.5 * (xf[0][0] + xf[1][0]) - cc[0]) + nrm[1] * (0.5 * (xf[0][1] + xf[1][1]) - cc[1]) < 0) {
          nrm[0] = -nrm[0];
          nrm[1] = -nrm[1];
        }
        {
          const PetscReal *g = &a->geom[c * GEOMSIZE(dim)], *v0 = g, *invJ = g + dim + dim * dim;
          PetscReal        xi[6];
          PetscTabulation  T;
          for (PetscInt q = 0; q < 3; ++q) {
            const PetscReal s = 0.5 * (gp[q] + 1.0), x = xf[0][0] + s * (xf[1][0] - xf[0][0]), y = xf[0][1] + s * (xf[1][1] - xf[0][1]);
            for (PetscInt d = 0; d < 2; ++d) xi[q * 2 + d] = invJ[d * 2 + 0] * (x - v0[0]) + invJ[d * 2 + 1] * (y - v0[1]) - 1.0;
          }
          if (func) { /* every field's values (no gradients) at the face's points */
            PetscScalar uq[3][3 * SLUMP_MAX_FIELDS], zero[3 * SLUMP_MAX_FIELDS * 3] = {0}, f;
            PetscInt    zoff[SLUMP_MAX_FIELDS + 1] = {0};
            PetscCall(PetscArrayzero(&uq[0][0], 3 * 3 * SLUMP_MAX_FIELDS));
            for (PetscInt fi = 0; fi < a->Nf; ++fi) {
              PetscFE fef;
              PetscCall(DMGetField(prob->dm, fi, NULL, (PetscObject *)&fef));
              PetscCall(PetscFECreateTabulation(fef, 1, 3, xi, 0, &T));
              for (PetscInt q = 0; q < 3; ++q)
                for (PetscInt b = 0; b < a->Nb[fi]; ++b)
                  for (PetscInt k = 0; k < a->Nc[fi]; ++k) uq[q][a->uOff[fi] + k] += T->T[0][(q * a->Nb[fi] + b) * a->Nc[fi] + k] * xa[a->lidx[c * N + a->off[fi] + b]];
              PetscCall(PetscTabulationDestroy(&T));
            }
            for (PetscInt q = 0; q < 3; ++q) {
              const PetscReal s = 0.5 * (gp[q] + 1.0), xq[2] = {xf[0][0] + s * (xf[1][0] - xf[0][0]), xf[0][1] + s * (xf[1][1] - xf[0][1])};
              const PetscReal wr = a->axis >= 0 ? xq[a->axis] : 1.0;
              func(dim, a->Nf, 0, a->uOff, a->uOff_x, uq[q], zero, zero, zoff, zoff, NULL, NULL, NULL, 0.0, xq, nrm, nc, constants, &f);
              Q[0] += 0.5 * len * gw[q] * wr * PetscRealPart(f);
              Q[1] += 0.5 * len * gw[q] * wr;
            }
          } else {
            PetscCall(PetscFECreateTabulation(fe, 1, 3, xi, 0, &T));
            for (PetscInt q = 0; q < 3; ++q) {
              PetscReal u[2] = {0, 0};
              for (PetscInt b = 0; b < a->Nb[0]; ++b)
                for (PetscInt cc2 = 0; cc2 < 2; ++cc2) u[cc2] += T->T[0][(q * a->Nb[0] + b) * 2 + cc2] * PetscRealPart(xa[a->lidx[c * N + a->off[0] + b]]);
              const PetscReal s = 0.5 * (gp[q] + 1.0), wr = a->axis >= 0 ? xf[0][a->axis] + s * (xf[1][a->axis] - xf[0][a->axis]) : 1.0;
              Q[0] += 0.5 * len * gw[q] * wr * (comp < 0 ? u[0] * nrm[0] + u[1] * nrm[1] : u[comp]);
              Q[1] += 0.5 * len * gw[q] * wr;
            }
            PetscCall(PetscTabulationDestroy(&T));
          }
        }
      }
      PetscCall(ISRestoreIndices(ptIS, &pts));
      PetscCall(ISDestroy(&ptIS));
    }
    PetscCall(ISRestoreIndices(valIS, &vals));
  }
  PetscCall(ISDestroy(&valIS));
  PetscCall(VecRestoreArrayRead(locX, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Q, 2, MPIU_REAL, MPIU_SUM, prob->comm));
  *integral = Q[0];
  if (length) *length = Q[1];
  PetscFunctionReturn(0);
}

/* Local indices of field `field`'s dofs in the closure of every local cell
   (ncell x nb, row-major; the caller frees idx). */
PetscErrorCode SlumpProblemGetFieldClosure(SlumpProblem prob, PetscInt field, PetscInt *ncell, PetscInt *nb, PetscInt **idx, PetscInt *cStart)
{
  SlumpAssembly a = prob->assembly;
  PetscFunctionBeginUser;
  PetscCheck(a, prob->comm, PETSC_ERR_ORDER, "Call SlumpProblemSetUp() first");
  PetscCheck(field >= 0 && field < a->Nf, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "No field %" PetscInt_FMT, field);
  *ncell = a->ncell;
  *nb    = a->Nb[field];
  if (cStart) *cStart = a->cStart;
  PetscCall(PetscMalloc1(PetscMax(a->ncell * a->Nb[field], 1), idx));
  for (PetscInt c = 0; c < a->ncell; ++c)
    for (PetscInt b = 0; b < a->Nb[field]; ++b) (*idx)[c * a->Nb[field] + b] = a->lidx[c * a->NbTot + a->off[field] + b];
  PetscFunctionReturn(0);
}

/* ---- quadrature-point fields (the exact method's stress and strain rate) ----
   Layout: value k of quadrature point q of local cell c at
   ((c * nq + q) * ns + k). ns = dim * dim for the plane formulation (the
   tensor, row-major), 9 in the axisymmetric geometry (the 3 x 3 tensor
   with its hoop entry (2,2)), and dim for the anti-plane one (a vector).
   The weights carry the radius in the axisymmetric geometry. */

PetscErrorCode SlumpProblemGetQuadratureLayout(SlumpProblem prob, PetscInt *npoints, PetscInt *ns)
{
  SlumpAssembly a = prob->assembly;
  PetscFunctionBeginUser;
  PetscCheck(a, prob->comm, PETSC_ERR_ORDER, "Call SlumpProblemSetUp() first");
  if (npoints) *npoints = a->ncell * a->Nq;
  if (ns) *ns = a->Nc[0] == 1 ? a->dim : a->kdim * a->kdim;
  PetscFunctionReturn(0);
}

/* w[c * nq + q]: quadrature weight times |det J| of each local point */
PetscErrorCode SlumpProblemGetQuadratureWeights(SlumpProblem prob, PetscReal w[])
{
  SlumpAssembly a = prob->assembly;
  PetscFunctionBeginUser;
  PetscCheck(a, prob->comm, PETSC_ERR_ORDER, "Call SlumpProblemSetUp() first");
  for (PetscInt c = 0; c < a->ncell; ++c) {
    const PetscReal detJ = a->geom[c * GEOMSIZE(a->dim) + a->dim + 2 * a->dim * a->dim];
    for (PetscInt q = 0; q < a->Nq; ++q) w[c * a->Nq + q] = a->w[q] * detJ * QuadRadius(a, c, q);
  }
  PetscFunctionReturn(0);
}

/* g = grad u + grad u^T (plane) or grad w (anti-plane) of the velocity X
   (boundary values at t inserted) at every local quadrature point. */
PetscErrorCode SlumpProblemComputeQuadratureStrainRate(SlumpProblem prob, PetscReal t, Vec X, PetscScalar g[])
{
  SlumpAssembly      a = prob->assembly;
  const PetscInt     dim = a->dim, kd = a->kdim, nc = a->Nc[0], ns = nc == 1 ? dim : kd * kd, N = a->NbTot;
  const PetscScalar *xa;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(VecGetArrayRead(prob->locX, &xa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    const PetscReal *gm = &a->geom[c * GEOMSIZE(dim)], *invJ = gm + dim + dim * dim;
    const PetscInt  *li = &a->lidx[c * N];
    for (PetscInt q = 0; q < a->Nq; ++q) {
      PetscScalar ux[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, *gq = &g[(c * a->Nq + q) * ns];
      const PetscInt st = nc == 1 ? dim : kd; /* row stride of ux */
      for (PetscInt b = 0; b < a->Nb[0]; ++b) {
        const PetscInt   B = a->off[0] + b, cc = a->comp[B];
        const PetscReal *rg = &a->dphi[(q * MAXNB + B) * 3];
        for (PetscInt d = 0; d < dim; ++d) {
          PetscReal G = 0.0;
          for (PetscInt e = 0; e < dim; ++e) G += rg[e] * invJ[e * dim + d];
          ux[cc * st + d] += G * xa[li[B]];
        }
        if (a->axis >= 0 && cc == a->axis) ux[8] += a->phi[q * MAXNB + B] * xa[li[B]] / QuadRadius(a, c, q); /* u_r / r */
      }
      if (nc == 1)
        for (PetscInt d = 0; d < dim; ++d) gq[d] = ux[d];
      else
        for (PetscInt i = 0; i < kd; ++i)
          for (PetscInt j = 0; j < kd; ++j) gq[i * kd + j] = ux[i * kd + j] + ux[j * kd + i];
    }
  }
  PetscCall(VecRestoreArrayRead(prob->locX, &xa));
  PetscFunctionReturn(0);
}

/* F += int T : grad v over the velocity test functions v (T given at every
   local quadrature point, the layout above; F global, its free dofs). */
PetscErrorCode SlumpProblemAddQuadratureFlux(SlumpProblem prob, const PetscScalar T[], Vec F)
{
  SlumpAssembly  a = prob->assembly;
  const PetscInt dim = a->dim, kd = a->kdim, nc = a->Nc[0], ns = nc == 1 ? dim : kd * kd, N = a->NbTot;
  PetscScalar   *fa;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(prob->locF));
  PetscCall(VecGetArray(prob->locF, &fa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    const PetscReal *gm = &a->geom[c * GEOMSIZE(dim)], *invJ = gm + dim + dim * dim, detJ = gm[dim + 2 * dim * dim];
    const PetscInt  *li = &a->lidx[c * N];
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscScalar *Tq = &T[(c * a->Nq + q) * ns];
      const PetscReal    rq = QuadRadius(a, c, q), wq = a->w[q] * detJ * rq;
      for (PetscInt b = 0; b < a->Nb[0]; ++b) {
        const PetscInt   B = a->off[0] + b, cc = a->comp[B];
        const PetscReal *rg = &a->dphi[(q * MAXNB + B) * 3];
        PetscScalar      v  = 0.0;
        for (PetscInt d = 0; d < dim; ++d) {
          PetscReal G = 0.0;
          for (PetscInt e = 0; e < dim; ++e) G += rg[e] * invJ[e * dim + d];
          v += (nc == 1 ? Tq[d] : Tq[cc * kd + d]) * G;
        }
        if (a->axis >= 0 && cc == a->axis) v += Tq[8] * a->phi[q * MAXNB + B] / rq; /* T_tt v_r / r */
        fa[li[B]] += wq * v;
      }
    }
  }
  PetscCall(VecRestoreArray(prob->locF, &fa));
  PetscCall(DMLocalToGlobal(prob->dm, prob->locF, ADD_VALUES, F));
  PetscFunctionReturn(0);
}

/* The velocity (field 0, Nc components) at the nx x ny points of the grid
   x_i = lower[0] + i (upper[0] - lower[0])/(nx - 1), likewise y_j, stored at
   (j * nx + i) * Nc + c; points outside the mesh get 0 and found[] = 0
   (found may be NULL). Each local cell evaluates the grid points inside it
   (one tabulation per cell); a point on a shared edge is averaged over the
   cells that find it, on every rank (collective). */
PetscErrorCode SlumpProblemSampleVelocity(SlumpProblem prob, PetscReal t, Vec X, PetscInt nx, PetscInt ny, const PetscReal lower[2], const PetscReal upper[2], PetscReal u[], PetscReal found[])
{
  SlumpAssembly      a = prob->assembly;
  const PetscInt     dim = a->dim, Nc = a->Nc[0], N = a->NbTot, npt = nx * ny;
  const PetscReal    dx = (upper[0] - lower[0]) / (nx - 1), dy = (upper[1] - lower[1]) / (ny - 1);
  PetscFE            fe;
  const PetscScalar *xa;
  PetscReal         *cnt, *xi;
  PetscInt          *idx, cap = 64;
  PetscFunctionBeginUser;
  PetscCheck(dim == 2 && nx >= 2 && ny >= 2, prob->comm, PETSC_ERR_ARG_WRONG, "Velocity sampling needs a 2-D mesh and a grid of at least 2 x 2 points");
  PetscCall(DMGetField(prob->dm, 0, NULL, (PetscObject *)&fe));
  PetscCall(PetscCalloc1(npt, &cnt));
  PetscCall(PetscArrayzero(u, npt * Nc));
  PetscCall(PetscMalloc2(2 * cap, &xi, cap, &idx));
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(VecGetArrayRead(prob->locX, &xa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    const PetscReal *g = &a->geom[c * GEOMSIZE(dim)], *v0 = g, *J = g + dim, *invJ = g + dim + dim * dim;
    PetscReal        bmin[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, bmax[2] = {PETSC_MIN_REAL, PETSC_MIN_REAL};
    PetscInt         n = 0;
    /* the triangle's vertices: reference (-1,-1), (1,-1), (-1,1) */
    for (PetscInt k = 0; k < 3; ++k) {
      const PetscReal r[2] = {k == 1 ? 1.0 : -1.0, k == 2 ? 1.0 : -1.0};
      for (PetscInt d = 0; d < 2; ++d) {
        const PetscReal x = v0[d] + J[d * 2 + 0] * (r[0] + 1.0) + J[d * 2 + 1] * (r[1] + 1.0);
        bmin[d] = PetscMin(bmin[d], x);
        bmax[d] = PetscMax(bmax[d], x);
      }
    }
    const PetscInt i0 = PetscMax(0, (PetscInt)PetscCeilReal((bmin[0] - lower[0]) / dx - 1e-9)), i1 = PetscMin(nx - 1, (PetscInt)PetscFloorReal((bmax[0] - lower[0]) / dx + 1e-9));
    const PetscInt j0 = PetscMax(0, (PetscInt)PetscCeilReal((bmin[1] - lower[1]) / dy - 1e-9)), j1 = PetscMin(ny - 1, (PetscInt)PetscFloorReal((bmax[1] - lower[1]) / dy + 1e-9));
    for (PetscInt j = j0; j <= j1; ++j)
      for (PetscInt i = i0; i <= i1; ++i) {
        const PetscReal x = lower[0] + i * dx - v0[0], y = lower[1] + j * dy - v0[1];
        const PetscReal r0 = invJ[0] * x + invJ[1] * y - 1.0, r1 = invJ[2] * x + invJ[3] * y - 1.0, tol = 1e-10;
        if (r0 < -1.0 - tol || r1 < -1.0 - tol || r0 + r1 > tol) continue;
        if (n == cap) {
          PetscReal *nxi;
          PetscInt  *nidx;
          PetscCall(PetscMalloc2(4 * cap, &nxi, 2 * cap, &nidx));
          PetscCall(PetscArraycpy(nxi, xi, 2 * n));
          PetscCall(PetscArraycpy(nidx, idx, n));
          PetscCall(PetscFree2(xi, idx));
          xi  = nxi;
          idx = nidx;
          cap *= 2;
        }
        xi[2 * n]     = r0;
        xi[2 * n + 1] = r1;
        idx[n++]      = j * nx + i;
      }
    if (!n) continue;
    {
      PetscTabulation T;
      PetscCall(PetscFECreateTabulation(fe, 1, n, xi, 0, &T));
      for (PetscInt p = 0; p < n; ++p) {
        for (PetscInt b = 0; b < a->Nb[0]; ++b) {
          const PetscReal v = PetscRealPart(xa[a->lidx[c * N + a->off[0] + b]]);
          for (PetscInt k = 0; k < Nc; ++k) u[idx[p] * Nc + k] += T->T[0][(p * a->Nb[0] + b) * Nc + k] * v;
        }
        cnt[idx[p]] += 1.0;
      }
      PetscCall(PetscTabulationDestroy(&T));
    }
  }
  PetscCall(VecRestoreArrayRead(prob->locX, &xa));
  PetscCall(PetscFree2(xi, idx));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, u, (PetscMPIInt)(npt * Nc), MPIU_REAL, MPIU_SUM, prob->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, (PetscMPIInt)npt, MPIU_REAL, MPIU_SUM, prob->comm));
  for (PetscInt p = 0; p < npt; ++p) {
    if (cnt[p] > 0)
      for (PetscInt k = 0; k < Nc; ++k) u[p * Nc + k] /= cnt[p];
    if (found) found[p] = cnt[p] > 0 ? 1.0 : 0.0;
  }
  PetscCall(PetscFree(cnt));
  PetscFunctionReturn(0);
}

/* The yielded state at every quadrature point of the mesh, written by rank 0
   to path as x,y,yielded (1 flowing, 0 unyielded): the map the exact method
   measured (SlumpProblemSetYieldMap), or the rheology's criterion ||tau|| >
   tau_y at X (collective). */
PetscErrorCode SlumpProblemWriteYieldMap(SlumpProblem prob, PetscReal t, Vec X, const char path[])
{
  SlumpAssembly          a = prob->assembly;
  const PetscInt         n = a->ncell * a->Nq;
  SlumpRheologyPointwise pw;
  PetscDS                ds;
  const PetscScalar     *constants, *xa;
  PetscInt               nc;
  PetscReal             *loc, *all = NULL;
  PetscMPIInt            rank, size, nloc;
  PetscMPIInt           *counts = NULL, *displs = NULL;
  CellData              *cd;
  PetscFunctionBeginUser;
  PetscCheck(a->dim == 2, prob->comm, PETSC_ERR_SUP, "The yield map is written for 2-D meshes");
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscMalloc1(3 * PetscMax(n, 1), &loc));
  PetscCall(PetscMalloc1(1, &cd));
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(VecGetArrayRead(prob->locX, &xa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    EvaluateCell(a, c, xa, NULL, NULL, cd);
    for (PetscInt q = 0; q < a->Nq; ++q) {
      const PetscInt i = c * a->Nq + q;
      PetscScalar    v = 0.0;
      loc[3 * i]       = cd->x[q * 3];
      loc[3 * i + 1]   = cd->x[q * 3 + 1];
      if (prob->yieldMap) v = prob->yieldMap[i];
      else if (pw.yielded) pw.yielded(a->kdim, a->Nf, 0, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], NULL, NULL, NULL, NULL, NULL, t, &cd->x[q * 3], nc, constants, &v);
      else v = 1.0;
      loc[3 * i + 2] = PetscRealPart(v) > 0.5 ? 1.0 : 0.0;
    }
  }
  PetscCall(VecRestoreArrayRead(prob->locX, &xa));
  PetscCall(PetscFree(cd));
  PetscCallMPI(MPI_Comm_rank(prob->comm, &rank));
  PetscCallMPI(MPI_Comm_size(prob->comm, &size));
  nloc = (PetscMPIInt)(3 * n);
  if (!rank) PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCallMPI(MPI_Gather(&nloc, 1, MPI_INT, counts, 1, MPI_INT, 0, prob->comm));
  if (!rank) {
    PetscInt tot = 0;
    for (PetscMPIInt r = 0; r < size; ++r) {
      displs[r] = (PetscMPIInt)tot;
      tot += counts[r];
    }
    PetscCall(PetscMalloc1(PetscMax(tot, 1), &all));
  }
  PetscCallMPI(MPI_Gatherv(loc, nloc, MPIU_REAL, all, counts, displs, MPIU_REAL, 0, prob->comm));
  if (!rank) {
    char  tmp[PETSC_MAX_PATH_LEN + 8];
    FILE *fp  = NULL;
    int   err = 0;
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
    err = SlumpFileOpen(tmp, &fp);
    if (!err) err = SlumpFilePrintf(fp, "x,y,yielded\n");
    for (PetscMPIInt r = 0; r < size && !err; ++r)
      for (PetscInt i = displs[r]; i < displs[r] + counts[r] && !err; i += 3) err = SlumpFilePrintf(fp, "%.6g,%.6g,%d\n", (double)all[i], (double)all[i + 1], (int)all[i + 2]);
    if (fp) {
      int e2 = SlumpFileClose(&fp);
      if (!err) err = e2;
    }
    PetscCall(SlumpFileCommit(PETSC_COMM_SELF, err, tmp, path));
    PetscCall(PetscFree(all));
    PetscCall(PetscFree2(counts, displs));
  }
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetYieldMap(SlumpProblem prob, PetscInt n, const PetscReal yielded[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(prob->yieldMap));
  if (!yielded) PetscFunctionReturn(0);
  PetscCheck(n == prob->assembly->ncell * prob->assembly->Nq, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "The yield map has %d values; this rank has %d quadrature points", (int)n, (int)(prob->assembly->ncell * prob->assembly->Nq));
  PetscCall(PetscMalloc1(PetscMax(n, 1), &prob->yieldMap));
  PetscCall(PetscArraycpy(prob->yieldMap, yielded, n));
  PetscFunctionReturn(0);
}

/* The force the fluid exerts on a boundary, component comp: the consistent
   reaction F = -R(phi_h e_comp) of the steady residual, with phi_h the P2
   interpolant of a cut-off phi equal to 1 on that boundary and 0 on the
   other no-slip and open boundaries (free-slip planes may cross its
   support: their shear traction vanishes). As phi_h lies in the velocity
   space, R(phi_h e_comp) involves only the residuals of the constrained
   dofs on that boundary, whatever the cut-off: the discrete solution's
   exact reaction (it converges at the order of the stress, faster than the
   traction integrated over the boundary). With a plastic stress at the
   quadrature points (SlumpProblemSetPlasticStress: the exact method) the
   flux is the viscous one plus that stress (collective). */
typedef struct {
  SlumpCutoffFn fn;
  void         *ctx;
  PetscInt      comp;
} CutoffProjection;

static PetscErrorCode ProjectCutoff(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CutoffProjection *cp = (const CutoffProjection *)ctx;
  PetscReal               phi, dphi[3];
  cp->fn(x, cp->ctx, &phi, dphi);
  for (PetscInt c = 0; c < Nc; ++c) u[c] = c == cp->comp ? phi : 0.0;
  return 0;
}

static PetscErrorCode ProjectZero(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0.0;
  return 0;
}

PetscErrorCode SlumpProblemComputeBoundaryForce(SlumpProblem prob, PetscReal t, Vec X, SlumpCutoffFn cutoff, void *ctx, PetscInt comp, PetscReal *force)
{
  SlumpAssembly      a = prob->assembly;
  const PetscInt     dim = a->dim, kd = a->kdim;
  PetscDS            ds;
  PetscPointFunc     f0, f1;
  const PetscScalar *constants, *xa, *pa;
  PetscInt           nc;
  PetscReal          F = 0.0, tau0 = 0.0;
  PetscBool          plastic = prob->plasticStress ? PETSC_TRUE : PETSC_FALSE, has;
  Vec                locPhi;
  CellData          *cd;
  PetscFunctionBeginUser;
  PetscCheck(a->Nc[0] == dim && comp >= 0 && comp < dim, prob->comm, PETSC_ERR_ARG_WRONG, "The boundary force needs the plane formulation and a component below %d", (int)dim);
  {
    CutoffProjection cp = {cutoff, ctx, comp};
    PetscErrorCode (*funcs[SLUMP_MAX_FIELDS])(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar[], void *);
    void *ctxs[SLUMP_MAX_FIELDS];
    for (PetscInt f = 0; f < a->Nf; ++f) {
      funcs[f] = f ? ProjectZero : ProjectCutoff;
      ctxs[f]  = f ? NULL : (void *)&cp;
    }
    PetscCall(DMGetLocalVector(prob->dm, &locPhi));
    PetscCall(VecZeroEntries(locPhi));
    PetscCall(DMProjectFunctionLocal(prob->dm, t, funcs, ctxs, INSERT_ALL_VALUES, locPhi));
  }
  if (plastic) {
    PetscCall(SlumpRheologyHasParameter(prob->rheo, "yield_stress", &has));
    if (has) PetscCall(SlumpRheologyGetParameter(prob->rheo, "yield_stress", &tau0));
    if (tau0 > 0) PetscCall(SlumpProblemSetRheologyParameter(prob, "yield_stress", 0.0));
  }
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSGetConstants(ds, &nc, &constants));
  PetscCall(PetscDSGetResidual(ds, 0, &f0, &f1));
  PetscCall(PetscMalloc1(1, &cd));
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(VecGetArrayRead(prob->locX, &xa));
  PetscCall(VecGetArrayRead(locPhi, &pa));
  for (PetscInt c = 0; c < a->ncell; ++c) {
    EvaluateCell(a, c, xa, NULL, pa, cd); /* phi_h's values and gradients in ul, ulx */
    for (PetscInt q = 0; q < a->Nq; ++q) {
      PetscScalar        r0[3] = {0, 0, 0}, r1[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      const PetscScalar *v = &cd->ul[q * 8], *vx = &cd->ulx[q * 24];
      PetscReal          s = PetscAbsReal(PetscRealPart(v[comp]));
      for (PetscInt d = 0; d < dim; ++d) s += PetscAbsReal(PetscRealPart(vx[comp * kd + d]));
      if (s == 0.0) continue;
      if (f0) f0(kd, a->Nf, 0, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], NULL, NULL, NULL, NULL, NULL, t, &cd->x[q * 3], nc, constants, r0);
      if (f1) f1(kd, a->Nf, 0, a->uOff, a->uOff_x, &cd->u[q * 8], &cd->ut[q * 8], &cd->ux[q * 24], NULL, NULL, NULL, NULL, NULL, t, &cd->x[q * 3], nc, constants, r1);
      if (plastic) /* the whole tensor: the contraction below uses the rows of comp (and the hoop entry) */
        for (PetscInt i = 0; i < kd * kd; ++i) r1[i] += prob->plasticStress[(c * a->Nq + q) * kd * kd + i];
      {
        /* phi_h e_comp's value and gradient (with its hoop entry, axisymmetric) */
        PetscReal val = PetscRealPart(r0[comp] * v[comp]);
        for (PetscInt i = 0; i < kd * kd; ++i) val += PetscRealPart(r1[i] * vx[i]);
        F -= a->w[q] * cd->detJ * RadialWeight(a, cd, q) * val;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(locPhi, &pa));
  PetscCall(VecRestoreArrayRead(prob->locX, &xa));
  PetscCall(DMRestoreLocalVector(prob->dm, &locPhi));
  PetscCall(PetscFree(cd));
  if (plastic && tau0 > 0) PetscCall(SlumpProblemSetRheologyParameter(prob, "yield_stress", tau0));
  PetscCall(MPIU_Allreduce(&F, force, 1, MPIU_REAL, MPIU_SUM, prob->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetPlasticStress(SlumpProblem prob, PetscInt n, const PetscScalar S[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(prob->plasticStress));
  if (!S) PetscFunctionReturn(0);
  PetscCheck(n == prob->assembly->ncell * prob->assembly->Nq * prob->assembly->kdim * prob->assembly->kdim, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "The plastic stress has %d values; this rank needs %d (plane formulation)", (int)n, (int)(prob->assembly->ncell * prob->assembly->Nq * prob->assembly->kdim * prob->assembly->kdim));
  PetscCall(PetscMalloc1(PetscMax(n, 1), &prob->plasticStress));
  PetscCall(PetscArraycpy(prob->plasticStress, S, n));
  PetscFunctionReturn(0);
}
