// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The sweep over MPI ranks: gathered CSV byte-identical to the threaded single-process CSV.
//
// Every rank compiles the same driven pendulum and runs its part of a 48-trajectory sweep
// over (drive amplitude, frequency) with one trajectory made invalid (negative mass); rank 0
// gathers, writes the CSV to argv[1] and compares it byte for byte with the same sweep run
// in this process alone on 2 threads (MPI_COMM_SELF is not needed: dal_sweep_run). The
// ctest script (run_mpi.sh) runs this under mpirun -np 1 and -np 2 and compares the files.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "dalembert/mpi.h"
#include "scenes.h"

static dal_system *driven(void) {
  scn_knobs k = scn_default(); // a drive of zero amplitude at w = 1, set per trajectory
  k.w = 1.0;
  return scn_pendulum(&k);
}

static int keep_final(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys;
  (void)ctx;
  dal_energies e;
  dal_state_energies(st, &e);
  tr->result[0] = dal_state_q(st)[0];
  tr->result[1] = dal_state_qdot(st)[0];
  tr->result[2] = e.E;
  return 0;
}

static char *csv_of(const dal_system *sys, const dal_sweep *sw, const dal_sweep_out *out) {
  FILE *fp = tmpfile();
  if (!fp) return NULL;
  const char *names[3] = {"theta", "thetadot", "E"};
  int rc = dal_sweep_write_csv(fp, sys, sw, out, names);
  long len = ftell(fp);
  char *buf = rc || len < 0 ? NULL : malloc((size_t)len + 1);
  if (buf) {
    rewind(fp);
    buf[fread(buf, 1, (size_t)len, fp)] = 0;
  }
  fclose(fp);
  return buf;
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  dal_system *sys = driven();
  CHECK(sys != NULL);
  enum { NA = 6, NW = 8, NT = NA * NW, NR = 3 };
  double values[NT * 3], q0 = 0.4, v0 = 0.0;
  int count[3] = {NA, NW, 1};
  double lo[3] = {0.0, 2.0, 1.0}, hi[3] = {0.3, 9.0, 1.0};
  CHECK(dal_sweep_grid(3, count, lo, hi, values) == NT);
  values[3 * 17 + 2] = -2.0; // trajectory 17: a negative mass
  dal_param_ref par[3];
  CHECK_OK(dal_param_find(sys, "place:bob:3", &par[0], NULL, 0));
  CHECK_OK(dal_param_find(sys, "place:bob:5", &par[1], NULL, 0));
  CHECK_OK(dal_param_find(sys, "mass:bob", &par[2], NULL, 0));
  dal_solve_opts so = dal_default_solve_opts();
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 3,
                  .params = par,
                  .values = values,
                  .q0 = &q0,
                  .qdot0 = &v0,
                  .solve = &so,
                  .t1 = 2.0,
                  .nresult = NR,
                  .reduce = keep_final};
  double res[NT * NR];
  int status[NT];
  char msgs[NT * 200];
  dal_sweep_out out = {res, status, msgs, 200, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = 1;
  char err[256];
  CHECK_OK(dal_sweep_run_mpi(sys, &sw, &o, &out, MPI_COMM_WORLD, err, sizeof err));
  int bad = 0;
  if (rank == 0) {
    CHECK(out.nrun == NT && out.nfailed == 1);
    CHECK(status[17] == DAL_E_ARG && strstr(msgs + 17 * 200, "mass -2 is not positive"));
    char *mpi_csv = csv_of(sys, &sw, &out);
    // the same sweep in this process alone
    double res2[NT * NR];
    int status2[NT];
    char msgs2[NT * 200];
    dal_sweep_out out2 = {res2, status2, msgs2, 200, 0, 0};
    o.nthreads = 2;
    CHECK_OK(dal_sweep_run(sys, &sw, &o, &out2, NULL, 0));
    char *local_csv = csv_of(sys, &sw, &out2);
    CHECK_MSG(mpi_csv && local_csv && strcmp(mpi_csv, local_csv) == 0,
              "CSV over %d ranks differs from the threaded run", size);
    FILE *fp = argc > 1 ? fopen(argv[1], "w") : NULL;
    CHECK(argc < 2 || fp != NULL);
    if (fp) {
      fputs(mpi_csv ? mpi_csv : "", fp);
      fclose(fp);
    }
    free(mpi_csv);
    free(local_csv);
    bad = check_summary("test_ensemble_mpi");
  }
  // a rejected sweep is rejected on every rank, without hanging
  dal_sweep badsw = sw;
  badsw.ntraj = 0;
  int rc = dal_sweep_run_mpi(sys, &badsw, &o, &out, MPI_COMM_WORLD, err, sizeof err);
  if (rc != DAL_E_ARG) bad = 1;
  // a non-finite target time too: DAL_E_NONFINITE on every rank, nothing gathered
  badsw = sw;
  badsw.t1 = NAN;
  for (int i = 0; i < NT; ++i)
    status[i] = 12345;
  rc = dal_sweep_run_mpi(sys, &badsw, &o, &out, MPI_COMM_WORLD, err, sizeof err);
  if (rc != DAL_E_NONFINITE || !strstr(err, "target time t1") || status[0] != 12345) bad = 1;
  MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
  dal_system_destroy(sys);
  MPI_Finalize();
  return bad;
}
