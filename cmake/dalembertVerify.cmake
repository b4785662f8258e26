# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# dalembert_add_verify_test: register a verification program of your own model as a ctest.
#
#   enable_testing()
#   dalembert_add_verify_test(<name> SOURCES <file.c>... [ARGS <arg>...]
#                             [LIBRARIES <lib>...] [LABELS <label>...])
#
# builds the executable <name> from SOURCES linked with dalembert::dalembert (and LIBRARIES),
# and adds the test <name> running it with ARGS, labelled `dalembert_verify` (plus LABELS).
# The program calls the checks of <dalembert/verify.h> (dal_verify_primitive, dal_verify_map,
# dal_verify_potential_q/r, dal_verify_lagrangian, dal_verify_model), prints their reports and
# returns nonzero when one fails; `ctest -L dalembert_verify` then runs all such checks.
# Installed with dalembert's CMake package: find_package(dalembert) makes it available.
function(dalembert_add_verify_test name)
  cmake_parse_arguments(DAV "" "" "SOURCES;ARGS;LIBRARIES;LABELS" ${ARGN})
  if(NOT DAV_SOURCES)
    message(FATAL_ERROR "dalembert_add_verify_test(${name}): give SOURCES")
  endif()
  if(NOT TARGET dalembert::dalembert)
    message(FATAL_ERROR "dalembert_add_verify_test(${name}): call find_package(dalembert) first")
  endif()
  add_executable(${name} ${DAV_SOURCES})
  target_link_libraries(${name} PRIVATE dalembert::dalembert ${DAV_LIBRARIES})
  if(NOT WIN32)
    target_link_libraries(${name} PRIVATE m)
  endif()
  add_test(NAME ${name} COMMAND ${name} ${DAV_ARGS})
  set_tests_properties(${name} PROPERTIES LABELS "dalembert_verify;${DAV_LABELS}")
endfunction()
