// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Minimal-coordinate mechanics: d'Alembert route vs Lagrangian route vs hand-derived physics.
//
// For each example system (2D harmonic oscillator, bead on a rotating ring, simple pendulum,
// pendulum with a driven support, double pendulum, spherical pendulum) at many random states:
//  - accelerations from particles (d'Alembert), from a Lagrangian written over jets, and from
//    the equation of motion derived by hand here, agree to ~1e-12 relative;
//  - M is symmetric positive definite and equals its hand formula; Q = -dU/dq for potential
//    forces (closed form and finite differences of a hand-written U); T, U, E, h and the
//    split T2 / T1 / T0 match hand formulas; reaction forces match closed forms;
// and separately: the Lagrange residual on exact and perturbed paths, scene sizes (1x1 M, no z
// in 2D), springs, dampers (dissipation -c v_rel^2), U(r,t), U(q,t), force and generalized force
// callbacks, a moving-anchor spring and damper, and the singular mass matrix at a chart pole.
//
// Conventions: angles from the downward vertical; the ring's theta is the polar angle from its
// bottom point, so theta'' = sin(theta) (w^2 cos(theta) - g/R) (dal_map_ring in primitives.h).
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define NSTATE 200
#define TOL 1e-12

static unsigned long long seed = 0x2545f4914f6cdd1dULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

// ---------------------------------------------------------------------------------------------
// helpers
#define BUILD(call)                                                                                \
  do {                                                                                             \
    int rc_ = (call);                                                                              \
    ++check_count;                                                                                 \
    if (rc_) {                                                                                     \
      ++check_failures;                                                                            \
      fprintf(stderr, "%s:%d: %s: %s\n", __FILE__, __LINE__, #call, dal_builder_errmsg(b));        \
    }                                                                                              \
  } while (0)

static dal_builder *builder(int dim) {
  dal_builder *b = NULL;
  CHECK_OK(dal_builder_create(dim, &b));
  return b;
}

// compile and free the builder
static dal_system *compile(dal_builder *b) {
  dal_system *s = NULL;
  int rc = dal_builder_compile(b, &s);
  CHECK_MSG(rc == 0, "compile: %s", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

typedef struct scene {
  dal_system *sys;
  dal_state *st;
} scene;

// a state for sys (NULL: the scene could not be built, a failure)
static scene scene_make(dal_system *sys) {
  scene s = {sys, NULL};
  CHECK_MSG(sys != NULL, "the scene could not be built");
  if (sys) CHECK_OK(dal_state_create(sys, &s.st));
  return s;
}

static void scene_free(scene *s) {
  dal_state_destroy(s->st);
  dal_system_destroy(s->sys);
  s->st = NULL;
  s->sys = NULL;
}

// set the state and evaluate; 0 on success
static int at(scene *s, double t, const double *q, const double *qd) {
  if (!s->st) return -1;
  int rc = dal_state_set(s->sys, s->st, t, q, qd);
  if (!rc) rc = dal_forward(s->sys, s->st);
  CHECK_MSG(rc == 0, "forward at t=%g: %s (%s)", t, dal_status_name(rc), dal_state_errmsg(s->st));
  return rc;
}

static dal_energies energies(const scene *s) {
  dal_energies e;
  memset(&e, 0, sizeof e);
  CHECK_OK(dal_state_energies(s->st, &e));
  return e;
}

// |a - b| <= tol * max(scale, |b|)
static int near(const char *what, int i, double a, double b, double tol, double scale) {
  double sc = fmax(scale, fabs(b));
  ++check_count;
  if (!(fabs(a - b) <= tol * sc)) {
    ++check_failures;
    fprintf(stderr, "  %s[%d] = %.17g, expected %.17g (rel diff %.3g, tol %g)\n", what, i, a, b,
            fabs(a - b) / sc, tol);
    return 0;
  }
  return 1;
}

static void near_vec(const char *what, const double *a, const double *b, int n, double tol,
                     double scale) {
  for (int i = 0; i < n; ++i)
    near(what, i, a[i], b[i], tol, scale);
}

// M (n x n column-major): symmetric, positive definite (own Cholesky), equal to Mh (row-major)
static void check_mass(const char *what, const double *M, const double *Mh, int n) {
  CHECK_MSG(M != NULL, "%s: no mass matrix", what);
  if (!M) return;
  double L[16], scale = 0.0;
  for (int i = 0; i < n * n; ++i)
    scale = fmax(scale, fabs(Mh[i]));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      CHECK_MSG(M[i + n * j] == M[j + n * i], "%s: M not symmetric at (%d, %d)", what, i, j);
      near(what, i * n + j, M[i + n * j], Mh[i * n + j], 1e-13, scale);
    }
  // Cholesky by hand: every pivot positive
  memcpy(L, M, (size_t)n * n * sizeof(double));
  for (int j = 0; j < n; ++j) {
    double p = L[j + n * j];
    for (int k = 0; k < j; ++k)
      p -= L[j + n * k] * L[j + n * k];
    CHECK_MSG(p > 1e-12 * scale, "%s: M not positive definite (pivot %d = %g)", what, j, p);
    if (!(p > 0)) return;
    L[j + n * j] = sqrt(p);
    for (int i = j + 1; i < n; ++i) {
      double s = L[i + n * j];
      for (int k = 0; k < j; ++k)
        s -= L[i + n * k] * L[j + n * k];
      L[i + n * j] = s / L[j + n * j];
    }
  }
}

// central FD of a hand-written scalar function U(q) in direction i (oracle for -dU/dq)
typedef double hand_U_fn(const double *q, double t, const void *ctx);
static double fd_grad(hand_U_fn *U, const double *q, double t, const void *ctx, int n, int i) {
  double qp[8], qm[8], h = 1e-5;
  memcpy(qp, q, (size_t)n * sizeof(double));
  memcpy(qm, q, (size_t)n * sizeof(double));
  qp[i] += h;
  qm[i] -= h;
  return (U(qp, t, ctx) - U(qm, t, ctx)) / (2 * h);
}

// ---------------------------------------------------------------------------------------------
// 1. 2D harmonic oscillator (SICM 1.6: m = 2, k = 1): L = m/2 |v|^2 - k/2 |x|^2
typedef struct ho_par {
  double m, k;
} ho_par;

static int ho_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  const ho_par *p = ctx;
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5 * p->m);
  dal_jet U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * p->k);
  *L = dal_sub(T, U);
  return 0;
}

static int ho_potential(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  const ho_par *p = ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * p->k);
  return 0;
}

static int identity_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = q[0];
  r[1] = q[1];
  return 0;
}

// exact solution x = A cos(w t + a), y = B sin(w t + b); ctx: {A, a, B, b, w, eps}
// eps adds eps t^3 to x (a perturbation)
static int ho_path(dal_jet t, dal_jet *q, void *ctx) {
  const double *c = ctx;
  q[0] = dal_scale(dal_cos(dal_addc(dal_scale(t, c[4]), c[1])), c[0]);
  q[0] = dal_add(q[0], dal_scale(dal_powi(t, 3), c[5]));
  q[1] = dal_scale(dal_sin(dal_addc(dal_scale(t, c[4]), c[3])), c[2]);
  return 0;
}

static void test_harmonic_oscillator(void) {
  int f0 = check_failures;
  ho_par par = {2.0, 1.0};
  // (a) Cartesian particle + anchor spring of rest length 0 at the origin
  scn_knobs kn = scn_weightless(); // the oscillator of the scene library
  kn.m = par.m;
  kn.k = par.k;
  scene sa = scene_make(scn_oscillator(&kn));
  // (b) whole-system identity map + U(q)
  dal_builder *b = builder(2);
  BUILD(dal_builder_add_coord(b, "x", NULL));
  BUILD(dal_builder_add_coord(b, "y", NULL));
  BUILD(dal_builder_add_particle(b, "m", par.m, NULL));
  BUILD(dal_builder_set_map(b, identity_map, NULL));
  BUILD(dal_builder_add_potential_q(b, ho_potential, &par));
  scene sb = scene_make(compile(b));
  // (c) the Lagrangian
  b = builder(2);
  BUILD(dal_builder_add_coord(b, "x", NULL));
  BUILD(dal_builder_add_coord(b, "y", NULL));
  BUILD(dal_builder_set_lagrangian(b, ho_lagrangian, &par));
  scene sc = scene_make(compile(b));
  if (!sa.st || !sb.st || !sc.st) goto done;

  // a 2D scene: dimension 2, the Jacobian is 2 x 2, positions carry no z
  CHECK(dal_system_dim(sa.sys) == 2 && dal_system_ncoords(sa.sys) == 2);
  CHECK(dal_system_nparticles(sc.sys) == 0 && dal_system_nconstraints(sa.sys) == 0);

  for (int it = 0; it < NSTATE; ++it) {
    double x[2] = {rnd(-2, 2), rnd(-2, 2)}, v[2] = {rnd(-2, 2), rnd(-2, 2)}, t = rnd(-5, 5);
    if (at(&sa, t, x, v) || at(&sb, t, x, v) || at(&sc, t, x, v)) continue;
    double hand[2] = {-par.k / par.m * x[0], -par.k / par.m * x[1]};
    near_vec("HO qddot (particle + spring)", dal_state_qddot(sa.st), hand, 2, TOL, 1);
    near_vec("HO qddot (map + U(q))", dal_state_qddot(sb.st), hand, 2, TOL, 1);
    near_vec("HO qddot (Lagrangian)", dal_state_qddot(sc.st), hand, 2, TOL, 1);
    double Mh[4] = {par.m, 0, 0, par.m};
    check_mass("HO M (spring)", dal_state_mass_matrix(sa.st), Mh, 2);
    check_mass("HO M (map)", dal_state_mass_matrix(sb.st), Mh, 2);
    check_mass("HO d2L/dv2", dal_state_mass_matrix(sc.st), Mh, 2);
    double Qh[2] = {-par.k * x[0], -par.k * x[1]};
    near_vec("HO Q (spring)", dal_state_genforces(sa.st), Qh, 2, TOL, 1);
    near_vec("HO Q (U(q))", dal_state_genforces(sb.st), Qh, 2, TOL, 1);
    double T = 0.5 * par.m * (v[0] * v[0] + v[1] * v[1]);
    double U = 0.5 * par.k * (x[0] * x[0] + x[1] * x[1]);
    dal_energies ea = energies(&sa), eb = energies(&sb), ec = energies(&sc);
    near("HO T", 0, ea.T, T, TOL, 1);
    near("HO U", 0, ea.U, U, TOL, 1);
    near("HO E", 0, ea.E, T + U, TOL, 1);
    near("HO h", 0, ea.h, T + U, TOL, 1);
    near("HO T2", 0, ea.T2, T, TOL, 1);
    near("HO T1", 0, ea.T1, 0, TOL, 1);
    near("HO T0", 0, ea.T0, 0, TOL, 1);
    near("HO E (map)", 0, eb.E, T + U, TOL, 1);
    near("HO h (Lagrangian)", 0, ec.h, T + U, TOL, 1);
    // a free particle feels no constraint: reactions vanish
    const double *N = dal_state_reactions(sa.st);
    near("HO reaction", 0, N[0], 0, TOL, 1);
    near("HO reaction", 1, N[1], 0, TOL, 1);
    // Jacobian is exactly d x n = 2 x 2 (sentinels after it stay untouched)
    double J[8];
    for (int i = 0; i < 8; ++i)
      J[i] = -777.0;
    CHECK_OK(dal_state_jacobian(sa.sys, sa.st, 0, J));
    CHECK(J[0] == 1 && J[1] == 0 && J[2] == 0 && J[3] == 1);
    CHECK(J[4] == -777.0 && J[5] == -777.0 && J[6] == -777.0 && J[7] == -777.0);
    const double *r = dal_state_positions(sa.st);
    CHECK(r[0] == x[0] && r[1] == x[1]);
  }

  // Lagrange residual: ~0 on the exact solution, the hand value on perturbed paths
  double w = sqrt(par.k / par.m);
  for (int it = 0; it < 50; ++it) {
    double c[6] = {rnd(0.2, 2), rnd(-3, 3), rnd(0.2, 2), rnd(-3, 3), w, 0.0};
    double t = rnd(-4, 4), res[2], exact_scale = par.k * (fabs(c[0]) + fabs(c[2]));
    scene *ss[3] = {&sa, &sb, &sc};
    const char *nm[3] = {"particle+spring", "map+U(q)", "Lagrangian"};
    for (int k = 0; k < 3; ++k) {
      c[4] = w;
      c[5] = 0.0;
      CHECK_OK(dal_lagrange_residual(ss[k]->sys, ss[k]->st, ho_path, t, res, c));
      CHECK_MSG(fabs(res[0]) <= TOL * exact_scale && fabs(res[1]) <= TOL * exact_scale,
                "HO residual (%s) on the exact path: (%g, %g)", nm[k], res[0], res[1]);
      // wrong frequency: res = (k - m w'^2) q(t)
      double w2 = 1.1 * w, ph0 = w2 * t + c[1], ph1 = w2 * t + c[3];
      c[4] = w2;
      CHECK_OK(dal_lagrange_residual(ss[k]->sys, ss[k]->st, ho_path, t, res, c));
      double f = par.k - par.m * w2 * w2;
      near("HO residual, wrong frequency", 0, res[0], f * c[0] * cos(ph0), TOL, exact_scale);
      near("HO residual, wrong frequency", 1, res[1], f * c[2] * sin(ph1), TOL, exact_scale);
      CHECK_MSG(fabs(res[0]) + fabs(res[1]) > 1e-3,
                "HO residual (%s), wrong frequency: (%g, %g) "
                "is not clearly non-zero",
                nm[k], res[0], res[1]);
      // added eps t^3 on x: res_x = m 6 eps t + k eps t^3
      c[4] = w;
      c[5] = 0.01;
      CHECK_OK(dal_lagrange_residual(ss[k]->sys, ss[k]->st, ho_path, t, res, c));
      near("HO residual, eps t^3", 0, res[0], par.m * 6 * c[5] * t + par.k * c[5] * t * t * t, TOL,
           exact_scale);
      near("HO residual, eps t^3", 1, res[1], 0.0, TOL, exact_scale);
    }
  }
done:
  scene_free(&sa);
  scene_free(&sb);
  scene_free(&sc);
  printf("  %-44s %s\n", "2D harmonic oscillator (3 routes)",
         check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// 2. bead on a ring of radius R turning about the vertical at rate w
typedef scn_knobs ring_par; // m, R, spin (the rate w), phi0, g: the scene library's bead

static int ring_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  const ring_par *p = ctx;
  dal_jet s = dal_sin(q[0]);
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_scale(dal_sq(s), p->spin * p->spin)),
                        0.5 * p->m * p->R * p->R);
  dal_jet U = dal_scale(dal_cos(q[0]), -p->m * p->g * p->R);
  *L = dal_sub(T, U);
  return 0;
}

static void test_ring(void) {
  int f0 = check_failures;
  for (int rep = 0; rep < 4; ++rep) {
    ring_par P = {
        .m = rnd(0.5, 2), .R = rnd(0.3, 2), .spin = rnd(0, 8), .phi0 = rnd(-1, 1), .g = 9.81};
    scene s = scene_make(scn_bead(&P));
    dal_builder *b = builder(3);
    BUILD(dal_builder_add_coord(b, "theta", NULL));
    BUILD(dal_builder_set_lagrangian(b, ring_lagrangian, &P));
    scene sl = scene_make(compile(b));
    if (s.st && sl.st) {
      CHECK(dal_system_dim(s.sys) == 3 && dal_system_ncoords(s.sys) == 1);
      for (int it = 0; it < NSTATE / 4; ++it) {
        double th0 = rnd(-3.1, 3.1), thd = rnd(-4, 4), t = rnd(-5, 5);
        if (at(&s, t, &th0, &thd) || at(&sl, t, &th0, &thd)) continue;
        double sn = sin(th0), cs = cos(th0), w = P.spin, R = P.R, m = P.m;
        double hand = sn * (w * w * cs - P.g / R);
        double sc = w * w + P.g / R;
        near("ring theta'' (particle)", 0, dal_state_qddot(s.st)[0], hand, TOL, sc);
        near("ring theta'' (Lagrangian)", 0, dal_state_qddot(sl.st)[0], hand, TOL, sc);
        double Mh = m * R * R;
        check_mass("ring M", dal_state_mass_matrix(s.st), &Mh, 1);
        check_mass("ring d2L/dv2", dal_state_mass_matrix(sl.st), &Mh, 1);
        // Q = -dU/dtheta, U = -m g R cos(theta); c = -m R^2 w^2 sin cos
        near("ring Q", 0, dal_state_genforces(s.st)[0], -m * P.g * R * sn, TOL, m * P.g * R);
        near("ring c", 0, dal_state_bias(s.st)[0], -m * R * R * w * w * sn * cs, TOL, Mh * sc);
        // energies: T2 = m/2 R^2 thd^2, T1 = 0, T0 = m/2 R^2 w^2 sin^2, U = -m g R cos
        double T2 = 0.5 * m * R * R * thd * thd, T0 = 0.5 * m * R * R * w * w * sn * sn;
        double U = -m * P.g * R * cs, esc = Mh * (thd * thd + w * w) + m * P.g * R;
        dal_energies e = energies(&s), el = energies(&sl);
        near("ring T", 0, e.T, T2 + T0, TOL, esc);
        near("ring T2", 0, e.T2, T2, TOL, esc);
        near("ring T1", 0, e.T1, 0.0, TOL, esc);
        near("ring T0", 0, e.T0, T0, TOL, esc);
        near("ring U", 0, e.U, U, TOL, esc);
        near("ring E", 0, e.E, T2 + T0 + U, TOL, esc);
        near("ring h", 0, e.h, T2 - T0 + U, TOL, esc);
        near("ring h (Lagrangian)", 0, el.h, T2 - T0 + U, TOL, esc);
        // kinematics: frame (e_rho, e_phi, e_z) at phi = w t + phi0
        double ph = w * t + P.phi0, cp = cos(ph), spp = sin(ph);
        double er[3] = {cp, spp, 0}, ef[3] = {-spp, cp, 0}, ez[3] = {0, 0, 1};
        double drdt[3], gam[3], n[3], tg[3];
        for (int a = 0; a < 3; ++a) {
          drdt[a] = w * R * sn * ef[a];
          gam[a] = (-R * sn * thd * thd - R * sn * w * w) * er[a] + 2 * R * cs * thd * w * ef[a] +
                   R * cs * thd * thd * ez[a];
          n[a] = sn * er[a] - cs * ez[a];  // outward normal in the ring's plane
          tg[a] = cs * er[a] + sn * ez[a]; // tangent along increasing theta
        }
        near_vec("ring dr/dt", dal_state_drdt(s.st), drdt, 3, TOL, w * R + 1);
        double rh[3] = {R * n[0], R * n[1], R * n[2]}; // on the ring: R times its normal
        near_vec("ring r", dal_state_positions(s.st), rh, 3, TOL, R);
        near_vec("ring gamma", dal_state_gamma(s.st), gam, 3, TOL, R * (thd * thd + w * w) + 1);
        // reaction force: N.n = -m R (thd^2 + w^2 sin^2) - m g cos, N.e_phi = 2 m w R cos thd,
        // N.t = 0 (frictionless ring)
        const double *N = dal_state_reactions(s.st);
        double Nn = -m * R * (thd * thd + w * w * sn * sn) - m * P.g * cs;
        double Nf = 2 * m * w * R * cs * thd, Nh[3];
        for (int a = 0; a < 3; ++a)
          Nh[a] = Nn * n[a] + Nf * ef[a];
        near_vec("ring reaction N", N, Nh, 3, TOL, m * (R * (thd * thd + w * w) + P.g + w * R));
        double Nt = N[0] * tg[0] + N[1] * tg[1] + N[2] * tg[2];
        near("ring N.tangent", 0, Nt, 0.0, TOL, m * (R * (thd * thd + w * w) + P.g));
      }
    }
    scene_free(&s);
    scene_free(&sl);
  }
  printf("  %-44s %s\n", "bead on a rotating ring", check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// 3./4. pendulum with a support moving as p(t) = (x0 + ax cos(w t + ph), y0 + ay cos(w t + ph))
typedef scn_knobs pend_par; // m, l, x0, y0, ax, ay, w, ph, g: the scene library's pendulum

// support position, velocity and acceleration
static void support(const pend_par *P, double t, double *p, double *pd, double *pdd) {
  double c = cos(P->w * t + P->ph), s = sin(P->w * t + P->ph);
  p[0] = P->x0 + P->ax * c;
  p[1] = P->y0 + P->ay * c;
  pd[0] = -P->ax * P->w * s;
  pd[1] = -P->ay * P->w * s;
  pdd[0] = -P->ax * P->w * P->w * c;
  pdd[1] = -P->ay * P->w * P->w * c;
}

// L = m/2 |p' + l thd (cos, sin)|^2 - m g (p_y - l cos)  (SICM 1.6.2, driven pendulum)
static int pend_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  const pend_par *P = ctx;
  dal_jet arg = dal_addc(dal_scale(t, P->w), P->ph);
  dal_jet c = dal_cos(arg), s = dal_sin(arg);
  dal_jet pdx = dal_scale(s, -P->ax * P->w), pdy = dal_scale(s, -P->ay * P->w);
  dal_jet vx = dal_add(pdx, dal_scale(dal_mul(v[0], dal_cos(q[0])), P->l));
  dal_jet vy = dal_add(pdy, dal_scale(dal_mul(v[0], dal_sin(q[0])), P->l));
  dal_jet T = dal_scale(dal_add(dal_sq(vx), dal_sq(vy)), 0.5 * P->m);
  dal_jet y = dal_sub(dal_addc(dal_scale(c, P->ay), P->y0), dal_scale(dal_cos(q[0]), P->l));
  *L = dal_sub(T, dal_scale(y, P->m * P->g));
  return 0;
}

static double pend_U(const double *q, double t, const void *ctx) {
  const pend_par *P = ctx;
  double p[2], pd[2], pdd[2];
  support(P, t, p, pd, pdd);
  return P->m * P->g * (p[1] - P->l * cos(q[0]));
}

// driven pendulum path theta(t) = 0.3 sin(1.7 t) + 0.1 t (for the residual)
static int pend_path(dal_jet t, dal_jet *q, void *ctx) {
  (void)ctx;
  q[0] = dal_add(dal_scale(dal_sin(dal_scale(t, 1.7)), 0.3), dal_scale(t, 0.1));
  return 0;
}

static void test_pendulum(int driven) {
  int f0 = check_failures;
  for (int rep = 0; rep < 4; ++rep) {
    pend_par P = {.m = rnd(0.5, 2),
                  .l = rnd(0.3, 2),
                  .x0 = rnd(-1, 1),
                  .y0 = rnd(-1, 1),
                  .w = rnd(0.5, 10),
                  .ph = rnd(-1, 1),
                  .g = 9.81};
    if (driven) {
      P.ay = rnd(-0.5, 0.5);
      P.ax = rep % 2 ? rnd(-0.5, 0.5) : 0.0; // SICM's vertical drive, and a general one
    }
    scene s = scene_make(scn_pendulum(&P));
    dal_builder *b = builder(2);
    BUILD(dal_builder_add_coord(b, "theta", NULL));
    BUILD(dal_builder_set_lagrangian(b, pend_lagrangian, &P));
    scene sl = scene_make(compile(b));
    if (s.st && sl.st) {
      // a 1-coordinate scene: n = 1, M is 1 x 1, the Jacobian is 2 x 1
      CHECK(dal_system_ncoords(s.sys) == 1 && dal_system_dim(s.sys) == 2);
      for (int it = 0; it < NSTATE / 4; ++it) {
        double th0 = rnd(-3.1, 3.1), thd = rnd(-4, 4), t = rnd(-5, 5);
        if (at(&s, t, &th0, &thd) || at(&sl, t, &th0, &thd)) continue;
        double m = P.m, l = P.l, sn = sin(th0), cs = cos(th0), pp[2], pd[2], pdd[2];
        support(&P, t, pp, pd, pdd);
        // hand: l theta'' = -(p''x cos + (g + p''y) sin)
        double hand = -(pdd[0] * cs + (P.g + pdd[1]) * sn) / l;
        double sc = (P.g + fabs(pdd[0]) + fabs(pdd[1])) / l;
        near(driven ? "driven theta'' (particle)" : "pendulum theta'' (particle)", 0,
             dal_state_qddot(s.st)[0], hand, TOL, sc);
        near(driven ? "driven theta'' (Lagrangian)" : "pendulum theta'' (Lagrangian)", 0,
             dal_state_qddot(sl.st)[0], hand, TOL, sc);
        double Mh = m * l * l;
        check_mass("pendulum M", dal_state_mass_matrix(s.st), &Mh, 1);
        check_mass("pendulum d2L/dv2", dal_state_mass_matrix(sl.st), &Mh, 1);
        // Q = -dU/dtheta: closed form and FD of the hand-written U
        double Qh = -m * P.g * l * sn;
        near("pendulum Q", 0, dal_state_genforces(s.st)[0], Qh, TOL, m * P.g * l);
        near("pendulum Q vs FD of U", 0, dal_state_genforces(s.st)[0],
             -fd_grad(pend_U, &th0, t, &P, 1, 0), 1e-8, m * P.g * l);
        // energies
        double vx = pd[0] + l * thd * cs, vy = pd[1] + l * thd * sn;
        double T = 0.5 * m * (vx * vx + vy * vy), U = m * P.g * (pp[1] - l * cs);
        double T2 = 0.5 * m * l * l * thd * thd, T0 = 0.5 * m * (pd[0] * pd[0] + pd[1] * pd[1]);
        double T1 = m * l * thd * (pd[0] * cs + pd[1] * sn);
        double esc = m * (l * l * thd * thd + P.w * P.w + P.g * (l + 2));
        dal_energies e = energies(&s), el = energies(&sl);
        near("pendulum T", 0, e.T, T, TOL, esc);
        near("pendulum T2", 0, e.T2, T2, TOL, esc);
        near("pendulum T1", 0, e.T1, T1, TOL, esc);
        near("pendulum T0", 0, e.T0, T0, TOL, esc);
        near("pendulum U", 0, e.U, U, TOL, esc);
        near("pendulum E", 0, e.E, T + U, TOL, esc);
        near("pendulum h", 0, e.h, T2 - T0 + U, TOL, esc);
        near("pendulum h (Lagrangian)", 0, el.h, T2 - T0 + U, TOL, esc);
        // reaction (rod tension) along e = (sin, -cos) from the support to the bob:
        // N = -(m l thd^2 + m (g + p''y) cos - m p''x sin) e, no tangential part
        double Nm = -(m * l * thd * thd + m * (P.g + pdd[1]) * cs - m * pdd[0] * sn);
        double Nh[2] = {Nm * sn, -Nm * cs};
        near_vec("pendulum reaction", dal_state_reactions(s.st), Nh, 2, TOL,
                 m * (l * thd * thd + P.g + fabs(pdd[0]) + fabs(pdd[1])));
        // the bob at p + l (sin, -cos), moving at p' + l thd (cos, sin)
        double rh[2] = {pp[0] + l * sn, pp[1] - l * cs}, vh[2] = {vx, vy};
        near_vec("pendulum r", dal_state_positions(s.st), rh, 2, TOL,
                 l + fabs(pp[0]) + fabs(pp[1]));
        near_vec("pendulum v", dal_state_velocities(s.st), vh, 2, TOL, l * fabs(thd) + P.w + 1);
        // sizes: the Jacobian is written as exactly 2 x 1
        double J[4] = {-777, -777, -777, -777};
        CHECK_OK(dal_state_jacobian(s.sys, s.st, 0, J));
        near("pendulum J", 0, J[0], l * cs, TOL, l);
        near("pendulum J", 1, J[1], l * sn, TOL, l);
        CHECK(J[2] == -777 && J[3] == -777);
      }
      // Lagrange residual of an arbitrary path: m l^2 th'' + m l (p''x cos + (g + p''y) sin)
      for (int it = 0; it < 20; ++it) {
        double t = rnd(-5, 5), res[2];
        double th0 = 0.3 * sin(1.7 * t) + 0.1 * t, thdd = -0.3 * 1.7 * 1.7 * sin(1.7 * t);
        double pp[2], pd[2], pdd[2];
        support(&P, t, pp, pd, pdd);
        double hand =
            P.m * P.l * P.l * thdd + P.m * P.l * (pdd[0] * cos(th0) + (P.g + pdd[1]) * sin(th0));
        double sc = P.m * P.l * (P.l + P.g + P.w * P.w);
        CHECK_OK(dal_lagrange_residual(s.sys, s.st, pend_path, t, res, NULL));
        near("pendulum residual (particle)", 0, res[0], hand, TOL, sc);
        CHECK_OK(dal_lagrange_residual(sl.sys, sl.st, pend_path, t, res, NULL));
        near("pendulum residual (Lagrangian)", 0, res[0], hand, TOL, sc);
      }
    }
    scene_free(&s);
    scene_free(&sl);
  }
  printf("  %-44s %s\n", driven ? "pendulum with a driven support" : "simple pendulum",
         check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// 5. double pendulum
typedef scn_knobs dbl_par; // m (m1), m2, l (l1), l2, x0, y0, g: the scene library's

static int dbl_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  const dbl_par *P = ctx;
  // T = (m1+m2)/2 l1^2 w1^2 + m2/2 l2^2 w2^2 + m2 l1 l2 w1 w2 cos(th1 - th2)
  dal_jet T = dal_scale(dal_sq(v[0]), 0.5 * (P->m + P->m2) * P->l * P->l);
  T = dal_add(T, dal_scale(dal_sq(v[1]), 0.5 * P->m2 * P->l2 * P->l2));
  T = dal_add(T, dal_scale(dal_mul(dal_mul(v[0], v[1]), dal_cos(dal_sub(q[0], q[1]))),
                           P->m2 * P->l * P->l2));
  // U = -(m1+m2) g l1 cos th1 - m2 g l2 cos th2 (+ constant)
  dal_jet U = dal_add(dal_scale(dal_cos(q[0]), -(P->m + P->m2) * P->g * P->l),
                      dal_scale(dal_cos(q[1]), -P->m2 * P->g * P->l2));
  *L = dal_sub(T, U);
  return 0;
}

static int dbl_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  const dbl_par *P = ctx;
  r[0] = dal_addc(dal_scale(dal_sin(q[0]), P->l), P->x0);
  r[1] = dal_addc(dal_scale(dal_cos(q[0]), -P->l), P->y0);
  r[2] = dal_add(r[0], dal_scale(dal_sin(q[1]), P->l2));
  r[3] = dal_sub(r[1], dal_scale(dal_cos(q[1]), P->l2));
  return 0;
}

static double dbl_U(const double *q, double t, const void *ctx) {
  (void)t;
  const dbl_par *P = ctx;
  double y1 = P->y0 - P->l * cos(q[0]), y2 = y1 - P->l2 * cos(q[1]);
  return P->g * (P->m * y1 + P->m2 * y2);
}

static void test_double_pendulum(void) {
  int f0 = check_failures;
  for (int rep = 0; rep < 4; ++rep) {
    dbl_par P = {.m = rnd(0.5, 2),
                 .m2 = rnd(0.5, 2),
                 .l = rnd(0.5, 2),
                 .l2 = rnd(0.5, 2),
                 .x0 = rnd(-1, 1),
                 .y0 = rnd(-1, 1),
                 .g = 9.81};
    double g[2] = {0, -P.g};
    // (a) primitives: pendulum + hanging from bob 1
    scene sa = scene_make(scn_double_pendulum(&P));
    // (b) whole-system map
    dal_builder *b = builder(2);
    BUILD(dal_builder_add_coord(b, "theta1", NULL));
    BUILD(dal_builder_add_coord(b, "theta2", NULL));
    BUILD(dal_builder_add_particle(b, "bob1", P.m, NULL));
    BUILD(dal_builder_add_particle(b, "bob2", P.m2, NULL));
    BUILD(dal_builder_set_map(b, dbl_map, &P));
    BUILD(dal_builder_set_gravity(b, g));
    scene sb = scene_make(compile(b));
    // (c) Lagrangian
    b = builder(2);
    BUILD(dal_builder_add_coord(b, "theta1", NULL));
    BUILD(dal_builder_add_coord(b, "theta2", NULL));
    BUILD(dal_builder_set_lagrangian(b, dbl_lagrangian, &P));
    scene sc = scene_make(compile(b));
    if (sa.st && sb.st && sc.st) {
      for (int it = 0; it < NSTATE / 4; ++it) {
        double th[2] = {rnd(-3.1, 3.1), rnd(-3.1, 3.1)}, w[2] = {rnd(-4, 4), rnd(-4, 4)};
        double t = rnd(-5, 5);
        if (at(&sa, t, th, w) || at(&sb, t, th, w) || at(&sc, t, th, w)) continue;
        double m1 = P.m, m2 = P.m2, l1 = P.l, l2 = P.l2, G = P.g;
        double c12 = cos(th[0] - th[1]), s12 = sin(th[0] - th[1]);
        // hand: M qdd = Q - c
        double Mh[4] = {(m1 + m2) * l1 * l1, m2 * l1 * l2 * c12, m2 * l1 * l2 * c12, m2 * l2 * l2};
        double ch[2] = {m2 * l1 * l2 * s12 * w[1] * w[1], -m2 * l1 * l2 * s12 * w[0] * w[0]};
        double Qh[2] = {-(m1 + m2) * G * l1 * sin(th[0]), -m2 * G * l2 * sin(th[1])};
        double r0 = Qh[0] - ch[0], r1 = Qh[1] - ch[1];
        double det = Mh[0] * Mh[3] - Mh[1] * Mh[2];
        double hand[2] = {(r0 * Mh[3] - Mh[1] * r1) / det, (Mh[0] * r1 - Mh[2] * r0) / det};
        double asc = G / fmin(l1, l2) + w[0] * w[0] + w[1] * w[1];
        near_vec("double pendulum qdd (primitives)", dal_state_qddot(sa.st), hand, 2, TOL, asc);
        near_vec("double pendulum qdd (map)", dal_state_qddot(sb.st), hand, 2, TOL, asc);
        near_vec("double pendulum qdd (Lagrangian)", dal_state_qddot(sc.st), hand, 2, TOL, asc);
        check_mass("double pendulum M (primitives)", dal_state_mass_matrix(sa.st), Mh, 2);
        check_mass("double pendulum M (map)", dal_state_mass_matrix(sb.st), Mh, 2);
        check_mass("double pendulum d2L/dv2", dal_state_mass_matrix(sc.st), Mh, 2);
        double fsc = (m1 + m2) * l1 * l2 * (G + w[0] * w[0] + w[1] * w[1]);
        near_vec("double pendulum Q", dal_state_genforces(sa.st), Qh, 2, TOL, fsc);
        near_vec("double pendulum c", dal_state_bias(sa.st), ch, 2, TOL, fsc);
        near_vec("double pendulum c (map)", dal_state_bias(sb.st), ch, 2, TOL, fsc);
        for (int i = 0; i < 2; ++i)
          near("double pendulum Q vs FD of U", i, dal_state_genforces(sa.st)[i],
               -fd_grad(dbl_U, th, t, &P, 2, i), 1e-8, fsc);
        double T = 0.5 * (m1 + m2) * l1 * l1 * w[0] * w[0] + 0.5 * m2 * l2 * l2 * w[1] * w[1] +
                   m2 * l1 * l2 * w[0] * w[1] * c12;
        double U = dbl_U(th, t, &P), Uc = U - G * (m1 + m2) * P.y0; // Lagrangian drops y0
        dal_energies ea = energies(&sa), eb = energies(&sb), ec = energies(&sc);
        near("double pendulum E", 0, ea.E, T + U, TOL, fsc);
        near("double pendulum h", 0, ea.h, T + U, TOL, fsc);
        near("double pendulum E (map)", 0, eb.E, T + U, TOL, fsc);
        near("double pendulum h (Lagrangian)", 0, ec.h, T + Uc, TOL, fsc);
        // positions and the chained Jacobian of bob 2 (2 x 2)
        double J[4], Jh[4] = {l1 * cos(th[0]), l2 * cos(th[1]), l1 * sin(th[0]), l2 * sin(th[1])};
        CHECK_OK(dal_state_jacobian(sa.sys, sa.st, 1, J));
        near_vec("double pendulum J2", J, Jh, 4, TOL, l1 + l2);
        const double *r = dal_state_positions(sa.st);
        double rh[4] = {P.x0 + l1 * sin(th[0]), P.y0 - l1 * cos(th[0]),
                        P.x0 + l1 * sin(th[0]) + l2 * sin(th[1]),
                        P.y0 - l1 * cos(th[0]) - l2 * cos(th[1])};
        near_vec("double pendulum positions", r, rh, 4, TOL, 1);
      }
    }
    scene_free(&sa);
    scene_free(&sb);
    scene_free(&sc);
  }
  printf("  %-44s %s\n", "double pendulum (3 routes)", check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// 6. spherical pendulum
typedef scn_knobs sph_par; // m, l, g and the pivot (x0, y0, z0): the scene library's

static int sph_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  const sph_par *P = ctx;
  dal_jet T = dal_add(dal_sq(v[0]), dal_mul(dal_sq(dal_sin(q[0])), dal_sq(v[1])));
  T = dal_scale(T, 0.5 * P->m * P->l * P->l);
  *L = dal_add(T, dal_scale(dal_cos(q[0]), P->m * P->g * P->l));
  return 0;
}

static void test_spherical(void) {
  int f0 = check_failures;
  sph_par P = {.m = 1.3, .l = 0.8, .g = 9.81, .x0 = 0.2, .y0 = -0.3, .z0 = 0.5};
  scene s = scene_make(scn_spherical(&P));
  dal_builder *b = builder(3);
  BUILD(dal_builder_add_coord(b, "theta", NULL));
  BUILD(dal_builder_add_coord(b, "phi", NULL));
  BUILD(dal_builder_set_lagrangian(b, sph_lagrangian, &P));
  scene sl = scene_make(compile(b));
  if (s.st && sl.st) {
    for (int it = 0; it < NSTATE; ++it) {
      double x[2] = {rnd(0.2, 2.9), rnd(-4, 4)}, v[2] = {rnd(-3, 3), rnd(-3, 3)}, t = rnd(-5, 5);
      if (at(&s, t, x, v) || at(&sl, t, x, v)) continue;
      double m = P.m, l = P.l, sn = sin(x[0]), cs = cos(x[0]);
      double hand[2] = {sn * cs * v[1] * v[1] - P.g / l * sn, -2 * cs / sn * v[0] * v[1]};
      double sc = P.g / l + (v[0] * v[0] + v[1] * v[1]) / sn;
      near_vec("spherical qdd (particle)", dal_state_qddot(s.st), hand, 2, TOL, sc);
      near_vec("spherical qdd (Lagrangian)", dal_state_qddot(sl.st), hand, 2, TOL, sc);
      double Mh[4] = {m * l * l, 0, 0, m * l * l * sn * sn};
      check_mass("spherical M", dal_state_mass_matrix(s.st), Mh, 2);
      check_mass("spherical d2L/dv2", dal_state_mass_matrix(sl.st), Mh, 2);
      double Qh[2] = {-m * P.g * l * sn, 0.0};
      near_vec("spherical Q", dal_state_genforces(s.st), Qh, 2, TOL, m * P.g * l);
      double T = 0.5 * m * l * l * (v[0] * v[0] + sn * sn * v[1] * v[1]);
      double U = m * P.g * (P.z0 - l * cs), esc = m * (l * l * 9 + P.g * (l + 1));
      dal_energies e = energies(&s), el = energies(&sl);
      near("spherical E", 0, e.E, T + U, TOL, esc);
      near("spherical h", 0, e.h, T + U, TOL, esc);
      near("spherical h (Lagrangian)", 0, el.h, T + U - m * P.g * P.z0, TOL, esc);
      // reaction along the rod: N = -(m l (thd^2 + sin^2 phd^2) + m g cos) e_r
      double er[3] = {sn * cos(x[1]), sn * sin(x[1]), -cs};
      double Nm = -(m * l * (v[0] * v[0] + sn * sn * v[1] * v[1]) + m * P.g * cs), Nh[3];
      for (int a = 0; a < 3; ++a)
        Nh[a] = Nm * er[a];
      near_vec("spherical reaction", dal_state_reactions(s.st), Nh, 3, TOL, m * (l * 18 + P.g));
    }
    // singular mass matrix at the poles: DAL_E_SINGULAR names 'phi', t and q
    double poles[3] = {0.0, 3.141592653589793, 1e-9};
    for (int k = 0; k < 3; ++k) {
      double x[2] = {poles[k], 0.7}, v[2] = {0.5, 0.25};
      scene *ss[2] = {&s, &sl};
      for (int r = 0; r < 2; ++r) {
        CHECK_OK(dal_state_set(ss[r]->sys, ss[r]->st, 2.5, x, v));
        int rc = dal_forward(ss[r]->sys, ss[r]->st);
        const char *msg = dal_state_errmsg(ss[r]->st);
        CHECK_MSG(rc == DAL_E_SINGULAR, "spherical at theta=%g (%s): %s, %s", poles[k],
                  r ? "Lagrangian" : "particle", dal_status_name(rc), msg);
        CHECK_MSG(strstr(msg, "'phi'") && strstr(msg, "t=2.5") && strstr(msg, "theta=") &&
                      strstr(msg, "phi=0.7"),
                  "singular message must name 'phi', t and q: %s", msg);
        CHECK(dal_state_q(ss[r]->st)[0] == poles[k] && dal_state_time(ss[r]->st) == 2.5);
      }
    }
    // near (not at) the pole the chart still works
    double x[2] = {1e-3, 0.7}, v[2] = {0.5, 0.25};
    if (!at(&s, 0.0, x, v)) {
      double hand1 = -2 * cos(x[0]) / sin(x[0]) * v[0] * v[1];
      near("spherical phi'' near the pole", 1, dal_state_qddot(s.st)[1], hand1, 1e-9, 1);
    }
  }
  scene_free(&s);
  scene_free(&sl);
  printf("  %-44s %s\n", "spherical pendulum (+ singular chart)",
         check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// forces: springs, dampers, U(r,t), U(q,t), force and generalized-force callbacks, moving anchors
//
// scene: 2D, particle A on a pendulum (theta; l, pivot 0), particle B Cartesian (x, y).
typedef struct zoo {
  double mA, mB, l, g;
  double k1, L1; // spring A-B
  double c1;     // damper A-B
  double k2, L2; // anchor spring A to fixed X2
  double X2[2];
  double k3, L3, c3; // spring and damper B to the moving anchor X3(t)
  double A3, B3, W3; // X3(t) = (A3 cos W3 t, B3 sin W3 t)
  double ur, uq;     // strengths of U(r,t) and U(q,t)
  double fb, ff, fw; // force callback on B: -fb v + ff cos(fw t) e_x
  double gb, gt;     // generalized force: -gb thetadot + gt sin(t) on theta, 0 on x, y
} zoo;

static int moving_anchor(dal_jet t, dal_jet *x, void *ctx) {
  const zoo *z = ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, z->W3)), z->A3);
  x[1] = dal_scale(dal_sin(dal_scale(t, z->W3)), z->B3);
  return 0;
}

// U(r,t) = ur (1 + 0.5 sin t) (xA yB^2 + 0.3 |rA - rB|^2)
static int zoo_Ur(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  const zoo *z = ctx;
  dal_jet a = dal_addc(dal_scale(dal_sin(t), 0.5), 1.0);
  dal_jet dx = dal_sub(r[0], r[2]), dy = dal_sub(r[1], r[3]);
  dal_jet u = dal_add(dal_mul(r[0], dal_sq(r[3])), dal_scale(dal_add(dal_sq(dx), dal_sq(dy)), 0.3));
  *U = dal_scale(dal_mul(a, u), z->ur);
  return 0;
}

// U(q,t) = uq (cos(t) theta^2 x + exp(0.2 y))
static int zoo_Uq(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  const zoo *z = ctx;
  dal_jet u = dal_mul(dal_cos(t), dal_mul(dal_sq(q[0]), q[1]));
  *U = dal_scale(dal_add(u, dal_exp(dal_scale(q[2], 0.2))), z->uq);
  return 0;
}

static int zoo_force(double t, const double *r, const double *v, double *F, void *ctx) {
  const zoo *z = ctx;
  (void)r;
  F[2] += -z->fb * v[2] + z->ff * cos(z->fw * t);
  F[3] += -z->fb * v[3];
  return 0;
}

static int zoo_genforce(double t, const double *q, const double *qd, double *Q, void *ctx) {
  const zoo *z = ctx;
  (void)q;
  Q[0] += -z->gb * qd[0] + z->gt * sin(t);
  return 0;
}

// which: bit 0 springs, 1 dampers, 2 U(r,t), 3 U(q,t), 4 force, 5 genforce, 6 gravity
static dal_system *zoo_build(const zoo *z, int which) {
  dal_builder *b = builder(2);
  int th, q[2], A, B;
  BUILD(dal_builder_add_coord(b, "theta", &th));
  BUILD(dal_builder_add_coord(b, "x", &q[0]));
  BUILD(dal_builder_add_coord(b, "y", &q[1]));
  BUILD(dal_builder_add_particle(b, "A", z->mA, &A));
  BUILD(dal_builder_add_particle(b, "B", z->mB, &B));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = z->l;
  BUILD(dal_builder_place_def(b, A, &pd));
  pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = q;
  pd.ncoords = 2;
  BUILD(dal_builder_place_def(b, B, &pd));
  if (which & 1) {
    dal_spring_def sd = dal_default_spring_def();
    sd.a = A;
    sd.b = B;
    sd.k = z->k1;
    sd.length = z->L1;
    BUILD(dal_builder_add_spring_def(b, &sd));
    sd = dal_default_spring_def();
    sd.a = A;
    memcpy(sd.anchor, z->X2, sizeof z->X2);
    sd.k = z->k2;
    sd.length = z->L2;
    BUILD(dal_builder_add_spring_def(b, &sd));
    sd = dal_default_spring_def();
    sd.a = B;
    sd.path = moving_anchor;
    sd.ctx = (void *)z;
    sd.k = z->k3;
    sd.length = z->L3;
    BUILD(dal_builder_add_spring_def(b, &sd));
  }
  if (which & 2) {
    dal_damper_def dd = dal_default_damper_def();
    dd.a = A;
    dd.b = B;
    dd.c = z->c1;
    BUILD(dal_builder_add_damper_def(b, &dd));
    dd = dal_default_damper_def();
    dd.a = B;
    dd.path = moving_anchor;
    dd.ctx = (void *)z;
    dd.c = z->c3;
    BUILD(dal_builder_add_damper_def(b, &dd));
  }
  if (which & 4) BUILD(dal_builder_add_potential_r(b, zoo_Ur, (void *)z));
  if (which & 8) BUILD(dal_builder_add_potential_q(b, zoo_Uq, (void *)z));
  if (which & 16) BUILD(dal_builder_add_force(b, zoo_force, (void *)z));
  if (which & 32) BUILD(dal_builder_add_genforce(b, zoo_genforce, (void *)z));
  if (which & 64) {
    double g[2] = {0, -z->g};
    BUILD(dal_builder_set_gravity(b, g));
  }
  return compile(b);
}

// hand-computed forces F (2 x 2: A, B), potential U and generalized Q_extra (from U(q), genforce)
typedef struct zoo_hand {
  double F[4], U, Qx[3], Ddamp; // Ddamp: dissipation of the dampers, -sum c v_rel^2
} zoo_hand;

static zoo_hand zoo_forces(const zoo *z, int which, double t, const double *q, const double *qd) {
  zoo_hand H;
  memset(&H, 0, sizeof H);
  double rA[2] = {z->l * sin(q[0]), -z->l * cos(q[0])}, rB[2] = {q[1], q[2]};
  double vA[2] = {z->l * cos(q[0]) * qd[0], z->l * sin(q[0]) * qd[0]}, vB[2] = {qd[1], qd[2]};
  double X3[2] = {z->A3 * cos(z->W3 * t), z->B3 * sin(z->W3 * t)};
  double V3[2] = {-z->A3 * z->W3 * sin(z->W3 * t), z->B3 * z->W3 * cos(z->W3 * t)};
  if (which & 1) {
    // U = k/2 (|r - s| - L)^2: force on r is -k (|r - s| - L) (r - s) / |r - s|
    double d[2] = {rB[0] - rA[0], rB[1] - rA[1]}, len = hypot(d[0], d[1]);
    double f = z->k1 * (len - z->L1) / len;
    for (int a = 0; a < 2; ++a) {
      H.F[a] += f * d[a];
      H.F[2 + a] -= f * d[a];
    }
    H.U += 0.5 * z->k1 * (len - z->L1) * (len - z->L1);
    double e[2] = {rA[0] - z->X2[0], rA[1] - z->X2[1]};
    len = hypot(e[0], e[1]);
    f = z->k2 * (len - z->L2) / len;
    for (int a = 0; a < 2; ++a)
      H.F[a] -= f * e[a];
    H.U += 0.5 * z->k2 * (len - z->L2) * (len - z->L2);
    double u[2] = {rB[0] - X3[0], rB[1] - X3[1]};
    len = hypot(u[0], u[1]);
    f = z->k3 * (len - z->L3) / len;
    for (int a = 0; a < 2; ++a)
      H.F[2 + a] -= f * u[a];
    H.U += 0.5 * z->k3 * (len - z->L3) * (len - z->L3);
  }
  if (which & 2) {
    // damper: F_B = -c ((vB - vA).e) e, e from A to B; F_A = -F_B
    double d[2] = {rB[0] - rA[0], rB[1] - rA[1]}, len = hypot(d[0], d[1]);
    double e[2] = {d[0] / len, d[1] / len};
    double rel = (vB[0] - vA[0]) * e[0] + (vB[1] - vA[1]) * e[1];
    for (int a = 0; a < 2; ++a) {
      H.F[2 + a] -= z->c1 * rel * e[a];
      H.F[a] += z->c1 * rel * e[a];
    }
    H.Ddamp -= z->c1 * rel * rel;
    double u[2] = {rB[0] - X3[0], rB[1] - X3[1]};
    len = hypot(u[0], u[1]);
    double eu[2] = {u[0] / len, u[1] / len};
    double rel3 = (vB[0] - V3[0]) * eu[0] + (vB[1] - V3[1]) * eu[1];
    for (int a = 0; a < 2; ++a)
      H.F[2 + a] -= z->c3 * rel3 * eu[a];
    H.Ddamp -= z->c3 * rel3 * rel3;
  }
  if (which & 4) {
    // U = ur a(t) (xA yB^2 + 0.3 |rA - rB|^2), a = 1 + 0.5 sin t
    double a = z->ur * (1 + 0.5 * sin(t)), dx = rA[0] - rB[0], dy = rA[1] - rB[1];
    H.U += a * (rA[0] * rB[1] * rB[1] + 0.3 * (dx * dx + dy * dy));
    H.F[0] -= a * (rB[1] * rB[1] + 0.6 * dx);
    H.F[1] -= a * (0.6 * dy);
    H.F[2] -= a * (-0.6 * dx);
    H.F[3] -= a * (2 * rA[0] * rB[1] - 0.6 * dy);
  }
  if (which & 8) {
    // U = uq (cos t theta^2 x + exp(0.2 y))
    H.U += z->uq * (cos(t) * q[0] * q[0] * q[1] + exp(0.2 * q[2]));
    H.Qx[0] -= z->uq * cos(t) * 2 * q[0] * q[1];
    H.Qx[1] -= z->uq * cos(t) * q[0] * q[0];
    H.Qx[2] -= z->uq * 0.2 * exp(0.2 * q[2]);
  }
  if (which & 16) {
    H.F[2] += -z->fb * vB[0] + z->ff * cos(z->fw * t);
    H.F[3] += -z->fb * vB[1];
  }
  if (which & 32) H.Qx[0] += -z->gb * qd[0] + z->gt * sin(t);
  if (which & 64) {
    H.F[1] -= z->mA * z->g;
    H.F[3] -= z->mB * z->g;
    H.U += z->g * (z->mA * rA[1] + z->mB * rB[1]);
  }
  return H;
}

static void test_forces(void) {
  int f0 = check_failures;
  zoo z = {1.2, 0.7, 0.9, 9.81, 3.0, 0.5, 0.8, 2.0, 0.3, {0.4, 0.6}, 1.5, 0.2,
           0.6, 0.5, 0.4, 1.3,  0.7, 0.9, 0.3, 1.1, 2.0, 0.6,        0.8};
  const int cases[] = {1, 2, 4, 8, 16, 32, 64, 127};
  const char *names[] = {"springs (incl. moving anchor)",
                         "dampers (incl. moving anchor)",
                         "U(r,t)",
                         "U(q,t)",
                         "force callback",
                         "generalized force callback",
                         "gravity",
                         "all together"};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
    int which = cases[c], f1 = check_failures;
    scene s = scene_make(zoo_build(&z, which));
    if (!s.st) continue;
    for (int it = 0; it < 50; ++it) {
      double q[3] = {rnd(-3, 3), rnd(-2, 2), rnd(-2, 2)},
             qd[3] = {rnd(-2, 2), rnd(-2, 2), rnd(-2, 2)};
      double t = rnd(-5, 5);
      if (at(&s, t, q, qd)) continue;
      zoo_hand H = zoo_forces(&z, which, t, q, qd);
      near_vec("forces F", dal_state_forces(s.st), H.F, 4, TOL, 10);
      // Q = J' F + Q_extra, J_A = l (cos, sin) on theta, J_B = identity on (x, y)
      double Qh[3] = {z.l * (cos(q[0]) * H.F[0] + sin(q[0]) * H.F[1]) + H.Qx[0], H.F[2] + H.Qx[1],
                      H.F[3] + H.Qx[2]};
      near_vec("forces Q", dal_state_genforces(s.st), Qh, 3, TOL, 10);
      // M = diag(mA l^2, mB, mB): qddot = M^-1 (Q - c), c_theta = 0 for a fixed pivot
      double qdd[3] = {Qh[0] / (z.mA * z.l * z.l), Qh[1] / z.mB, Qh[2] / z.mB};
      near_vec("forces qddot", dal_state_qddot(s.st), qdd, 3, TOL, 10);
      dal_energies e = energies(&s);
      near("forces U", 0, e.U, H.U, TOL, 10);
      double T =
          0.5 * z.mA * z.l * z.l * qd[0] * qd[0] + 0.5 * z.mB * (qd[1] * qd[1] + qd[2] * qd[2]);
      near("forces E", 0, e.E, T + H.U, TOL, 10);
      if (which == 2) {
        // dissipation: F_A = F_AB, F_B = -F_AB + F_3 (anchor damper), so the power into the
        // dampers, F_AB . (vA - vB) + F_3 . (vB - V3) = F . v - (F_A + F_B) . V3 = -sum c v_rel^2
        const double *F = dal_state_forces(s.st), *v = dal_state_velocities(s.st);
        double V3[2] = {-z.A3 * z.W3 * sin(z.W3 * t), z.B3 * z.W3 * cos(z.W3 * t)};
        double P = F[0] * v[0] + F[1] * v[1] + F[2] * v[2] + F[3] * v[3] - (F[0] + F[2]) * V3[0] -
                   (F[1] + F[3]) * V3[1];
        near("damper dissipation", 0, P, H.Ddamp, TOL, 10);
        CHECK(P <= 0);
      }
      if ((which & ~(1 | 4 | 8 | 64)) == 0) {
        // potential forces only: Q = -dU/dq, against FD of the hand-written U
        for (int i = 0; i < 3; ++i) {
          double qp[3], qm[3], hh = 1e-5;
          memcpy(qp, q, sizeof qp);
          memcpy(qm, q, sizeof qm);
          qp[i] += hh;
          qm[i] -= hh;
          double dU =
              (zoo_forces(&z, which, t, qp, qd).U - zoo_forces(&z, which, t, qm, qd).U) / (2 * hh);
          near("Q = -dU/dq (FD of hand U)", i, dal_state_genforces(s.st)[i], -dU, 1e-8, 10);
        }
      }
    }
    printf("    %-42s %s\n", names[c], check_failures > f1 ? "FAILED" : "ok");
    scene_free(&s);
  }
  printf("  %-44s %s\n", "forces", check_failures > f0 ? "FAILED" : "ok");
}

// a Lagrangian system with a generalized force: pendulum L plus Q = -b thd + a sin t
static int lag_genforce(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)q;
  const double *c = ctx;
  Q[0] += -c[0] * qd[0] + c[1] * sin(t);
  return 0;
}

static void test_lagrangian_genforce(void) {
  int f0 = check_failures;
  pend_par P = {.m = 1.1, .l = 0.7, .w = 1, .g = 9.81};
  double c[2] = {0.4, 1.5};
  dal_builder *b = builder(2);
  BUILD(dal_builder_add_coord(b, "theta", NULL));
  BUILD(dal_builder_set_lagrangian(b, pend_lagrangian, &P));
  BUILD(dal_builder_add_genforce(b, lag_genforce, c));
  scene s = scene_make(compile(b));
  for (int it = 0; s.st && it < 50; ++it) {
    double th = rnd(-3, 3), thd = rnd(-3, 3), t = rnd(-5, 5);
    if (at(&s, t, &th, &thd)) continue;
    double Q = -c[0] * thd + c[1] * sin(t);
    double hand = -P.g / P.l * sin(th) + Q / (P.m * P.l * P.l);
    near("Lagrangian + genforce theta''", 0, dal_state_qddot(s.st)[0], hand, TOL, 20);
  }
  scene_free(&s);
  printf("  %-44s %s\n", "Lagrangian with a generalized force",
         check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// composite-mass (tree) assembly against the general Jacobian route: a chain of 4 hanging from
// a vertically driven pivot, built once from primitives (translating parent links: the tree
// path) and once as one whole-system map (the general path), with springs and a damper so
// that F, Q and c are all non-trivial.

#define TREE_N 4
static const double tree_len[TREE_N] = {1.0, 0.7, 1.3, 0.5};
static const double tree_mass[TREE_N] = {1.0, 2.0, 0.5, 1.5};
static const double tree_drive[3] = {0.3, 5.0, 0.2}; // ay, w, ph

static int tree_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)ctx;
  dal_jet x = dal_const(0.0);
  dal_jet y =
      dal_scale(dal_cos(dal_addc(dal_scale(t, tree_drive[1]), tree_drive[2])), tree_drive[0]);
  for (int k = 0; k < TREE_N; ++k) {
    x = dal_add(x, dal_scale(dal_sin(q[k]), tree_len[k]));
    y = dal_sub(y, dal_scale(dal_cos(q[k]), tree_len[k]));
    r[2 * k] = x;
    r[2 * k + 1] = y;
  }
  return 0;
}

static dal_system *tree_build(int general) {
  dal_builder *b = builder(2);
  int c[TREE_N], p[TREE_N];
  double g[2] = {0.0, -9.81}, x0[2] = {0.5, -1.0};
  for (int k = 0; k < TREE_N; ++k)
    BUILD(dal_builder_add_coord(b, NULL, &c[k]));
  for (int k = 0; k < TREE_N; ++k)
    BUILD(dal_builder_add_particle(b, NULL, tree_mass[k], &p[k]));
  if (general) {
    BUILD(dal_builder_set_map(b, tree_map, NULL));
  } else {
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_pendulum;
    pd.coords = &c[0];
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = tree_len[0];
    pd.param[DAL_PENDULUM_AY] = tree_drive[0];
    pd.param[DAL_PENDULUM_W] = tree_drive[1];
    pd.param[DAL_PENDULUM_PH] = tree_drive[2];
    BUILD(dal_builder_place_def(b, p[0], &pd));
    for (int k = 1; k < TREE_N; ++k) {
      pd = dal_default_place_def(); // each link hangs from the previous one
      pd.prim = &dal_map_hanging;
      pd.parent = p[k - 1];
      pd.coords = &c[k];
      pd.ncoords = 1;
      pd.param[DAL_HANGING_L] = tree_len[k];
      BUILD(dal_builder_place_def(b, p[k], &pd));
    }
  }
  BUILD(dal_builder_set_gravity(b, g));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p[0];
  sd.b = p[2];
  sd.k = 40.0;
  sd.length = 1.1;
  BUILD(dal_builder_add_spring_def(b, &sd));
  sd = dal_default_spring_def();
  sd.a = p[3];
  memcpy(sd.anchor, x0, sizeof x0);
  sd.k = 25.0;
  sd.length = 0.3;
  BUILD(dal_builder_add_spring_def(b, &sd));
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p[1];
  dd.b = p[3];
  dd.c = 0.8;
  BUILD(dal_builder_add_damper_def(b, &dd));
  return compile(b);
}

static void test_tree_vs_general(void) {
  scene tr = scene_make(tree_build(0)), ge = scene_make(tree_build(1));
  int n = TREE_N, N = TREE_N;
  for (int trial = 0; trial < 200 && tr.st && ge.st; ++trial) {
    double q[TREE_N], qd[TREE_N], t = rnd(0, 3);
    for (int k = 0; k < n; ++k) {
      q[k] = rnd(-3, 3);
      qd[k] = rnd(-2, 2);
    }
    if (at(&tr, t, q, qd) || at(&ge, t, q, qd)) break;
    near_vec("tree qddot", dal_state_qddot(tr.st), dal_state_qddot(ge.st), n, 1e-12, 1.0);
    near_vec("tree M", dal_state_mass_matrix(tr.st), dal_state_mass_matrix(ge.st), n * n, 1e-13,
             1.0);
    near_vec("tree Q", dal_state_genforces(tr.st), dal_state_genforces(ge.st), n, 1e-12, 1.0);
    near_vec("tree c", dal_state_bias(tr.st), dal_state_bias(ge.st), n, 1e-12, 1.0);
    near_vec("tree dr/dt", dal_state_drdt(tr.st), dal_state_drdt(ge.st), 2 * N, 1e-13, 1.0);
    near_vec("tree accelerations", dal_state_accelerations(tr.st), dal_state_accelerations(ge.st),
             2 * N, 1e-12, 1.0);
    near_vec("tree reactions", dal_state_reactions(tr.st), dal_state_reactions(ge.st), 2 * N, 1e-12,
             1.0);
    dal_energies et = energies(&tr), eg = energies(&ge);
    near("tree h", 0, et.h, eg.h, 1e-13, 1.0);
    near("tree T0", 0, et.T0, eg.T0, 1e-13, 1.0);
    const double *M = dal_state_mass_matrix(tr.st);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        CHECK(M[j * n + i] == M[i * n + j]);
    for (int k = 0; k < N; ++k) {
      double Jt[2 * TREE_N], Jg[2 * TREE_N];
      CHECK_OK(dal_state_jacobian(tr.sys, tr.st, k, Jt));
      CHECK_OK(dal_state_jacobian(ge.sys, ge.st, k, Jg));
      near_vec("tree J", Jt, Jg, 2 * n, 1e-14, 1.0);
    }
  }
  scene_free(&tr);
  scene_free(&ge);
}

// a parent link that is not a translation (the child sits at 1.5 x its parent's position plus
// a pendulum offset): the library must leave the tree assembly and form J by the chain rule
static int scaled_child(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_add(dal_scale(in[0], 1.5), dal_scale(dal_sin(in[2]), p[0]));
  out[1] = dal_sub(dal_scale(in[1], 1.5), dal_scale(dal_cos(in[2]), p[0]));
  return 0;
}
static const dal_primitive scaled_prim = {.name = "scaled_child",
                                          .version = 1,
                                          .nin = 3,
                                          .nout = 2,
                                          .nparam = 1,
                                          .eval = scaled_child,
                                          .doc = "1.5 parent + l (sin th, -cos th)",
                                          .flags = 0};

static int scaled_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = dal_sin(q[0]);
  r[1] = dal_neg(dal_cos(q[0]));
  r[2] = dal_add(dal_scale(r[0], 1.5), dal_scale(dal_sin(q[1]), 0.8));
  r[3] = dal_sub(dal_scale(r[1], 1.5), dal_scale(dal_cos(q[1]), 0.8));
  return 0;
}

static void test_non_translating_parent(void) {
  scene s[2];
  for (int general = 0; general < 2; ++general) {
    dal_builder *b = builder(2);
    int c[2], p[2];
    double g[2] = {0.0, -9.81}, l = 0.8;
    BUILD(dal_builder_add_coord(b, NULL, &c[0]));
    BUILD(dal_builder_add_coord(b, NULL, &c[1]));
    BUILD(dal_builder_add_particle(b, NULL, 1.0, &p[0]));
    BUILD(dal_builder_add_particle(b, NULL, 2.0, &p[1]));
    if (general) {
      BUILD(dal_builder_set_map(b, scaled_map, NULL));
    } else {
      BUILD(scn_place_swing(b, NULL, p[0], -1, 1.0, c[0]));
      dal_place_def pd = dal_default_place_def();
      pd.prim = &scaled_prim;
      pd.parent = p[0];
      pd.coords = &c[1];
      pd.ncoords = 1;
      pd.param[0] = l;
      BUILD(dal_builder_place_def(b, p[1], &pd));
    }
    BUILD(dal_builder_set_gravity(b, g));
    s[general] = scene_make(compile(b));
  }
  for (int trial = 0; trial < 50 && s[0].st && s[1].st; ++trial) {
    double q[2] = {rnd(-3, 3), rnd(-3, 3)}, qd[2] = {rnd(-2, 2), rnd(-2, 2)};
    if (at(&s[0], 0.0, q, qd) || at(&s[1], 0.0, q, qd)) break;
    near_vec("scaled qddot", dal_state_qddot(s[0].st), dal_state_qddot(s[1].st), 2, 1e-12, 1.0);
    near_vec("scaled accelerations", dal_state_accelerations(s[0].st),
             dal_state_accelerations(s[1].st), 4, 1e-12, 1.0);
    near_vec("scaled dr/dt", dal_state_drdt(s[0].st), dal_state_drdt(s[1].st), 4, 1e-13, 1.0);
    double Jt[4], Jg[4];
    CHECK_OK(dal_state_jacobian(s[0].sys, s[0].st, 1, Jt));
    CHECK_OK(dal_state_jacobian(s[1].sys, s[1].st, 1, Jg));
    near_vec("scaled J", Jt, Jg, 4, 1e-14, 1.0);
  }
  scene_free(&s[0]);
  scene_free(&s[1]);
}

int main(void) {
  printf("d'Alembert route vs Lagrangian route vs hand-derived equations:\n");
  test_harmonic_oscillator();
  test_ring();
  test_pendulum(0);
  test_pendulum(1);
  test_double_pendulum();
  test_spherical();
  test_forces();
  test_lagrangian_genforce();
  test_tree_vs_general();
  test_non_translating_parent();
  return check_summary("test_mechanics");
}
