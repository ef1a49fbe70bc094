/*
   The nearest of a set of points to a query point within a tolerance: the points sorted by x once, each query a
   binary search for the window |x - xq| <= tol and a scan of it (used to pair the interface's nodes and to match
   saved preload rows to the pairs).
*/
#include <jointrom.h>

typedef struct {
  PetscReal x;
  PetscInt  i;
} XKey;

struct _p_JRNearest {
  PetscInt         n;
  const PetscReal *x; /* 3 n coordinates [m], the caller's */
  XKey            *key;
};

static int CompareXKey(const void *a, const void *b)
{
  const XKey *p = (const XKey *)a, *q = (const XKey *)b;
  return (p->x > q->x) - (p->x < q->x);
}

/* JRNearestCreate - a search over the n points x (3 n coordinates, kept by reference: they must outlive it) */
PetscErrorCode JRNearestCreate(PetscInt n, const PetscReal x[], JRNearest *s)
{
  JRNearest t;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&t));
  t->n = n;
  t->x = x;
  PetscCall(PetscMalloc1(PetscMax(n, 1), &t->key));
  for (PetscInt i = 0; i < n; i++) {
    t->key[i].x = x[3 * i];
    t->key[i].i = i;
  }
  qsort(t->key, (size_t)n, sizeof(XKey), CompareXKey);
  *s = t;
  PetscFunctionReturn(0);
}

/* JRNearestFind - the point nearest p within tol (ties: the later in x order), or -1 (and dist = tol) if none */
PetscErrorCode JRNearestFind(JRNearest s, const PetscReal p[3], PetscReal tol, PetscInt *best, PetscReal *dist)
{
  PetscInt  lo = 0, hi = s->n, b = -1;
  PetscReal bd = tol;

  PetscFunctionBeginUser;
  while (lo < hi) { /* the first point with x >= p_x - tol */
    const PetscInt mid = (lo + hi) / 2;
    if (s->key[mid].x < p[0] - tol) lo = mid + 1;
    else hi = mid;
  }
  for (PetscInt j = lo; j < s->n && s->key[j].x <= p[0] + tol; j++) {
    const PetscInt   k = s->key[j].i;
    const PetscReal *q = s->x + 3 * k;
    const PetscReal  r = PetscSqrtReal(PetscSqr(p[0] - q[0]) + PetscSqr(p[1] - q[1]) + PetscSqr(p[2] - q[2]));
    if (r <= bd) {
      bd = r;
      b  = k;
    }
  }
  *best = b;
  if (dist) *dist = bd;
  PetscFunctionReturn(0);
}

/* JRNearestDestroy - free the search (not the points) */
PetscErrorCode JRNearestDestroy(JRNearest *s)
{
  PetscFunctionBeginUser;
  if (!*s) PetscFunctionReturn(0);
  PetscCall(PetscFree((*s)->key));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}
