// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Status strings from the X-macro list, and the library version.
#include "dalembert/base.h"

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
