/* Scene registry and helpers. */
#include "slumpscene.h"

typedef struct {
  char               name[64];
  char               description[160];
  SlumpSceneCreateFn create;
} SceneEntry;

static SceneEntry scenes[32];
static PetscInt   nscenes = 0;

PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Poiseuille(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Decay(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_CouetteCessation(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_MMSStokes(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_CouetteStartup(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_VerticalChute(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Bagnold(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Duct(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_PoiseuilleCessation(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_DuctCessation(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_CavityCessation(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Cavity(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Cylinder(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_GranularCylinder(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_Expansion(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_LevelSetRotation(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_DamBreak(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_BinghamDamBreak(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_ColumnCollapse(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_ColumnChute(SlumpScene, SlumpProblem, MPI_Comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate_ChupinColumn(SlumpScene, SlumpProblem, MPI_Comm);

PetscErrorCode SlumpSceneRegister(const char name[], const char description[], SlumpSceneCreateFn create)
{
  PetscFunctionBeginUser;
  PetscCheck(nscenes < 32, PETSC_COMM_SELF, PETSC_ERR_SUP, "Too many scenes");
  PetscCall(PetscStrncpy(scenes[nscenes].name, name, sizeof(scenes[nscenes].name)));
  PetscCall(PetscStrncpy(scenes[nscenes].description, description, sizeof(scenes[nscenes].description)));
  scenes[nscenes++].create = create;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (nscenes) PetscFunctionReturn(0);
  PetscCall(SlumpSceneRegister("couette_cessation", "Bingham plane Couette flow, top plate stopped at t = 0 (the demo): adaptive BDF2 to arrest", SlumpSceneCreate_CouetteCessation));
  PetscCall(SlumpSceneRegister("poiseuille_cessation", "Bingham plane Poiseuille flow (steady state by KINSOL), driving removed at t = 0: arrest and energy bound", SlumpSceneCreate_PoiseuilleCessation));
  PetscCall(SlumpSceneRegister("duct_cessation", "anti-plane Bingham flow in a square duct (steady state by KINSOL), pressure gradient removed at t = 0", SlumpSceneCreate_DuctCessation));
  PetscCall(SlumpSceneRegister("cavity_cessation", "Bingham lid-driven cavity (steady state by KINSOL), lid stopped at t = 0; enclosed flow", SlumpSceneCreate_CavityCessation));
  PetscCall(SlumpSceneRegister("cavity", "steady Bingham lid-driven cavity (Re >= 0): stream-function maximum, vortex centre, unyielded areas", SlumpSceneCreate_Cavity));
  PetscCall(SlumpSceneRegister("cylinder", "steady Bingham flow past a cylinder between walls (blockage 1/2) or in a uniform stream (Gmsh meshes): drag coefficient", SlumpSceneCreate_Cylinder));
  PetscCall(SlumpSceneRegister("expansion", "steady Bingham flow through a planar 1:2 sudden expansion (Gmsh mesh): corner dead zone, developed flow downstream", SlumpSceneCreate_Expansion));
  PetscCall(SlumpSceneRegister("poiseuille", "steady Bingham plane Poiseuille flow driven by a pressure gradient; analytic solution", SlumpSceneCreate_Poiseuille));
  PetscCall(SlumpSceneRegister("decay", "Newtonian flow between plates decaying as sin(pi y) exp(-pi^2 nu t); analytic solution", SlumpSceneCreate_Decay));
  PetscCall(SlumpSceneRegister("couette_startup", "Newtonian Couette start-up, top plate accelerating as 1 - exp(-t/tau); exact series solution", SlumpSceneCreate_CouetteStartup));
  PetscCall(SlumpSceneRegister("bagnold", "mu(I) layer on a rough inclined plane (Chauchat & Medale); analytic Bagnold profile", SlumpSceneCreate_Bagnold));
  PetscCall(SlumpSceneRegister("granular_cylinder", "mu(I) chute flow over a cylinder between rough walls under a confining pressure (Chauchat & Medale 2014): flow rate, drag", SlumpSceneCreate_GranularCylinder));
  PetscCall(SlumpSceneRegister("vertical_chute", "mu(I) flow between rough vertical walls at uniform pressure; analytic profile and plug", SlumpSceneCreate_VerticalChute));
  PetscCall(SlumpSceneRegister("duct", "anti-plane Bingham flow in a square duct (Mosolov problem); flow threshold Bn_c = 1/(2 + sqrt(pi))", SlumpSceneCreate_Duct));
  PetscCall(SlumpSceneRegister("levelset_rotation", "circle or slotted disc in a rotating field (prescribed velocity): level-set transport and reinitialisation", SlumpSceneCreate_LevelSetRotation));
  PetscCall(SlumpSceneRegister("dam_break", "Newtonian column collapse with air (two-phase, level set): box 0.42 x 0.44 m, column 0.114 m (Cruchaga et al.)", SlumpSceneCreate_DamBreak));
  PetscCall(SlumpSceneRegister("bingham_dam_break", "Bingham column collapse with air (Liu et al., Riber's thesis): Re = 1e-3, Bn by -bn, to arrest", SlumpSceneCreate_BinghamDamBreak));
  PetscCall(SlumpSceneRegister("column_collapse", "Granular column collapse, mu(I) with air (Lagree et al. 2011, Riber's thesis): aspect ratio by -aspect_ratio (0.5), Coulomb floor mu_w 0.6", SlumpSceneCreate_ColumnCollapse));
  PetscCall(SlumpSceneRegister("column_chute", "The mu(I) column of column_collapse released from -release_height h_r (0.5): starts at the impact, t = sqrt(2 h_r/g), velocity sqrt(2 g h_r) (Riber's thesis sec. 4.3.3, in 2-D)", SlumpSceneCreate_ColumnChute));
  PetscCall(SlumpSceneRegister("chupin_column", "Drucker-Prager column of Chupin, Dubois & Phan (SI): 0.20 x 0.14 m (-column_height 0.40), tan 24 deg (-friction_angle), Coulomb floor -wall rough|smooth", SlumpSceneCreate_ChupinColumn));
  PetscCall(SlumpSceneRegister("mms_stokes", "manufactured Stokes solution on the unit square (Dirichlet + traction); spatial orders", SlumpSceneCreate_MMSStokes));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneView(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneRegisterAll());
  for (PetscInt i = 0; i < nscenes; ++i) PetscCall(PetscPrintf(comm, "%-20s %s\n", scenes[i].name, scenes[i].description));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate(MPI_Comm comm, const char name[], SlumpProblem prob, SlumpScene *scene)
{
  char known[512] = "";
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneRegisterAll());
  for (PetscInt i = 0; i < nscenes; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(scenes[i].name, name, &same));
    if (same) {
      PetscCall(PetscNew(scene));
      PetscCall(PetscStrncpy((*scene)->name, name, sizeof((*scene)->name)));
      (*scene)->tfinal = 1.0;
      (*scene)->dtout  = 0.1;
      PetscCall(scenes[i].create(*scene, prob, comm));
      {
        /* -geometry axisymmetric is read by the scenes that offer it */
        char      geom[32] = "";
        PetscBool set, planar;
        PetscInt  axis;
        PetscCall(PetscOptionsGetString(NULL, NULL, "-geometry", geom, sizeof(geom), &set));
        PetscCall(SlumpProblemGetAxisymmetric(prob, &axis));
        PetscCall(PetscStrcmp(geom, "planar", &planar));
        PetscCheck(!set || axis >= 0 || planar, comm, PETSC_ERR_USER_INPUT, "-geometry %s is not available for the %s scene; the axisymmetric geometry is offered by poiseuille, poiseuille_cessation, decay, mms_stokes and the column scenes (dam_break, bingham_dam_break, column_collapse, column_chute, chupin_column)", geom, name);
      }
      PetscFunctionReturn(0);
    }
  }
  for (PetscInt i = 0; i < nscenes; ++i) {
    if (i) PetscCall(PetscStrlcat(known, ", ", sizeof(known)));
    PetscCall(PetscStrlcat(known, scenes[i].name, sizeof(known)));
  }
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "Unknown scene '%s' (-scene); accepted: %s (or 'list')", name, known);
}

PetscErrorCode SlumpSceneDestroy(SlumpScene *scene)
{
  PetscFunctionBeginUser;
  if (*scene) PetscCall(PetscFree((*scene)->ctx));
  PetscCall(PetscFree(*scene));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneAddParameter(SlumpScene scene, const char name[], PetscReal value)
{
  PetscFunctionBeginUser;
  PetscCheck(scene->nparam < SLUMP_SCENE_MAX_ITEMS, PETSC_COMM_SELF, PETSC_ERR_SUP, "Too many scene parameters");
  PetscCall(PetscStrncpy(scene->pname[scene->nparam], name, 32));
  scene->pvalue[scene->nparam++] = value;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneAddResult(SlumpScene scene, const char name[], PetscReal value)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < scene->nresult; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(scene->rname[i], name, &same));
    if (same) {
      scene->rvalue[i] = value;
      PetscFunctionReturn(0);
    }
  }
  PetscCheck(scene->nresult < SLUMP_SCENE_MAX_ITEMS, PETSC_COMM_SELF, PETSC_ERR_SUP, "Too many scene results");
  PetscCall(PetscStrncpy(scene->rname[scene->nresult], name, 32));
  scene->rvalue[scene->nresult++] = value;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreateMesh(SlumpScene scene, MPI_Comm comm, const PetscReal lower[2], const PetscReal upper[2], DM *dm)
{
  char      file[PETSC_MAX_PATH_LEN] = "";
  PetscInt  nx = scene->mesh_n[0], ny = scene->mesh_n[1], n = 0;
  PetscBool has_file, has_n;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Mesh", "SlumpScene");
  PetscCall(PetscOptionsString("-mesh_file", "Gmsh .msh file (physical names become boundary labels)", "", file, file, sizeof(file), &has_file));
  PetscCall(PetscOptionsInt("-mesh_n", "Cells along x and y of the rectangle (a square grid; -mesh_nx, -mesh_ny override)", "", n, &n, &has_n));
  if (has_n) {
    PetscCheck(n > 0, comm, PETSC_ERR_USER_INPUT, "-mesh_n must be a positive integer; got %" PetscInt_FMT, n);
    nx = ny = n;
  }
  PetscCall(PetscOptionsInt("-mesh_nx", "Cells along x of the rectangle", "", nx, &nx, NULL));
  PetscCall(PetscOptionsInt("-mesh_ny", "Cells along y of the rectangle", "", ny, &ny, NULL));
  PetscOptionsEnd();
  scene->mesh_n[0] = nx;
  scene->mesh_n[1] = ny;
  if (has_file && file[0]) PetscCall(SlumpMeshCreateGmsh(comm, file, dm));
  else {
    PetscCheck(!has_file, comm, PETSC_ERR_USER_INPUT, "-mesh_file needs a file name");
    PetscCall(SlumpMeshCreateRectangle(comm, nx, ny, lower, upper, dm));
  }
  /* the mesh is distributed already (SlumpMeshDistribute, METIS with a fixed
     seed): without this DMSetFromOptions repartitions it with PETSc's default
     parallel partitioner, whose partition changes from run to run (2-rank
     results then differed between runs) */
  PetscCall(DMPlexDistributeSetDefault(*dm, PETSC_FALSE));
  PetscCall(DMSetFromOptions(*dm));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscFunctionReturn(0);
}
