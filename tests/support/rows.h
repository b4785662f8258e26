// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The row table of the bad-input and reliability suites: a row provokes one failure, and the
// loop checks its exact status and the words its message must (and must not) contain.
#ifndef DAL_TESTS_ROWS_H
#define DAL_TESTS_ROWS_H

#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

/// The size of the message buffer a row fills.
#define MSG_LEN 512

/// One row: a function that sets up its scene, makes the failing call, copies the message into
/// msg, checks survival and recovery itself, frees everything and returns the failing call's
/// status; or one case of a function shared by several rows, with its data.
typedef struct bad_row {
  const char *name;
  int expect;                                   ///< the exact status
  const char *culprit, *culprit2;               ///< substrings the message must contain, or NULL
  const char *never;                            ///< a substring it must not contain, or NULL
  int (*run)(char *msg);                        ///< a row of its own, or NULL and
  int (*run_case)(char *msg, const void *data); ///< a row shared by cases, with
  const void *data;                             ///< the case's data
} bad_row;

/// Copy s (NULL: nothing) into a row's message buffer of MSG_LEN bytes.
static inline void copy_msg(char *msg, const char *s) { snprintf(msg, MSG_LEN, "%s", s ? s : ""); }

/// Run the n rows and print one line each; the suite's summary (0 when every check held).
static inline int rows_run(const bad_row *rows, int n, const char *suite) {
  for (int i = 0; i < n; ++i) {
    const bad_row *r = &rows[i];
    char msg[MSG_LEN] = "";
    int before = check_failures;
    int rc = r->run ? r->run(msg) : r->run_case(msg, r->data);
    CHECK_MSG(rc == r->expect, "row '%s': status %s, expected %s (message: %s)", r->name,
              dal_status_name(rc), dal_status_name(r->expect), msg);
    const char *want[2] = {r->culprit, r->culprit2};
    for (int k = 0; k < 2; ++k)
      if (want[k])
        CHECK_MSG(strstr(msg, want[k]) != NULL, "row '%s': message does not name '%s': %s", r->name,
                  want[k], msg);
    if (r->never)
      CHECK_MSG(strstr(msg, r->never) == NULL, "row '%s': message names '%s' (wrong culprit): %s",
                r->name, r->never, msg);
    printf("%-55s %-16s %s | %.300s\n", r->name, dal_status_name(rc),
           check_failures == before ? "ok  " : "FAIL", msg);
  }
  return check_summary(suite);
}

#endif
