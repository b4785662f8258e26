// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Umbrella header: everything a dalembert user needs.
#ifndef DAL_DALEMBERT_H
#define DAL_DALEMBERT_H

#include "dalembert/analysis.h"
#include "dalembert/base.h"
#include "dalembert/codegen.h"
#include "dalembert/dae.h"
#include "dalembert/ensemble.h"
#include "dalembert/events.h"
#include "dalembert/expr.h"
#include "dalembert/output.h"
#include "dalembert/jet.h"
#include "dalembert/params.h"
#include "dalembert/primitives.h"
#include "dalembert/scene.h"
#include "dalembert/solve.h"
#include "dalembert/state.h"
#include "dalembert/system.h"
#include "dalembert/verify.h"

#endif
