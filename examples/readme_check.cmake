# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The README's first C code block must be examples/first_program.c verbatim (so it cannot rot).
file(READ ${README} readme)
file(READ ${PROGRAM} program)
string(FIND "${readme}" "```c\n" start)
if(start LESS 0)
  message(FATAL_ERROR "no C code block in ${README}")
endif()
math(EXPR start "${start} + 5")
string(SUBSTRING "${readme}" ${start} -1 rest)
string(FIND "${rest}" "```" end)
string(SUBSTRING "${rest}" 0 ${end} block)
if(NOT block STREQUAL program)
  message(FATAL_ERROR "README's first program differs from ${PROGRAM}; copy the file into the README")
endif()
message(STATUS "README first program matches ${PROGRAM}")
