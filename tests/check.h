// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A tiny test harness: CHECK, CHECK_CLOSE (relative + absolute), CHECK_OK, and a summary.
#ifndef DAL_CHECK_H
#define DAL_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_failures = 0, check_count = 0;

#define CHECK(cond)                                                                                \
  do {                                                                                             \
    ++check_count;                                                                                 \
    if (!(cond)) {                                                                                 \
      ++check_failures;                                                                            \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);                     \
    }                                                                                              \
  } while (0)

#define CHECK_MSG(cond, ...)                                                                       \
  do {                                                                                             \
    ++check_count;                                                                                 \
    if (!(cond)) {                                                                                 \
      ++check_failures;                                                                            \
      fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);                     \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fputc('\n', stderr);                                                                         \
    }                                                                                              \
  } while (0)

/// |a - b| <= tol * max(1, |b|): relative for large values, absolute near zero
#define CHECK_CLOSE(a, b, tol)                                                                     \
  do {                                                                                             \
    double ca_ = (a), cb_ = (b), ct_ = (tol);                                                      \
    double scale_ = fabs(cb_) > 1.0 ? fabs(cb_) : 1.0;                                             \
    ++check_count;                                                                                 \
    if (!(fabs(ca_ - cb_) <= ct_ * scale_)) {                                                      \
      ++check_failures;                                                                            \
      fprintf(stderr, "%s:%d: %s = %.17g, expected %s = %.17g (tol %g, diff %.3g)\n", __FILE__,    \
              __LINE__, #a, ca_, #b, cb_, ct_, fabs(ca_ - cb_));                                   \
    }                                                                                              \
  } while (0)

#define CHECK_OK(call)                                                                             \
  do {                                                                                             \
    int rc_ = (call);                                                                              \
    ++check_count;                                                                                 \
    if (rc_ != 0) {                                                                                \
      ++check_failures;                                                                            \
      fprintf(stderr, "%s:%d: %s returned %d\n", __FILE__, __LINE__, #call, rc_);                  \
    }                                                                                              \
  } while (0)

/// deterministic uniform random numbers in [lo, hi) (xorshift64*)
static inline double check_rand(unsigned long long *s, double lo, double hi) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  unsigned long long x = *s * 2685821657736338717ULL;
  return lo + (hi - lo) * (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

static inline int check_summary(const char *name) {
  printf("%s: %d checks, %d failed\n", name, check_count, check_failures);
  return check_failures ? 1 : 0;
}

#endif
