// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the analysis files: the exact tangent workspace (analysis_tangent.c).
#ifndef DAL_ANALYSIS_INTERNAL_H
#define DAL_ANALYSIS_INTERNAL_H

#include "dalembert/analysis.h"
#include "drive/drive.h"




#endif
