// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Every threshold that chooses a code path or a tolerance, in one place, with its reason.
#ifndef DAL_BASE_BOUNDS_H
#define DAL_BASE_BOUNDS_H

#include <float.h>

/// Largest n with a dense mass matrix in a constrained system (n x n doubles per state:
/// 2 MiB at 512). Above it M exists only through the particle Jacobians (sparse KKT, IDA
/// residual). Systems without constraints always keep a dense M (Cholesky).
#define DAL_DENSE_M_MAX 512

/// Most constraint rows solved by the m x m loop system on top of the recursion (aba.c: m
/// recursion solves with unit loads, the m x m matrix G M^-1 G' and its unblocked Cholesky,
/// O(m N + m^2 + m^3)); with more rows the KKT matrix in all coordinates is used. Which wins
/// depends on M's coupling. Where M is dense (a tree in minimal coordinates: the held 64-link
/// chain, m = 1, runs 9.7x faster on the loop system) its KKT matrix is dense too and the loop
/// system wins at every m measured (0.28 of the dense KKT matrix at m = 4, 0.47 at 64:
/// routes_ir.csv). Where M couples few coordinates (DAL_KKT_LOCAL_COUPLING: Cartesian
/// particles) the KKT matrix goes to KLU, which wins from m = 3: on the Cartesian N-link chain
/// (index-1 with projection, DOPRI5, rtol 1e-6, instructions per step, bench/cliff.sh) loop
/// system / KKT by KLU is 1.02 at m = 2, 1.10 at 3, 1.35 at 6, 2.05 at 16, 3.0 at 32, 6.9 at
/// 128 (it was handed the dense KKT matrix from m = 33 to 66: 8.7x KLU at m = 64, the cliff
/// of the old thresholds).
#ifndef DAL_LOOP_ROWS_MAX
#define DAL_LOOP_ROWS_MAX 32
#endif
#ifndef DAL_LOOP_ROWS_LOCAL_MAX
#define DAL_LOOP_ROWS_LOCAL_MAX 2
#endif

/// M couples few coordinates when the sum over particles of the square of the number of
/// coordinates each depends on is at most this many times n (a Cartesian particle in 3D:
/// 9 for 3 coordinates); such a system's KKT matrix is factored by KLU at any order. Measured
/// on the Cartesian N-link chain (KKT order 3N, index-1 with projection, instructions per
/// step): dense (LAPACK dsytrf) / KLU 3.7 at order 6, 4.8 at 24, 6.5 at 96, 8.7 at 192 — the
/// dense factorization never wins (OpenBLAS' per-call overhead at small orders, O(n^3) at
/// large ones).
#define DAL_KKT_LOCAL_COUPLING 3.0

/// Smallest KKT order factored sparse (KLU) for a strongly coupled M (a dense M exists and
/// the system is not DAL_KKT_LOCAL_COUPLING), and the largest fill (non-zeros / order^2) for
/// it (N = 256: 0.22 s dense -> 0.09 s KLU; not re-measured: no default route of the
/// benchmark scenes reaches it).
#ifndef DAL_KKT_SPARSE_MIN
#define DAL_KKT_SPARSE_MIN 200
#endif
#ifndef DAL_KKT_SPARSE_FILL
#define DAL_KKT_SPARSE_FILL 0.05
#endif
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

/// DAL_METHOD_AUTO for the ODE and index-1 forms (integrate/methods.c, solve.h): DOPRI5 from
/// rtol DAL_AUTO_LOOSE_RTOL up; below, Bulirsch-Stoer for systems of at most DAL_AUTO_SMALL_N
/// coordinates, otherwise DOPRI5 down to DAL_AUTO_MID_RTOL and Bulirsch-Stoer below. Read off
/// the work-precision tables of bench/auto.sh and bench/dense_auto.sh (docs/performance.md
/// "AUTO"), among the methods whose error estimate holds on the differential set of
/// tests/test_auto_set.c (300 random trees with springs between siblings): Fehlberg 7(8), the
/// cheapest at 1e-5 ... 1e-8 on the seed scenes, gave up to 112 x rtol times the scene's
/// amplification there and is no longer taken (issue 31).
#define DAL_AUTO_SMALL_N 2
#define DAL_AUTO_LOOSE_RTOL 1e-3

/// Three or more coordinates: DOPRI5 down to this rtol, Bulirsch-Stoer below, with or without
/// dense output (outputs every 0.001 on the chain, N = 1 ... 64, bench/dense_auto.sh: DOPRI5
/// 1.3-2.7x the cheapest method at errors of 1e-8 ... 1e-10, Bulirsch-Stoer 1.0-1.2x there and
/// at most 1.44x at 1e-7).
#define DAL_AUTO_MID_RTOL 1e-5

/// Smallest local relative tolerance handed to any integrator: below it the error
/// estimates are dominated by rounding and the step size collapses.
#define DAL_TOL_FLOOR 1e-15
/// Local relative tolerance IDA retreats to (after the tolerance factor) when a step fails
/// below it: there the corrector may stall on rounding (measured: the Cartesian double
/// pendulum fails at t = 9.5 with h = 5e-23 at 1e-13; the moving-pivot pendulum collapses at
/// t = 1.9e-8 at 5e-14; the spherical pendulum fails at the start at 1e-13 on some starts),
/// while other scenes gain from running below it (the car axis of tests/test_caraxis.c: 7.5
/// digits at 1e-12, 9.3 at 1e-14). A tighter run starts at the requested tolerance and, on a
/// failed step, continues at this floor from its last accepted step, with a note
/// (integrate/ida.c); DAL_FORM_AUTO with DAL_METHOD_AUTO avoids IDA below it.
#define DAL_IDA_TOL_FLOOR 1e-12
/// Smallest local relative tolerance IDA is tried at: below it the step count grows
/// without gain (the car axis: 9.32 digits in 28888 steps at 1e-14, 9.05 in 326466 at 1e-15;
/// 1e-16 stops at t = 3.3e-4). Tighter requests are clamped to it, reported in
/// dal_stats.rtol_used.
#define DAL_IDA_TOL_TRY 1e-14
/// An IDA failure blames the constraints when the smallest pivot ratio of their gradients (the
/// rank test of dal_check_constraints) fell below this share of the start's (they are becoming
/// dependent: the rod-and-rail scene of tests/test_dae_messages.c, 0.87 at the start and
/// 2.2e-3 where IDA stops), or when a row's largest gradient entry did (a cusp).
#define DAL_IDA_DEP_DROP 0.01

/// Share of the velocity (position) tolerance that the Newton correction of a multiplier lambda
/// (GGL's mu) may take through its effect h M^-1 G' d lambda on v (h G' d mu on q) in IDA's
/// convergence test (integrate/ida.c, docs/dae.md). Measured on the spherical pendulum's
/// 180-start grid (rtol 1e-4 ... 1e-9, GGL): 1 passes every start but takes 40% more steps
/// than 0.001 (which keeps the old weights and fails 85 starts at 1e-8); 0.01 fails 26 at
/// 1e-9 (the rounding of G v, amplified by cj, fails the test again); 0.1 passes every start
/// with 11% more steps than the old weights where they worked.
#define DAL_IDA_MULT_SHARE 0.1

/// IDA's Newton upkeep on systems of DAL_IDA_UPKEEP_MIN unknowns and more (integrate/ida.c).
/// IDA rebuilds the Newton matrix only when cj = alpha / h moved by a share DCJ (its default
/// 0.25): between, the matrix ages, the iteration slows until a step needs a second iteration
/// (every step of the Cartesian chain at 724 links, rtol 1e-6) or fails (3-6 times per run
/// at 1e-8, each failure quartering h). A matrix is rebuilt at a 5% change of cj
/// (DAL_IDA_DCJ) and after DAL_IDA_STALE_SOLVES solves in a row that each needed two or more
/// iterations on the same matrix. Measured (bench/dae_bench.c scaling, GGL + KLU, N = 256 ...
/// 4096 links, rtol 1e-6 and 1e-8): Newton iterations 30-60% fewer, 1.11-1.21 per step at
/// every size, errors within 2x either way (docs/performance.md, DAE scaling). Kept off below 24
/// unknowns: on the car axis (12, tests/test_caraxis.c) the failures had been shortening the
/// steps, and without them GGL gives 0.1-0.3 fewer digits at rtol 1e-7 ... 1e-10 (in 20-25%
/// fewer steps).
#define DAL_IDA_UPKEEP_MIN 24
#define DAL_IDA_DCJ 0.05
#define DAL_IDA_STALE_SOLVES 3

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
