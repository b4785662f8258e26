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

#endif
