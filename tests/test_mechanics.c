// SPDX-License-Identifier: MIT
// placeholder replaced by the jet test suite
#include "check.h"
#include "dalembert/jet.h"
int main(void) {
  dal_jet x = dal_var(0.3, 1.0);
  CHECK_CLOSE(dal_sin(x).d, cos(0.3), 1e-15);
  return check_summary("test_mechanics");
}
