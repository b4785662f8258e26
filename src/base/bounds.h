// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Every threshold that chooses a code path or a tolerance, in one place, with its reason.
#ifndef DAL_BOUNDS_H
#define DAL_BOUNDS_H

#include <float.h>

/// Largest n with a dense mass matrix in a constrained system (n x n doubles per state:
/// 2 MiB at 512). Above it M exists only through the particle Jacobians (sparse KKT, IDA
/// residual). Systems without constraints always keep a dense M (Cholesky).
#define DAL_DENSE_M_MAX 512

/// Most constraint rows solved by the m x m loop system on top of the recursion (aba.c: m
/// recursion solves with unit loads, the m x m matrix G M^-1 G' and its unblocked Cholesky,
/// O(m N + m^2 + m^3)); with more rows the KKT matrix in all coordinates is used (dense, or
/// KLU from order DAL_KKT_SPARSE_MIN). Measured in instructions on the Cartesian chain (N
/// particles with their own coordinates, N rods, index-1 with projection, bench/overhead_ir.sh
/// routes_ir.csv): loop system / KKT matrix 0.35 at m = 4, 0.45 at 16, 0.47 at 32 and 0.49 at
/// 64 (dense KKT), 3.7 at 72 and 5.6 at 128 (KKT by KLU): the loop system wins while the
/// KKT matrix is dense and loses to KLU's O(N) once it is sparse. 32 keeps every system of up
/// to 32 rows on the loop system and hands larger Cartesian systems to KLU; a tree with a few
/// loops (the held 64-link chain, m = 1) runs 9.7x faster than through the dense KKT matrix.
#define DAL_LOOP_ROWS_MAX 32

/// Smallest KKT order factored sparse (KLU) when a dense M exists, and the largest fill
/// (non-zeros / order^2) for it: measured on the chain, KLU wins from ~200 unknowns when the
/// matrix is sparse (N = 256: 0.22 s dense -> 0.09 s KLU).
#define DAL_KKT_SPARSE_MIN 200
#define DAL_KKT_SPARSE_FILL 0.05
/// Reciprocal condition number below which a KKT matrix counts as singular.
#define DAL_KKT_RCOND_MIN 1e-14

/// Rank check of the constraint Jacobian by dense QR: at most this many rows and entries
/// (larger systems skip the named diagnosis and rely on the factorization's pivots).
#define DAL_RANK_MAX_ROWS 512
#define DAL_RANK_MAX_ENTRIES 1000000.0

/// Default number of unknowns from which DAL_LINSOL_AUTO uses KLU in IDA (opts.sparse_threshold;
/// systems without a dense M use KLU at any size). Measured in instructions (callgrind,
/// bench/dae_bench.c) on the N-link Cartesian chain in GGL (6N unknowns) at rtol 1e-4 and
/// 1e-8, dense LU / KLU: 1.0 at 6 unknowns, 1.3-1.4 at 12, 1.5 at 18, 1.8-2.0 at 24, 3.1-3.3 at
/// 48, 5.6-6.3 at 96, 13-14 at 192 (it was 200: the 32-link chain then ran dense, 10-12x slower
/// than with KLU at every rtol from 1e-3 to 1e-9, bench/dae_configs). SUNDIALS' dense LU as
/// Debian packages it is compiled without optimization, which moves the crossover down; with
/// an optimized one KLU still wins well below 192 unknowns.
#define DAL_SPARSE_THRESHOLD 12

/// Smallest local relative tolerance handed to any integrator: below it the error
/// estimates are dominated by rounding and the step size collapses.
#define DAL_TOL_FLOOR 1e-15
/// Smallest relative tolerance IDA is run at (after the tolerance factor): below it the
/// corrector stalls on rounding (measured: the Cartesian double pendulum fails at t = 9.5 with
/// h = 5e-23 at 1e-13; the moving-pivot pendulum collapses at t = 1.9e-8 at 5e-14).
/// Tighter requests are clamped to it and the clamp reported in dal_stats.rtol_used.
#define DAL_IDA_TOL_FLOOR 1e-12

/// Share of the velocity (position) tolerance that the Newton correction of a multiplier lambda
/// (GGL's mu) may take through its effect h M^-1 G' d lambda on v (h G' d mu on q) in IDA's
/// convergence test (integrate/ida.c, docs/dae.md). Measured on the spherical pendulum's
/// 180-start grid (rtol 1e-4 ... 1e-9, GGL): 1 passes every start but takes 40% more steps
/// than 0.001 (which keeps the old weights and fails 85 starts at 1e-8); 0.01 fails 26 at
/// 1e-9 (the rounding of G v, amplified by cj, fails the test again); 0.1 passes every start
/// with 11% more steps than the old weights where they worked.
#define DAL_IDA_MULT_SHARE 0.1

/// IDA's first step: 0.1 sqrt(rtol) (its own estimate is ~1e-16 at tight tolerances and
/// fails there).
#define DAL_IDA_H0_FACTOR 0.1

/// A step that advances t by at most this many ulps of max(1, |t|) makes no progress; this
/// many such steps in a row are a step size collapse (every method's progress guard).
#define DAL_TINY_STEP_ULPS 8.0
#define DAL_TINY_STEP_COUNT 5
#define DAL_TINY_STEP(t)                                                                           \
  (DAL_TINY_STEP_ULPS * DBL_EPSILON * ((t) > 1.0 || (t) < -1.0 ? ((t) < 0 ? -(t) : (t)) : 1.0))

/// Pivot ratio (smallest / largest squared Cholesky pivot of M) below which a non-finite
/// acceleration is blamed on a nearly singular mass matrix (a chart singularity) rather than on
/// forces too large for the masses; the factorization itself refuses ratios below 2.2e-13.
#define DAL_NEAR_SINGULAR 1e-8

/// A jet function whose inputs (values or directions) exceed this size and whose outputs are
/// not finite has overflowed (a product of two such numbers nears double range), which is a
/// trial step too long or a motion beyond double range (DAL__RETRY_NONFINITE), not a domain
/// error of the function (DAL_E_DOMAIN).
#define DAL_JET_OVERFLOW 1e100

#endif
