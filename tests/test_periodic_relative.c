// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Relative equilibria of uniformly turning scenes in Cartesian coordinates, found in the
// co-rotating frame: the conical pendulum (cos th0 = g / (l W^2), wobble w^2 = W^2 (1 + 3
// cos^2 th0)) and the bead on a turning circle (cos th* = g / (R w^2), oscillation w sin th*),
// against their closed forms; the conical motion's return after one turn (dal_floquet's gap)
// as a check that it is one.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double PI = 3.14159265358979323846;

static void test_conical(void) {
  const double l = 1.0, W = 5.0, c0 = SCN_G / (l * W * W), s0 = sqrt(1 - c0 * c0);
  dal_system *sys = scn_cart_spherical(NULL); // rod "rod" of length 1 to the origin, 3D
  CHECK(sys != NULL);
  if (!sys) return;
  dal_state *st = NULL;
  // a guess off the cone: 0.1 rad too steep, at rest
  double th = acos(c0) + 0.1, q[3] = {l * sin(th), 0.0, -l * cos(th)}, v[3] = {0, 0, 0};
  double axis[3] = {0, 0, 2}, re[4], im[4];
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  dal_relative_report rep;
  CHECK_OK(dal_relative_equilibrium(sys, st, axis, W, re, im, &rep));
  const double *qs = dal_state_q(st), *vs = dal_state_qdot(st);
  double rho = hypot(qs[0], qs[1]);
  CHECK_CLOSE(-qs[2], l * c0, 1e-12); // cos th0 = g / (l W^2)
  CHECK_CLOSE(rho, l * s0, 1e-12);
  CHECK_CLOSE(vs[1] * qs[0] - vs[0] * qs[1], W * rho * rho, 1e-11); // turning at W
  CHECK(rep.residual <= 1e-12);
  // the wobble: +-i w with w^2 = W^2 (1 + 3 cos^2 th0); a zero pair along the family
  double w = W * sqrt(1 + 3 * c0 * c0);
  // (the zero pair is a Jordan block: rounding splits it by ~sqrt(eps))
  int big = 0, small = 0;
  for (int i = 0; i < 4; ++i) {
    CHECK(fabs(re[i]) < 1e-6);
    if (fabs(im[i]) > 1.0) {
      CHECK_CLOSE(fabs(im[i]), w, 1e-10);
      ++big;
    } else {
      CHECK(hypot(re[i], im[i]) < 1e-6);
      ++small;
    }
  }
  CHECK(big == 2 && small == 2);
  // the state is a periodic motion of period 2 pi / W in the inertial frame (independently:
  // the integrator's return after one turn)
  dal_floquet_report fr;
  CHECK_OK(dal_floquet(sys, st, NULL, 2 * PI / W, NULL, NULL, NULL, &fr));
  CHECK(fr.gap < 1e-8);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void test_turning_circle(void) {
  const double R = 1.0, w = 6.0, c = SCN_G / (R * w * w), s = sqrt(1 - c * c);
  scn_knobs k = scn_default();
  k.R = R;
  k.spin = w;
  dal_system *sys = scn_cart_bead(&k); // plane through the z axis at angle w t
  CHECK(sys != NULL);
  if (!sys) return;
  dal_state *st = NULL;
  double th = acos(c) - 0.15, q[3] = {R * sin(th), 0.0, -R * cos(th)}, v[3] = {0, 0, 0};
  double axis[3] = {0, 0, 1}, re[2], im[2];
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  // frozen modes refused away from the relative equilibrium: the circle turns in these
  // coordinates and the motion from there is not steady
  CHECK_OK(dal_make_consistent(sys, st, 0.0, NULL));
  CHECK(dal_normal_modes(sys, st, NULL, NULL, NULL, NULL, NULL) == DAL_E_UNSUPPORTED);
  CHECK_MSG(strstr(dal_state_errmsg(st), "changes along the motion"), "%s", dal_state_errmsg(st));
  CHECK_OK(dal_relative_equilibrium(sys, st, axis, w, re, im, NULL));
  const double *qs = dal_state_q(st);
  CHECK_CLOSE(-qs[2], R * c, 1e-12); // cos th* = g / (R w^2)
  CHECK_CLOSE(qs[0], R * s, 1e-12);
  CHECK(fabs(qs[1]) < 1e-12);
  CHECK_CLOSE(fabs(im[0]), w * s, 1e-10); // oscillation about it: w sin th*
  CHECK(fabs(re[0]) < 1e-8 && fabs(re[1]) < 1e-8);
  // a particle in other coordinates is refused, naming it
  dal_system *ang = scn_bead(&k);
  dal_state *sa = NULL;
  double t1 = 1.0, z = 0.0;
  CHECK_OK(dal_state_create(ang, &sa));
  CHECK_OK(dal_state_set(ang, sa, 0.0, &t1, &z));
  CHECK(dal_relative_equilibrium(ang, sa, axis, w, NULL, NULL, NULL) == DAL_E_UNSUPPORTED);
  CHECK_MSG(strstr(dal_state_errmsg(sa), "'bead'") && strstr(dal_state_errmsg(sa), "co-rotating"),
            "%s", dal_state_errmsg(sa));
  dal_state_destroy(sa);
  dal_system_destroy(ang);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  test_conical();
  test_turning_circle();
  return check_summary("test_periodic_relative");
}
