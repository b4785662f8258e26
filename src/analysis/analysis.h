// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the analysis files: the exact tangent workspace (analysis_tangent.c).
#ifndef DAL_ANALYSIS_INTERNAL_H
#define DAL_ANALYSIS_INTERNAL_H

#include "dalembert/analysis.h"
#include "drive/drive.h"

/// dal_equilibrium for a system with constraint rows: Newton on (q, lambda) for the static
/// KKT system (equilibrium_manifold.c); o checked, the tangent supported.
int dal__equilibrium_manifold(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                              dal_equilibrium_report *rep);

/// The Newton step x of dal_equilibrium (n coordinate entries, then m multiplier entries)
/// scaled to opts.max_step (max_step <= 0: unbounded): *big is its largest coordinate entry in
/// magnitude (inf when any entry is not finite), *far the first coordinate that q_i + f x_i
/// sends beyond reach (-1: none, not looked for when *big is not finite); returns the factor f
/// (equilibrium_manifold.c)
double dal__newton_scale(const double *x, int n, int m, const double *q, double max_step,
                         double reach, double *big, int *far);
/// take the scaled Newton step q += f x (n = sys->n entries) after dal__newton_scale (big,
/// far, reach from it): DAL_E_CONV with the state's message when the step is not finite or
/// sends a coordinate beyond reach, `singular` naming the nearly singular matrix; *conv: the
/// largest change relative to 1 + |q_i|
int dal__newton_apply(const dal_system *sys, dal_state *st, const double *x, double *q, double f,
                      double big, int far, double reach, const char *singular, double *conv);

/// Put the state back at (t, y = (q, qdot)), evaluated, keeping the message of a failure rc
/// (floquet.c): returns rc when it is a failure, else the status of the evaluation
int dal__restore_state(const dal_system *sys, dal_state *st, double t, const double *y, int rc);
/// DAL_OK when the equations of motion of sys do not depend on time explicitly; else
/// DAL_E_UNSUPPORTED with "<what>: <the dependence>: a linearization frozen at t=... says
/// nothing about the motion; <remedy>" in the state's message (floquet.c); the state is left
/// as given, evaluated
int dal__time_dependence_refusal(const dal_system *sys, dal_state *st, const char *what,
                                 const char *remedy);
/// 1 when the state's q (with qdot = 0) is an equilibrium at six pseudo-random times in
/// [t, t + 7] (accelerations, and with constraint rows phi and dphi/dt, within 1e-8 of their
/// scales), 0 when not (*worst: the largest scaled residual, *t_at its time), or a status
/// (floquet.c); the state is left as given, evaluated
int dal__equilibrium_all_times(const dal_system *sys, dal_state *st, double *worst, double *t_at);
/// The Floquet verdict of dal_floquet_report from k2 multipliers and their accuracy, leaving
/// out the multipliers of index skip1 and skip2 (-1: none; the trivial ones of an autonomous
/// orbit); *max_abs the largest |mu| of the others (floquet.c)
dal_stability dal__floquet_verdict(int k2, const double *re, const double *im, double acc,
                                   int skip1, int skip2, double *max_abs);

#endif
