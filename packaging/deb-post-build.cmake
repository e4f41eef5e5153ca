# CPack post-build script of meshtopo's shared-library package
# (CPACK_POST_BUILD_SCRIPTS, set in cmake/MeshtopoPackage.cmake for
# -DBUILD_SHARED_LIBS=ON builds). CPack's DEB generator writes a postinst and
# a postrm that call ldconfig into every package holding a library in
# /usr/lib, with no way to turn that off but shipping other scripts. The
# package activates dpkg's ldconfig trigger instead (packaging/
# libmeshtopo.triggers), as Debian wants (lintian: maintscript-calls-ldconfig),
# so this script unpacks it with dpkg-deb, removes those two scripts (only
# when they are exactly CPack's), adds a symbols control file (dpkg-gensymbols:
# the symbols each library exports, which CPack cannot write) beside CPack's
# shlibs, and builds it again with dpkg-deb.
set(package "${CPACK_MESHTOPO_LIBS_PACKAGE}")
if(NOT package)
  return()
endif()
find_program(MESHTOPO_DPKG_DEB dpkg-deb REQUIRED)
find_program(MESHTOPO_DPKG_GENSYMBOLS dpkg-gensymbols)

# CPack's two scripts (cmCPackDebGenerator.cxx), byte for byte.
set(cpack_postinst "#!/bin/sh\n\nset -e\n\nif [ \"$1\" = \"configure\" ]; then\n\tldconfig\nfi\n")
set(cpack_postrm "#!/bin/sh\n\nset -e\n\nif [ \"$1\" = \"remove\" ]; then\n\tldconfig\nfi\n")

foreach(deb IN LISTS CPACK_PACKAGE_FILES)
  get_filename_component(deb_name "${deb}" NAME)
  if(NOT deb_name MATCHES "^${package}_.*\\.deb$")
    continue()
  endif()
  set(tree "${CPACK_TOPLEVEL_DIRECTORY}/${package}-rebuild")
  file(REMOVE_RECURSE "${tree}")
  execute_process(COMMAND ${MESHTOPO_DPKG_DEB} --raw-extract "${deb}" "${tree}"
                  RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "dpkg-deb --raw-extract ${deb} failed")
  endif()
  set(changed FALSE)
  foreach(script postinst postrm)
    set(path "${tree}/DEBIAN/${script}")
    if(EXISTS "${path}")
      file(READ "${path}" text)
      if(NOT text STREQUAL "${cpack_${script}}")
        message(FATAL_ERROR "${deb_name}: its ${script} is not CPack's ldconfig call; "
                            "packaging/deb-post-build.cmake leaves it alone and stops")
      endif()
      file(REMOVE "${path}")
      set(changed TRUE)
    endif()
  endforeach()
  if(MESHTOPO_DPKG_GENSYMBOLS AND NOT EXISTS "${tree}/DEBIAN/symbols")
    # Each symbol is first in this upstream version (no Debian revision),
    # and programs built against it build-depend on the -dev package.
    file(STRINGS "${tree}/DEBIAN/control" version_line REGEX "^Version: ")
    string(REGEX REPLACE "^Version: ([^-]+)(-.*)?$" "\\1" version "${version_line}")
    execute_process(COMMAND ${MESHTOPO_DPKG_GENSYMBOLS} -q -c0 -p${package} -P${tree} -v${version}
                            -O${tree}/DEBIAN/symbols
                    WORKING_DIRECTORY "${CPACK_TOPLEVEL_DIRECTORY}" RESULT_VARIABLE result)
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "dpkg-gensymbols failed for ${deb_name}")
    endif()
    file(READ "${tree}/DEBIAN/symbols" symbols)
    string(REGEX REPLACE "(^|\n)([^ *#\n][^\n]*)\n"
           "\\1\\2\n* Build-Depends-Package: ${CPACK_MESHTOPO_DEV_PACKAGE}\n" symbols "${symbols}")
    file(WRITE "${tree}/DEBIAN/symbols" "${symbols}")
    file(CHMOD "${tree}/DEBIAN/symbols" PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
    set(changed TRUE)
  elseif(NOT MESHTOPO_DPKG_GENSYMBOLS)
    message(WARNING "dpkg-gensymbols not found (Debian: dpkg-dev): ${deb_name} has no symbols file")
  endif()
  if(changed)
    execute_process(COMMAND ${MESHTOPO_DPKG_DEB} --root-owner-group -Zgzip --build "${tree}" "${deb}"
                    RESULT_VARIABLE result)
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "dpkg-deb --build ${deb} failed")
    endif()
    message(STATUS "${deb_name}: CPack's ldconfig postinst and postrm removed "
                   "(the package activates the ldconfig trigger), symbols file added")
  endif()
  file(REMOVE_RECURSE "${tree}")
endforeach()
