# Checks that the README's library example is tests/install/main.c, byte for
# byte, so the example the README shows is the one the install test builds.
# The block is the ```c fence right after the line
# "<!-- example: tests/install/main.c -->".
# usage: cmake -DREADME=README.md -DEXAMPLE=tests/install/main.c -P readme_example.cmake
file(READ "${README}" readme)
file(READ "${EXAMPLE}" example)
set(marker "<!-- example: tests/install/main.c -->\n```c\n")
string(FIND "${readme}" "${marker}" start)
if(start EQUAL -1)
  message(FATAL_ERROR "${README}: no line '<!-- example: tests/install/main.c -->' "
                      "followed by a ```c fence")
endif()
string(LENGTH "${marker}" marker_length)
math(EXPR start "${start} + ${marker_length}")
string(SUBSTRING "${readme}" ${start} -1 rest)
string(FIND "${rest}" "\n```" end)
if(end EQUAL -1)
  message(FATAL_ERROR "${README}: the example's code fence is not closed")
endif()
math(EXPR end "${end} + 1")
string(SUBSTRING "${rest}" 0 ${end} block)
if(NOT block STREQUAL example)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/readme_example.c" "${block}")
  message(FATAL_ERROR "The README example differs from ${EXAMPLE} (README's block written "
                      "to ${CMAKE_CURRENT_BINARY_DIR}/readme_example.c; diff them and paste "
                      "main.c into README.md)")
endif()
message(STATUS "README example matches ${EXAMPLE}")
