// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The face of analysis/: what its files share (the constrained equilibrium's Newton step).
#ifndef DAL_ANALYSIS_ANALYSIS_H
#define DAL_ANALYSIS_ANALYSIS_H

#include "dalembert/analysis.h"
#include "drive/drive.h"

/// dal_equilibrium for a system with constraint rows: Newton on (q, lambda) for the static
/// KKT system (equilibrium_manifold.c); o checked, the tangent supported.
int dal__equilibrium_manifold(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                              dal_equilibrium_report *rep);

/// The size of the particle forces that make an equilibrium's residual, sum_k |F_k| / sqrt(m_k)
/// over the particles with mass (|Q_j| <= sqrt(M_jj) times it), from the state's forces F
/// (equilibrium_manifold.c)
double dal__force_scale(const dal_system *sys, const dal_state *st);

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
/// 1 when the motion through the state is steady for its linearization: the eigenvalues of
/// the frozen (reduced) linearization at the state and at t + 0.37, 1.9, 4.3 along the motion
/// (dal_advance at rtol 1e-10 on a copy of the state) agree within 1e-6 of their size or the
/// verdict's tolerance tau of dal_modes, whichever is larger (a
/// relative equilibrium of a turning constraint); 0 when not (*worst: the largest relative
/// difference, inf when the motion could not be followed), or a status (floquet.c)
int dal__steady_modes(const dal_system *sys, dal_state *st, double *worst);

#endif
