// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Export macro, status codes and version of the dalembert library.
#ifndef DAL_BASE_H
#define DAL_BASE_H

#if defined(DAL_STATIC)
#define DAL_API
#elif defined(_WIN32) && defined(DAL_BUILDING)
#define DAL_API __declspec(dllexport)
#elif defined(_WIN32)
#define DAL_API __declspec(dllimport)
#elif defined(__GNUC__)
#define DAL_API __attribute__((visibility("default")))
#else
/// Marks a declaration exported by the dalembert library (symbol visibility on ELF, dllexport /
/// dllimport on Windows); empty for a static build (define DAL_STATIC when linking statically
/// outside CMake; the CMake package does it for you).
#define DAL_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/// Major version of the headers being compiled against (incompatible API changes).
#define DAL_VERSION_MAJOR 0
/// Minor version of the headers: additions that keep the API compatible from 1.0 on; while
/// MAJOR is 0 a minor step may change the API (CHANGELOG.md says how to port).
#define DAL_VERSION_MINOR 3
/// Patch version of the headers (fixes only).
#define DAL_VERSION_PATCH 0
/// The version as one comparable integer, e.g. `#if DAL_VERSION_NUMBER >= 300` for 0.3.0.
#define DAL_VERSION_NUMBER (DAL_VERSION_MAJOR * 10000 + DAL_VERSION_MINOR * 100 + DAL_VERSION_PATCH)

// Conventions of the whole API (0.3 on):
// - names: dal_<object>_<verb>[_<what>] for a call on an object (dal_builder_add_particle,
//   dal_state_set), dal_<object>_create/_destroy for its life; an element made from a def is
//   added by dal_builder_<verb>_def.
// - defaults: every def and every options struct T (dal_place_def, dal_solve_opts, ...) is
//   started from `T x = dal_default_<T without dal_>();`, which returns it by value with every
//   field at its documented default and a `cookie` field set; a struct that did not come from
//   it is refused (DAL_E_ARG, the message naming the constructor). One form for both kinds:
//   by value, as Box2D v3's b2Default*Def(), because a def or options struct is small, is
//   filled once and read during the call only, and `T x = dal_default_x();` cannot leave x
//   uninitialized (an out-parameter constructor can be forgotten before the first field is
//   set). The cookie catches a struct written field by field or zeroed by memset.

/// The one list of status codes: X(name, value, description).
/// 0 is success; every failure is negative. The positive codes are not failures: dal_evolve
/// returns DAL_STOPPED when a monitor asked to stop before the end time, dal_advance and
/// dal_evolve return DAL_EVENT when a terminal event stopped them (events.h), and every run
/// returns DAL_CANCELLED when the cancel hook of its options asked it to stop (solve.h). A detailed
/// message naming the culprit and a remedy is kept by the object that failed (dal_builder_errmsg,
/// dal_state_errmsg).
#define DAL_STATUS_LIST(X)                                                                         \
  X(DAL_OK, 0, "ok")                                                                               \
  X(DAL_STOPPED, 1, "stopped early by a monitor (not an error)")                                   \
  X(DAL_EVENT, 2, "stopped at a terminal event (not an error)")                                    \
  X(DAL_CANCELLED, 3, "cancelled by the caller's cancel hook (not an error)")                      \
  X(DAL_E_ARG, -1, "invalid argument (index, dimension, count or option)")                         \
  X(DAL_E_NOMEM, -2, "out of memory")                                                              \
  X(DAL_E_NONFINITE, -3, "non-finite input (NaN or inf)")                                          \
  X(DAL_E_DOMAIN, -4, "a jet function produced NaN or inf (domain error)")                         \
  X(DAL_E_SINGULAR, -5, "mass matrix singular or not positive definite")                           \
  X(DAL_E_CALLBACK, -6, "a user callback reported an unrecoverable failure")                       \
  X(DAL_E_CONSTRAINT, -7, "redundant or conflicting constraints")                                  \
  X(DAL_E_INIT, -8, "consistent initial state could not be assembled")                             \
  X(DAL_E_STEP, -9, "step size underflow")                                                         \
  X(DAL_E_MAXSTEPS, -10, "too many steps before the target time")                                  \
  X(DAL_E_CONV, -11, "nonlinear or error-test convergence failure")                                \
  X(DAL_E_SOLVER, -12, "integrator or linear solver failure")                                      \
  X(DAL_E_TIME, -13, "target time lies behind the current time")                                   \
  X(DAL_E_STATE, -14, "state not initialized or belongs to another system")                        \
  X(DAL_E_UNSUPPORTED, -15, "method and formulation cannot be combined")                           \
  X(DAL_E_IO, -16, "file input/output failed")                                                     \
  X(DAL_E_VERIFY, -17, "a verification check found a mismatch (see its report)")                   \
  X(DAL_E_TOO_LARGE, -18, "too large to show (a size or work bound of the symbolic algebra)")

#ifdef DAL_DOXYGEN
/// Status codes returned by every fallible dalembert call: DAL_OK (0), the three positive
/// statuses that are not failures, and the negative failure codes. (The API reference reads
/// this spelled-out copy; the compiler reads DAL_STATUS_LIST. The reference's ctest checks that
/// both give the same names and values.)
typedef enum dal_status {
  DAL_OK = 0,              ///< ok
  DAL_STOPPED = 1,         ///< stopped early by a monitor (not an error)
  DAL_EVENT = 2,           ///< stopped at a terminal event (not an error)
  DAL_CANCELLED = 3,       ///< cancelled by the caller's cancel hook (not an error)
  DAL_E_ARG = -1,          ///< invalid argument (index, dimension, count or option)
  DAL_E_NOMEM = -2,        ///< out of memory
  DAL_E_NONFINITE = -3,    ///< non-finite input (NaN or inf)
  DAL_E_DOMAIN = -4,       ///< a jet function produced NaN or inf (domain error)
  DAL_E_SINGULAR = -5,     ///< mass matrix singular or not positive definite
  DAL_E_CALLBACK = -6,     ///< a user callback reported an unrecoverable failure
  DAL_E_CONSTRAINT = -7,   ///< redundant or conflicting constraints
  DAL_E_INIT = -8,         ///< consistent initial state could not be assembled
  DAL_E_STEP = -9,         ///< step size underflow
  DAL_E_MAXSTEPS = -10,    ///< too many steps before the target time
  DAL_E_CONV = -11,        ///< nonlinear or error-test convergence failure
  DAL_E_SOLVER = -12,      ///< integrator or linear solver failure
  DAL_E_TIME = -13,        ///< target time lies behind the current time
  DAL_E_STATE = -14,       ///< state not initialized or belongs to another system
  DAL_E_UNSUPPORTED = -15, ///< method and formulation cannot be combined
  DAL_E_IO = -16,          ///< file input/output failed
  DAL_E_VERIFY = -17,      ///< a verification check found a mismatch (see its report)
  DAL_E_TOO_LARGE = -18,   ///< too large to show (a size or work bound of the symbolic algebra)
} dal_status;
#else
typedef enum dal_status {
#define DAL_X_ENUM(name, value, text) name = value,
  DAL_STATUS_LIST(DAL_X_ENUM)
#undef DAL_X_ENUM
} dal_status;
#endif

/// Short static description of a status code ("unknown status" for other values).
DAL_API const char *dal_status_string(int status);

/// Symbolic name of a status code, e.g. "DAL_E_SINGULAR" ("DAL_UNKNOWN" for other values).
DAL_API const char *dal_status_name(int status);

/// Version of the library actually linked, as "major.minor.patch" (static string); compare
/// with DAL_VERSION_MAJOR/MINOR/PATCH to detect a header/library mismatch.
DAL_API const char *dal_version(void);

#ifdef __cplusplus
}
#endif
#endif
