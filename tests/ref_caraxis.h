// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The car axis problem of the Bari IVP test set (index-3 DAE, 10 unknowns) at t = 3: this
// library's own reference, computed by tests/ref_caraxis.c in __float128 (the index-1 form with
// hand-derived accelerations, Gragg-Bulirsch-Stoer with 14 columns and 600 steps; 300 steps
// with 12 columns give the same 25 digits, 100 steps with 8 agree to 10-14 digits), and the values
// the test set publishes (they agree with it to 9.2-14.4 digits).
//
// Unknowns: x_l, y_l, x_r, y_r, u_l, v_l, u_r, v_r (velocities), lambda_1, lambda_2.
#ifndef DAL_REF_CARAXIS_H
#define DAL_REF_CARAXIS_H

static const char *const caraxis_ref[10] = {
    "+4.934557842752409213152679e-02", "+4.969894602300081067629340e-01",
    "+1.041742524885426115194776e+00", "+3.739110272653658193578977e-01",
    "-7.705836840359208428394056e-02", "+7.446866592068416491401753e-03",
    "+1.755681575354173662974062e-02", "+7.703410437796010631206428e-01",
    "-4.736886590853326515313476e-03", "-1.104680331259565839860601e-03"};

// the test set's reference (its deTestSet distribution, GAMD in quadruple precision)
static const double caraxis_published[10] = {
    0.493455784275402809122e-1, 0.496989460230171153861,     0.104174252488542151681e1,
    0.373911027265361256927,    -0.770583684040972357970e-1, 0.744686658723778553466e-2,
    0.175568157537232222276e-1, 0.770341043779251976443,     -0.473688659084893324729e-2,
    -0.110468033125734368808e-2};

#endif
