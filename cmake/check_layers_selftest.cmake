# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The layer check's own test (ctest `layers_selftest`): in a copy of the tree, each rule of
# check_layers.cmake is broken once on purpose, and the check must fail with the message that
# names the break; the copy as it is must pass.
# Run: cmake -DROOT=<repo> -DWORK=<scratch folder> -P check_layers_selftest.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(d src include constraints cmake tests bench examples tools scripts docs)
  file(COPY ${ROOT}/${d} DESTINATION ${WORK})
endforeach()
file(GLOB mds ${ROOT}/*.md)
file(COPY ${mds} DESTINATION ${WORK})

# run the check on the copy: *rc its exit status, *text its messages on one line
function(run_check rc text)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSRC=${WORK}/src -P ${WORK}/cmake/check_layers.cmake
    RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX REPLACE "[ \t\r\n]+" " " t "${out} ${err}")
  set(${rc} ${r} PARENT_SCOPE)
  set(${text} "${t}" PARENT_SCOPE)
endfunction()

# one break: in `file` of the copy, `from` replaced by `to` (from "" appends `to`); the check
# must fail naming `want`; the file is put back
function(expect_break name file from to want)
  file(READ ${WORK}/${file} orig)
  if(from STREQUAL "")
    set(broken "${orig}${to}")
  else()
    string(REPLACE "${from}" "${to}" broken "${orig}")
  endif()
  if(broken STREQUAL orig)
    message(SEND_ERROR "${name}: '${from}' is not in ${file}; update this case")
    return()
  endif()
  file(WRITE ${WORK}/${file} "${broken}")
  run_check(rc text)
  file(WRITE ${WORK}/${file} "${orig}")
  string(FIND "${text}" "${want}" at)
  if(rc EQUAL 0 OR at EQUAL -1)
    message(SEND_ERROR "${name}: the check gave rc=${rc} without '${want}': ${text}")
  else()
    message(STATUS "${name}: fails (rc=${rc}) with: ${want}")
  endif()
endfunction()

run_check(rc text)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the unbroken copy fails the check: ${text}")
endif()

expect_break("an include running up" src/base/errors.c "" "#include \"eval/eval.h\"\n"
  "src/base/errors.c: layer base includes eval/eval.h of the layer above it (eval)")
expect_break("an include running up in angle brackets" src/base/opts.c "" "#include <eval/eval.h>\n"
  "src/base/opts.c: layer base includes eval/eval.h of the layer above it (eval)")
expect_break("a private header of another folder" src/drive/csv.c "" "#include \"integrate/nvec.h\"\n"
  "src/drive/csv.c: includes integrate/nvec.h, a private header of src/integrate/ (only integrate/integrate.h faces the layers above)")
expect_break("an include that is no header of its folder" src/eval/rank.c "" "#include \"kkt.h\"\n"
  "src/eval/rank.c: \"kkt.h\" is not a header of src/eval/")
expect_break("a face declaring what another folder defines" src/base/base.h ""
  "int dal__eval(void);\n"
  "src/base/base.h: declares dal__eval, which src/eval/")
expect_break("a face declaring what no file defines" src/model/model.h "" "int dal__nowhere(void);\n"
  "src/model/model.h: declares dal__nowhere, which no .c file of src/ defines: remove the declaration")
expect_break("a guard off its path" src/eval/eval.h "DAL_EVAL_EVAL_H" "DAL_DAE_INTERNAL_H"
  "src/eval/eval.h: include guard '#ifndef DAL_DAE_INTERNAL_H' does not spell the path: use DAL_EVAL_EVAL_H")
expect_break("a public guard off its path" include/dalembert/solve.h "DAL_SOLVE_H" "DAL_SOLVE_OPTS_H"
  "include/dalembert/solve.h: include guard '#ifndef DAL_SOLVE_OPTS_H' does not spell the path: use DAL_SOLVE_H")
expect_break("a comment naming a missing file" src/form/init.c "" "// as solve.c did\n"
  "src/form/init.c: a comment names solve.c, which does not exist")
expect_break("a comment naming a missing path" include/dalembert/state.h "" "// src/dae_ida.c\n"
  "include/dalembert/state.h: a comment names src/dae_ida.c, which does not exist")

# a folder of src/ that is no layer
file(WRITE ${WORK}/src/extra/extra.c "// SPDX-License-Identifier: MIT\n")
run_check(rc text)
file(REMOVE_RECURSE ${WORK}/src/extra)
set(want "src/extra/ is not a layer: add it to cmake/check_layers.cmake")
string(FIND "${text}" "${want}" at)
if(rc EQUAL 0 OR at EQUAL -1)
  message(SEND_ERROR "a folder that is no layer: the check gave rc=${rc} without '${want}': ${text}")
else()
  message(STATUS "a folder that is no layer: fails (rc=${rc}) with: ${want}")
endif()
file(REMOVE_RECURSE ${WORK})
