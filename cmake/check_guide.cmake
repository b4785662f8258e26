# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The guide is the path through the library: it names every public header and every example.
# usage: cmake -DGUIDE=docs/guide.md -DHEADERS=include/dalembert -DEXAMPLES=examples -P check_guide.cmake
file(READ ${GUIDE} guide)
file(GLOB headers ${HEADERS}/*.h)
file(GLOB examples ${EXAMPLES}/*.c)
set(missing "")
set(n 0)
foreach(f IN LISTS headers examples)
  get_filename_component(name ${f} NAME)
  string(FIND "${guide}" "${name}" pos)
  if(pos LESS 0)
    list(APPEND missing ${name})
  else()
    math(EXPR n "${n} + 1")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "the guide (${GUIDE}) does not name: ${missing}")
endif()
message(STATUS "guide: names all ${n} headers and examples")
