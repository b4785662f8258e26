// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White-box test of the Adams and BDF dense output (the interp operation of src/integrate/cvode.c),
// which calls CVodeGetDky for the first output of a step only and forms the same Nordsieck sum
// itself for the others: against CVodeGetDky at the same times (the same polynomial: equal to
// rounding, the order of the sums aside), the first output of a step again through the fast path
// (bit for bit), and against the elliptic pendulum (within the tolerance).
//
// The integrator is created directly (dal__ode_create) with an after-step hook that samples
// interp at NS points inside every step (NS = 1: one CVodeGetDky call a step, the sample asked
// again by the fast path; NS = 40: the fast path; and NS = 40 with every output by CVodeGetDky,
// the path after a mismatch of the columns' form).
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "integrate/families.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define G0 SCN_G

typedef struct probe {
  dal_ode_integ *ig;
  int ns;           // samples per step
  int slow;         // every output by CVodeGetDky (dal__cvode_slow_dense)
  double th0, tol;  // release angle, rtol = atol
  double worst_ulp; // worst |interp - CVodeGetDky| / (eps (|y| + h |y'|)), both components
  long again_diff;  // first samples of a step that differ when asked again (fast path)
  double worst_ref; // worst |th - elliptic| / tol at the samples
  double worst_pt;  // the same at the step points
  long steps, samples, bad;
} probe;

static double ref_err(const probe *pr, double t, const double *y) {
  double th, thd;
  ref_pendulum(pr->th0, sqrt(G0), t, &th, &thd);
  return fabs(y[0] - th) / pr->tol;
}

// every accepted step: its end against the closed form, and ns points inside it through interp
// against CVodeGetDky and against the closed form
static int probe_hook(void *ctx) {
  probe *pr = ctx;
  dal_ode_integ *ig = pr->ig;
  double t0 = ig->tprev, t1 = ig->t, h = t1 - t0, y[2], yc[2], yd[2], tfirst = -1, yfirst[2];
  pr->steps++;
  pr->worst_pt = fmax(pr->worst_pt, ref_err(pr, t1, ig->y));
  for (int j = 1; j <= pr->ns; ++j) {
    // irregular points (an irrational stride) so that no two steps sample alike
    double s = fmod(j * 0.6180339887498949 + 0.001 * pr->steps, 1.0), t = t0 + s * h;
    if (!(t > t0 && t < t1)) continue;
    if (ig->ops->interp(ig, t, y) != DAL_OK || dal__cvode_dky(ig, t, 0, yc) != 0 ||
        dal__cvode_dky(ig, t, 1, yd) != 0) {
      pr->bad++;
      continue;
    }
    for (int i = 0; i < 2; ++i) {
      // the scale of the polynomial's terms: its value and its first-order change in a step
      double scale = DBL_EPSILON * (fabs(yc[i]) + fabs(h * yd[i]));
      pr->worst_ulp = fmax(pr->worst_ulp, fabs(y[i] - yc[i]) / scale);
    }
    pr->worst_ref = fmax(pr->worst_ref, ref_err(pr, t, y));
    pr->samples++;
    if (tfirst < 0) {
      tfirst = t;
      memcpy(yfirst, y, sizeof y);
    }
  }
  // the step's first sample (CVodeGetDky) again, now by the columns it read: the same bits
  if (tfirst >= 0 && (ig->ops->interp(ig, tfirst, y) != DAL_OK || memcmp(y, yfirst, sizeof y) != 0))
    pr->again_diff++;
  return 0;
}

// the pendulum from pr->th0 at rest to t = 10 by method m at rtol = atol = pr->tol, pr->ns
// samples a step
static void run(const dal_system *sys, dal_state *st, dal_method m, probe *pr, long *fast) {
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = pr->tol;
  double q = pr->th0, qd = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  dal_ode_integ *ig = NULL;
  CHECK_OK(dal__ode_create(sys, st, &o, m, &dal__problem_minimal, &ig));
  pr->ig = ig;
  if (pr->slow) dal__cvode_slow_dense(ig);
  ig->hook = probe_hook;
  ig->hook_ctx = pr;
  CHECK_MSG(dal__ode_advance(ig, 10.0) == DAL_OK, "%s: %s", dal_method_name(m),
            dal_state_errmsg(st));
  // outside the last step: refused, not extrapolated
  double y[2];
  CHECK(ig->ops->interp(ig, ig->t + 0.5, y) == DAL_E_ARG);
  CHECK(ig->ops->interp(ig, ig->tprev - 0.5, y) == DAL_E_ARG);
  *fast = dal__cvode_fast_outputs(ig);
  dal__ode_destroy(ig);
}

static void test_against_getdky(void) {
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  static const dal_method ms[] = {DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  static const double tols[] = {1e-6, 1e-10};
  // samples a step, and whether every output takes CVodeGetDky (the path after a mismatch)
  static const int nss[] = {1, 40, 40}, slows[] = {0, 0, 1};
  printf("  pendulum from 2 rad to t = 10: interp against CVodeGetDky at the same times "
         "(ulps of |y| + h |y'|) and against the elliptic solution (x rtol)\n");
  printf("  %-6s %6s %3s %4s %6s %9s %8s %8s %9s\n", "method", "rtol", "ns", "slow", "steps",
         "fast", "ulps", "inside", "stepends");
  for (int mi = 0; mi < 2; ++mi)
    for (int ti = 0; ti < 2; ++ti)
      for (int ni = 0; ni < 3; ++ni) {
        probe pr = {.ns = nss[ni], .slow = slows[ni], .th0 = 2.0, .tol = tols[ti]};
        long fast = 0;
        run(s, st, ms[mi], &pr, &fast);
        printf("  %-6s %6.0e %3d %4d %6ld %9ld %8.2f %8.2f %9.2f\n", dal_method_name(ms[mi]),
               tols[ti], nss[ni], slows[ni], pr.steps, fast, pr.worst_ulp, pr.worst_ref,
               pr.worst_pt);
        CHECK_MSG(pr.bad == 0, "%ld samples failed", pr.bad);
        CHECK(pr.samples >= pr.steps * nss[ni] * 9 / 10);
        // every sample but the first of a step (and the first asked again) by the fast path;
        // none after a mismatch
        CHECK_MSG(fast == (slows[ni] ? 0 : pr.samples),
                  "%ld of %ld outputs without a CVodeGetDky call", fast, pr.samples);
        CHECK_MSG(pr.again_diff == 0, "%ld of %ld steps: the fast path differs from CVodeGetDky",
                  pr.again_diff, pr.steps);
        // the same polynomial as CVodeGetDky into a vector of the library's kernels: equal up
        // to the order of the sums
        CHECK_MSG(pr.worst_ulp <= 2.0, "interp %g ulps from CVodeGetDky", pr.worst_ulp);
        // inside the steps the error is the step points' (the library's calibration: below
        // 16 x rtol, tests/test_core.c), the interpolant adds no visible error
        CHECK_MSG(pr.worst_ref < 16.0 && pr.worst_ref <= 1.25 * pr.worst_pt + 0.5,
                  "%g x rtol inside the steps, %g at their ends", pr.worst_ref, pr.worst_pt);
      }
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  test_against_getdky();
  return check_summary("test_dense_cvode");
}
