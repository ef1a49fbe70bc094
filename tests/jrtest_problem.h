/*
   Test helpers: a matrices model, its harmonic balance and continuation from dense arrays (Problem), with options
   set beforehand (Options).
*/
#if !defined(JRTEST_PROBLEM_H)
#define JRTEST_PROBLEM_H
#include "jrtest.h"

/* n x n MPIAIJ from a dense row-major array */
static PetscErrorCode DenseToMat(PetscInt n, const double *A, Mat *M)
{
  PetscInt lo, hi;

  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, n, NULL, n, NULL, M));
  PetscCall(MatGetOwnershipRange(*M, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++)
    for (PetscInt j = 0; j < n; j++)
      if (A[i * n + j] != 0.0) PetscCall(MatSetValue(*M, i, j, A[i * n + j], INSERT_VALUES));
  PetscCall(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* element table from arrays; type names of the elements given per element */
typedef struct {
  const char *type;
  PetscInt    a, b, na, nb;
  double      kt, kn, mu, n0;
} El;

static PetscErrorCode MakeElements(PetscInt n, const El *e, JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(el, sizeof(*el)));
  el->n = n;
  PetscCall(PetscMalloc5(n, &el->type, n, &el->dof_a, n, &el->dof_b, n, &el->ndof_a, n, &el->ndof_b));
  PetscCall(PetscMalloc4(n, &el->kt, n, &el->kn, n, &el->mu, n, &el->n0));
  for (PetscInt i = 0; i < n; i++) {
    PetscInt t = -1;
    for (PetscInt k = 0; k < el->ntypes; k++)
      if (!strcmp(el->typename[k], e[i].type)) t = k;
    if (t < 0) {
      t = el->ntypes++;
      PetscCall(PetscStrncpy(el->typename[t], e[i].type, sizeof(el->typename[t])));
    }
    el->type[i]   = t;
    el->dof_a[i]  = e[i].a;
    el->dof_b[i]  = e[i].b;
    el->ndof_a[i] = e[i].na;
    el->ndof_b[i] = e[i].nb;
    el->kt[i]     = e[i].kt;
    el->kn[i]     = e[i].kn;
    el->mu[i]     = e[i].mu;
    el->n0[i]     = e[i].n0;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode FreeElements(JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree5(el->type, el->dof_a, el->dof_b, el->ndof_a, el->ndof_b));
  PetscCall(PetscFree4(el->kt, el->kn, el->mu, el->n0));
  PetscCall(PetscFree(el->joint));
  PetscCall(PetscFree(el->pos));
  PetscCall(PetscFree(el->phi));
  PetscFunctionReturn(0);
}

static const PetscInt *jr_joints = NULL; /* ProblemCreate: the elements' joints (first reduction), if set */
static PetscInt        jr_njoints = 0;
static const double   *jr_pos     = NULL; /* ProblemCreate: the elements' positions (3 each), if set */
static const double   *jr_phi     = NULL; /* ProblemCreate: the elements' stuck-mode coordinates (2 each), if set */
static JRJointMotion   jr_jmotion = JR_JOINT_MOTION_MEAN; /* ProblemCreate: how the joints' members move */

/* a model + HBM (+ continuation) built from dense K, M, C and elements, options set beforehand */
typedef struct {
  JRModel model;
  JRHBM   hbm;
  JRCont  cont;
} Problem;

static PetscErrorCode ProblemCreate(PetscInt n, const double *K, const double *M, const double *C, PetscInt ne, const El *e, Problem *p)
{
  Mat        Km, Mm, Cm = NULL;
  JRElements el;

  PetscFunctionBeginUser;
  PetscCall(DenseToMat(n, K, &Km));
  PetscCall(DenseToMat(n, M, &Mm));
  if (C) PetscCall(DenseToMat(n, C, &Cm));
  PetscCall(JRModelCreate(PETSC_COMM_WORLD, &p->model));
  PetscCall(JRModelSetType(p->model, JRMODELMATRICES));
  PetscCall(JRModelSetMatrices(p->model, Km, Mm, Cm));
  if (ne) {
    PetscCall(MakeElements(ne, e, &el));
    if (jr_joints) {
      el.njoints = jr_njoints;
      PetscCall(PetscMalloc1(ne, &el.joint));
      PetscCall(PetscArraycpy(el.joint, jr_joints, ne));
    }
    if (jr_pos) {
      PetscCall(PetscMalloc1(3 * ne, &el.pos));
      for (PetscInt i = 0; i < 3 * ne; i++) el.pos[i] = jr_pos[i];
    }
    if (jr_phi) {
      PetscCall(PetscMalloc1(2 * ne, &el.phi));
      for (PetscInt i = 0; i < 2 * ne; i++) el.phi[i] = jr_phi[i];
    }
    PetscCall(JRModelSetElements(p->model, &el));
    PetscCall(FreeElements(&el));
  }
  PetscCall(JRModelSetUp(p->model));
  PetscCall(JRHBMCreate(PETSC_COMM_WORLD, &p->hbm));
  PetscCall(JRHBMSetModel(p->hbm, p->model));
  PetscCall(JRHBMSetJointMotion(p->hbm, jr_jmotion));
  PetscCall(JRHBMSetFromOptions(p->hbm));
  PetscCall(JRContCreate(PETSC_COMM_WORLD, &p->cont));
  PetscCall(JRContSetHBM(p->cont, p->hbm));
  PetscCall(JRContSetFromOptions(p->cont));
  PetscCall(JRHBMSetUp(p->hbm));
  PetscCall(MatDestroy(&Km));
  PetscCall(MatDestroy(&Mm));
  PetscCall(MatDestroy(&Cm));
  PetscFunctionReturn(0);
}

static PetscErrorCode ProblemDestroy(Problem *p)
{
  PetscFunctionBeginUser;
  PetscCall(JRContDestroy(&p->cont));
  PetscCall(JRHBMDestroy(&p->hbm));
  PetscCall(JRModelDestroy(&p->model));
  PetscFunctionReturn(0);
}

static PetscErrorCode Options(const char *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, "-cont_monitor 0 -frf_output_file ''"));
  PetscCall(PetscOptionsInsertString(NULL, s));
  PetscFunctionReturn(0);
}


/* One RK4 step dt of the oscillator m x'' + c x' + k x + kt (x - s) = F sin(w t) from time t with a jenkins element
   (stiffness kt, slip force fs): every stage sees the committed slip s pushed by its own motion (the return map),
   which is then committed at the step's end; an independent reference march. (A stage force from the committed slip
   alone, kt (x - s), would exceed fs while slipping by kt v dt / 2: a spurious viscous damping of about kt dt / 2.)
   The kinks at the stick-slip transitions keep the march first-order accurate in dt. */
static inline void JenkinsOscillatorStep(double m, double c, double k, double kt, double fs, double F, double w, double t, double dt, double *x, double *v, double *s)
{
  double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
#define ACC(xx, vv, tt) ((F * sin(w * (tt)) - c * (vv) - k * (xx) - kt * ((xx) - fmin(fmax(*s, (xx) - fs / kt), (xx) + fs / kt))) / m)
  k1x = *v;
  k1v = ACC(*x, *v, t);
  k2x = *v + 0.5 * dt * k1v;
  k2v = ACC(*x + 0.5 * dt * k1x, *v + 0.5 * dt * k1v, t + 0.5 * dt);
  k3x = *v + 0.5 * dt * k2v;
  k3v = ACC(*x + 0.5 * dt * k2x, *v + 0.5 * dt * k2v, t + 0.5 * dt);
  k4x = *v + dt * k3v;
  k4v = ACC(*x + dt * k3x, *v + dt * k3v, t + dt);
#undef ACC
  *x += dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
  *v += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  *s = fmin(fmax(*s, *x - fs / kt), *x + fs / kt);
}
#endif
