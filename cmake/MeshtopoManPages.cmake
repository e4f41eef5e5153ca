# Manual pages of the installed programs, written at build time by help2man
# from each program's own --help (packaging/man-pages.sh): meshtopo(1),
# meshtopo-COMMAND(1) for every command `meshtopo --help` lists, meshtopod(1)
# and meshtopo-bench(1) (when the benchmarks are built), gzip -9n compressed
# into BUILD/man/man1 and installed to share/man/man1 (component runtime, so
# the meshtopo Debian package has them). A page follows its program: it is
# written again whenever the program, the archive-commands module or the
# script changes. Without help2man (Debian: help2man), with
# -DMESHTOPO_BUILD_MAN_PAGES=OFF or when cross-compiling (the programs must
# run) there are no pages and a message says so; the package test
# (tests/install/package_check.sh) then fails. Included from
# cmake/MeshtopoInstall.cmake, after every program's target exists.

option(MESHTOPO_BUILD_MAN_PAGES "Write man pages of the programs with help2man at build time" ON)
find_program(MESHTOPO_HELP2MAN help2man)
find_program(MESHTOPO_GZIP gzip)
mark_as_advanced(MESHTOPO_HELP2MAN MESHTOPO_GZIP)

set(MESHTOPO_MAN_DIR ${PROJECT_BINARY_DIR}/man)
set(MESHTOPO_HAVE_MAN_PAGES OFF)
if(NOT MESHTOPO_BUILD_MAN_PAGES)
  message(STATUS "man pages: not written (MESHTOPO_BUILD_MAN_PAGES is OFF)")
elseif(NOT TARGET meshtopo OR NOT TARGET meshtopod)
  message(STATUS "man pages: not written (meshtopo or meshtopod is not built)")
elseif(CMAKE_CROSSCOMPILING)
  message(STATUS "man pages: not written (cross-compiling: help2man runs the programs)")
elseif(NOT MESHTOPO_HELP2MAN OR NOT MESHTOPO_GZIP)
  message(STATUS "man pages: not written, help2man or gzip not found "
                 "(Debian: apt-get install help2man)")
else()
  set(MESHTOPO_HAVE_MAN_PAGES ON)
  set(man_programs $<TARGET_FILE:meshtopo> $<TARGET_FILE:meshtopod>)
  set(man_depends meshtopo meshtopod)
  if(TARGET meshtopo_archive_commands)
    list(APPEND man_depends meshtopo_archive_commands)
  endif()
  if(TARGET meshtopo-bench)
    list(APPEND man_programs $<TARGET_FILE:meshtopo-bench>)
    list(APPEND man_depends meshtopo-bench)
  endif()
  set(man_script ${PROJECT_SOURCE_DIR}/packaging/man-pages.sh)
  add_custom_command(
    OUTPUT ${MESHTOPO_MAN_DIR}/man-pages.stamp
    COMMAND bash ${man_script} ${MESHTOPO_MAN_DIR} ${PROJECT_VERSION} ${man_programs}
    COMMAND ${CMAKE_COMMAND} -E touch ${MESHTOPO_MAN_DIR}/man-pages.stamp
    DEPENDS ${man_script} ${man_depends}
    COMMENT "Writing man pages with help2man"
    VERBATIM)
  add_custom_target(meshtopo_man_pages ALL DEPENDS ${MESHTOPO_MAN_DIR}/man-pages.stamp)
  install(DIRECTORY ${MESHTOPO_MAN_DIR}/man1 DESTINATION ${CMAKE_INSTALL_MANDIR}
          COMPONENT runtime FILES_MATCHING PATTERN "*.1.gz")
  message(STATUS "man pages: written by ${MESHTOPO_HELP2MAN} at build time")
endif()
