/* The rheology object: registry (PetscFunctionList), named parameters read
 * from options and checked, host-side evaluation. */
#include "rheologyimpl.h"

static PetscFunctionList SlumpRheologyList       = NULL;
static PetscBool         SlumpRheologyRegistered = PETSC_FALSE;
static char              SlumpRheologyNames[1024] = "";

PetscErrorCode SlumpRheologyRegister(const char name[], PetscErrorCode (*create)(SlumpRheology))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&SlumpRheologyList, name, create));
  if (SlumpRheologyNames[0]) PetscCall(PetscStrlcat(SlumpRheologyNames, ", ", sizeof(SlumpRheologyNames)));
  PetscCall(PetscStrlcat(SlumpRheologyNames, name, sizeof(SlumpRheologyNames)));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (SlumpRheologyRegistered) PetscFunctionReturn(0);
  SlumpRheologyRegistered = PETSC_TRUE;
  PetscCall(SlumpRheologyRegister(SLUMP_RHEOLOGY_NEWTONIAN, SlumpRheologyCreate_Newtonian));
  PetscCall(SlumpRheologyRegister(SLUMP_RHEOLOGY_PAPANASTASIOU, SlumpRheologyCreate_Papanastasiou));
  PetscCall(SlumpRheologyRegister(SLUMP_RHEOLOGY_BERCOVIER, SlumpRheologyCreate_Bercovier));
  PetscCall(SlumpRheologyRegister(SLUMP_RHEOLOGY_BINGHAM_SIMPLE, SlumpRheologyCreate_BinghamSimple));
  PetscCall(SlumpRheologyRegister_HerschelBulkley());
  PetscCall(SlumpRheologyRegister_MuI());
  PetscCall(SlumpRheologyRegister_DruckerPrager());
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyListTypes(MPI_Comm comm, char list[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegisterAll());
  PetscCall(PetscStrncpy(list, SlumpRheologyNames, len));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCreate(MPI_Comm comm, SlumpRheology *rheo)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegisterAll());
  PetscCall(PetscNew(rheo));
  (*rheo)->comm = comm;
  (*rheo)->ireg = -1;
  PetscCall(SlumpRheologySetType(*rheo, SLUMP_RHEOLOGY_NEWTONIAN));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyDestroy(SlumpRheology *rheo)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*rheo));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyAddParameter(SlumpRheology rheo, const char name[], const char option[], const char help[], PetscReal value, PetscReal lower, PetscBool strict)
{
  PetscFunctionBeginUser;
  PetscCheck(rheo->nparam < SLUMP_RHEOLOGY_MAX_PARAM, rheo->comm, PETSC_ERR_PLIB, "Too many rheology parameters");
  SlumpRheologyParam *q = &rheo->param[rheo->nparam++];
  q->name   = name;
  q->option = option;
  q->help   = help;
  q->value  = value;
  q->lower  = lower;
  q->strict = strict;
  PetscFunctionReturn(0);
}

/* The regularisation parameter of a yield term: m (Papanastasiou, larger is
   stiffer) or eps (Bercovier-Engelman, simple; smaller is stiffer). */
PetscErrorCode SlumpRheologyAddRegularisation(SlumpRheology rheo, SlumpRegKind kind)
{
  PetscFunctionBeginUser;
  rheo->ireg               = rheo->nparam;
  rheo->reg_larger_stiffer = kind == SLUMP_REG_PAPANASTASIOU ? PETSC_TRUE : PETSC_FALSE;
  if (kind == SLUMP_REG_PAPANASTASIOU) PetscCall(SlumpRheologyAddParameter(rheo, "m", "-rheology_papanastasiou_m", "Papanastasiou exponent m", 1e3, 0.0, PETSC_TRUE));
  else if (kind == SLUMP_REG_BERCOVIER) PetscCall(SlumpRheologyAddParameter(rheo, "eps", "-rheology_bercovier_eps", "Bercovier-Engelman epsilon", 1e-3, 0.0, PETSC_TRUE));
  else PetscCall(SlumpRheologyAddParameter(rheo, "eps", "-rheology_simple_eps", "Simple regularisation epsilon", 1e-3, 0.0, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* Changing type keeps the values of parameters the new type also has
   (viscosity, yield stress), so a scene may set them before the user's
   -rheology_type is read. */
PetscErrorCode SlumpRheologySetType(SlumpRheology rheo, SlumpRheologyType type)
{
  PetscErrorCode (*create)(SlumpRheology);
  SlumpRheologyParam old[SLUMP_RHEOLOGY_MAX_PARAM];
  PetscInt           nold = rheo->nparam;
  char               known[512];

  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegisterAll());
  PetscCall(PetscFunctionListFind(SlumpRheologyList, type, &create));
  if (!create) {
    PetscCall(SlumpRheologyListTypes(rheo->comm, known, sizeof(known)));
    SETERRQ(rheo->comm, PETSC_ERR_USER_INPUT, "Unknown rheology '%s' (-rheology_type); accepted: %s", type, known);
  }
  PetscCall(PetscArraycpy(old, rheo->param, nold));
  rheo->nparam             = 0;
  rheo->ireg               = -1;
  rheo->reg_larger_stiffer = PETSC_TRUE;
  rheo->ops.check          = NULL;
  rheo->ops.plugviscosity  = NULL;
  rheo->plastic            = NULL;
  PetscCall(PetscStrncpy(rheo->type, type, sizeof(rheo->type)));
  PetscCall((*create)(rheo));
  for (PetscInt i = 0; i < rheo->nparam; ++i)
    for (PetscInt j = 0; j < nold; ++j) {
      PetscBool same;
      PetscCall(PetscStrcmp(rheo->param[i].name, old[j].name, &same));
      if (same) rheo->param[i].value = old[j].value;
    }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetType(SlumpRheology rheo, SlumpRheologyType *type)
{
  PetscFunctionBeginUser;
  *type = rheo->type;
  PetscFunctionReturn(0);
}

static PetscErrorCode FindParam(SlumpRheology rheo, const char name[], PetscInt *idx)
{
  PetscFunctionBeginUser;
  *idx = -1;
  for (PetscInt i = 0; i < rheo->nparam; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(rheo->param[i].name, name, &same));
    if (same) *idx = i;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyHasParameter(SlumpRheology rheo, const char name[], PetscBool *has)
{
  PetscInt i;
  PetscFunctionBeginUser;
  PetscCall(FindParam(rheo, name, &i));
  *has = i >= 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologySetParameter(SlumpRheology rheo, const char name[], PetscReal value)
{
  PetscInt i;
  PetscFunctionBeginUser;
  PetscCall(FindParam(rheo, name, &i));
  PetscCheck(i >= 0, rheo->comm, PETSC_ERR_USER_INPUT, "Rheology '%s' has no parameter '%s'", rheo->type, name);
  rheo->param[i].value = value;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetParameter(SlumpRheology rheo, const char name[], PetscReal *value)
{
  PetscInt i;
  PetscFunctionBeginUser;
  PetscCall(FindParam(rheo, name, &i));
  PetscCheck(i >= 0, rheo->comm, PETSC_ERR_USER_INPUT, "Rheology '%s' has no parameter '%s'", rheo->type, name);
  *value = rheo->param[i].value;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCopy(SlumpRheology src, SlumpRheology dst)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologySetType(dst, src->type));
  for (PetscInt i = 0; i < src->nparam; ++i) dst->param[i].value = src->param[i].value;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCheck(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < rheo->nparam; ++i) {
    const SlumpRheologyParam *q  = &rheo->param[i];
    PetscBool                 ok = q->strict ? (q->value > q->lower) : (q->value >= q->lower);
    PetscCheck(ok && !PetscIsInfOrNanReal(q->value), rheo->comm, PETSC_ERR_USER_INPUT, "%s (%s of rheology '%s') must be %s %g; got %g", q->option, q->name, rheo->type, q->strict ? ">" : ">=", (double)q->lower, (double)q->value);
  }
  if (rheo->ops.check) PetscCall(rheo->ops.check(rheo));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologySetFromOptions(SlumpRheology rheo)
{
  char      type[64];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscOptionsBegin(rheo->comm, NULL, "Rheology", "SlumpRheology");
  PetscCall(PetscOptionsString("-rheology_type", "Constitutive model", "SlumpRheologySetType", rheo->type, type, sizeof(type), &set));
  PetscOptionsEnd();
  if (set) PetscCall(SlumpRheologySetType(rheo, type));
  PetscOptionsBegin(rheo->comm, NULL, "Rheology parameters", "SlumpRheology");
  for (PetscInt i = 0; i < rheo->nparam; ++i) PetscCall(PetscOptionsReal(rheo->param[i].option, rheo->param[i].help, "SlumpRheologySetParameter", rheo->param[i].value, &rheo->param[i].value, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpRheologyCheck(rheo));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyView(SlumpRheology rheo, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "rheology %s:", rheo->type));
  for (PetscInt i = 0; i < rheo->nparam; ++i) PetscCall(PetscViewerASCIIPrintf(viewer, " %s=%g", rheo->param[i].name, (double)rheo->param[i].value));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetConstants(SlumpRheology rheo, PetscInt *n, PetscScalar params[])
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < rheo->nparam; ++i) params[i] = rheo->param[i].value;
  *n = rheo->nparam;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyEvaluate(SlumpRheology rheo, PetscReal gdot, PetscReal p, PetscReal *eta, PetscReal *deta_dgdot, PetscReal *deta_dp)
{
  PetscScalar cst[SLUMP_C_NUM] = {0}, *prm = &cst[SLUMP_C_RHEO]; /* laid out as the kernels' constants, no surface table */
  PetscReal   a, b, c, ty;
  PetscInt    n;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetConstants(rheo, &n, prm));
  rheo->kernel(prm, gdot, p, NULL, &a, &b, &c, &ty);
  if (eta) *eta = a;
  if (deta_dgdot) *deta_dgdot = b;
  if (deta_dp) *deta_dp = c;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyEvaluateAt(SlumpRheology rheo, PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *deta_dgdot, PetscReal *deta_dp, PetscReal *yield_stress)
{
  PetscScalar cst[SLUMP_C_NUM] = {0}, *prm = &cst[SLUMP_C_RHEO]; /* laid out as the kernels' constants, no surface table */
  PetscReal   a, b, c, ty;
  PetscInt    n;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetConstants(rheo, &n, prm));
  rheo->kernel(prm, gdot, p, x, &a, &b, &c, &ty);
  if (eta) *eta = a;
  if (deta_dgdot) *deta_dgdot = b;
  if (deta_dp) *deta_dp = c;
  if (yield_stress) *yield_stress = ty;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetYieldStress(SlumpRheology rheo, PetscReal p, PetscReal *tau_y)
{
  PetscScalar cst[SLUMP_C_NUM] = {0}, *prm = &cst[SLUMP_C_RHEO]; /* laid out as the kernels' constants, no surface table */
  PetscReal   a, b, c;
  PetscInt    n;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetConstants(rheo, &n, prm));
  rheo->kernel(prm, 1.0, p, NULL, &a, &b, &c, tau_y);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetPlugViscosity(SlumpRheology rheo, PetscReal p, PetscReal *eta_plug)
{
  PetscFunctionBeginUser;
  if (rheo->ops.plugviscosity) PetscCall(rheo->ops.plugviscosity(rheo, p, eta_plug));
  else PetscCall(SlumpRheologyEvaluate(rheo, 0.0, p, eta_plug, NULL, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetRegularisation(SlumpRheology rheo, const char **name, PetscReal *value, PetscBool *stiffer_when_larger)
{
  PetscFunctionBeginUser;
  if (rheo->ireg < 0) {
    if (name) *name = NULL;
    if (value) *value = 0.0;
  } else {
    if (name) *name = rheo->param[rheo->ireg].name;
    if (value) *value = rheo->param[rheo->ireg].value;
  }
  if (stiffer_when_larger) *stiffer_when_larger = rheo->reg_larger_stiffer;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyGetPointwise(SlumpRheology rheo, SlumpRheologyPointwise *pw)
{
  PetscFunctionBeginUser;
  *pw = rheo->pointwise;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyHasPlasticPart(SlumpRheology rheo, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = rheo->plastic ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyEvaluatePlastic(SlumpRheology rheo, PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *tau_y, PetscReal *R, PetscReal *dR)
{
  PetscScalar cst[SLUMP_C_NUM] = {0}, *prm = &cst[SLUMP_C_RHEO]; /* laid out as the kernels' constants, no surface table */
  PetscInt    n;
  PetscFunctionBeginUser;
  PetscCheck(rheo->plastic, rheo->comm, PETSC_ERR_SUP, "Rheology '%s' has no plastic part", rheo->type);
  PetscCall(SlumpRheologyGetConstants(rheo, &n, prm));
  rheo->plastic(prm, gdot, p, x, tau_y, R, dR);
  PetscFunctionReturn(0);
}
