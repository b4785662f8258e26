// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Errors: status strings from the X-macro list, message formatting, the one conversion of
// internal codes to public statuses, and the library version.
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/base.h"

const char *dal_status_string(int status) {
  switch (status) {
#define DAL_X_CASE(name, value, text)                                                              \
  case value:                                                                                      \
    return text;
    DAL_STATUS_LIST(DAL_X_CASE)
#undef DAL_X_CASE
  default:
    return "unknown status";
  }
}

const char *dal_status_name(int status) {
  switch (status) {
#define DAL_X_NAME(name, value, text)                                                              \
  case value:                                                                                      \
    return #name;
    DAL_STATUS_LIST(DAL_X_NAME)
#undef DAL_X_NAME
  default:
    return "DAL_UNKNOWN";
  }
}

const char *dal_version(void) { return DAL_VERSION_STRING; }

int dal__set_err(char *buf, int status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, DAL_ERRMSG_LEN, fmt, ap);
  va_end(ap);
  return status;
}

void dal__fmt_q(const dal_system *sys, const double *q, char *buf, size_t len) {
  size_t used = 0;
  buf[0] = 0;
  int shown = sys->n < 6 ? sys->n : 6;
  for (int i = 0; i < shown && used < len; ++i)
    used += (size_t)snprintf(buf + used, len - used, "%s%s=%.6g", i ? ", " : "",
                             sys->coord_names[i], q[i]);
  if (sys->n > shown && used < len) snprintf(buf + used, len - used, ", ...");
}

void dal__free_all(void *const *p, size_t n) {
  for (size_t i = 0; i < n; ++i)
    free(p[i]);
}

dal_qtext dal__qtext(const dal_system *sys, const double *q) {
  dal_qtext t;
  dal__fmt_q(sys, q, t.s, sizeof t.s);
  return t;
}

int dal__cb_status(dal_state *st, int rc, const char *what) {
  if (rc == 0) return DAL_OK;
  if (rc > 0) {
    DAL_FAIL(st, DAL__RECOVERABLE, "%s asked for a smaller step (returned %d) at t=%.17g", what, rc,
             st->t);
    return DAL__RECOVERABLE;
  }
  return DAL_FAIL(st, DAL_E_CALLBACK,
                  "%s failed (returned %d) at t=%.17g; the state holds the "
                  "last accepted step",
                  what, rc, st->t);
}

int dal__public_status(int rc) {
  switch (rc) {
  case DAL__RECOVERABLE:
    return DAL_E_CALLBACK;
  case DAL__RETRY_NONFINITE:
    return DAL_E_NONFINITE;
  case DAL__RETRY_SINGULAR:
    return DAL_E_SINGULAR;
  default:
    return rc > 0 ? DAL_E_SOLVER : rc;
  }
}

int dal__check_idle(dal_state *st, const char *what) {
  if (!st->busy) return DAL_OK;
  return DAL_FAIL(st, DAL_E_STATE,
                  "%s: the state is being integrated (called from a monitor or event function "
                  "of dal_advance / dal_evolve on this state, which would pull it from under the "
                  "integrator); return 1 from the monitor to stop the run, then call it, or work "
                  "on a copy",
                  what);
}

int dal__check_pair(const dal_system *sys, const dal_state *st, const char *what) {
  if (!st) return DAL_E_ARG;
  if (sys && st->sys == sys) return DAL_OK;
  return DAL_FAIL_C(st, DAL_E_STATE,
                    "%s: %s; create the state from the system you pass (dal_state_create)", what,
                    sys ? "the state belongs to another system" : "the system is NULL");
}
