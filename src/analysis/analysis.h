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

#endif
