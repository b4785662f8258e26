# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Embed text files as the bytes of C initializers (src/view/page.c includes them): the viewer's
# page, src/view/page.*, stays a source in the tree and is compiled into the library.
# Run: cmake -DFILES="out.inc=in.js;..." -P embed.cmake
foreach(pair ${FILES})
  string(REGEX REPLACE "=.*" "" out "${pair}")
  string(REGEX REPLACE "^[^=]*=" "" path "${pair}")
  file(READ ${path} hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REGEX REPLACE "((0x..,){24})" "\\1\n" bytes "${bytes}")
  file(WRITE ${out}.tmp "${bytes}0x00\n")
  file(COPY_FILE ${out}.tmp ${out} ONLY_IF_DIFFERENT)
endforeach()
