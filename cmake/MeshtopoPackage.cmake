# Debian packages of meshtopo, made by CPack's DEB generator from the
# install components of cmake/MeshtopoInstall.cmake and the other install
# rules: `cmake --build BUILD --target package` (or `cpack -G DEB` in BUILD)
# writes into BUILD
#
#   meshtopo           meshtopo, meshtopod and meshtopo-bench with their man
#                      pages, the systemd unit with its sysusers.d and
#                      tmpfiles.d snippets, the LCM message definitions and
#                      their jar for lcm-spy, the docs
#   libmeshtopo-dev    headers, the libraries (static ones, or the link names
#                      of shared ones), the CMake package and pkg-config files
#   python3-meshtopo   the Python package with libmeshtopo-python.so
#   libmeshtopo<M.m>   the shared libraries, in a -DBUILD_SHARED_LIBS=ON build
#
# The packages install under /usr whatever prefix was configured (paths the
# programs use are found relative to them or chosen when installing), and are
# meant to pass lintian without errors or warnings
# (tests/install/package_check.sh). The Debian files they need besides the
# build's own (copyright, changelog, maintainer scripts, sysusers.d and
# tmpfiles.d snippets, ldconfig trigger, lintian overrides) are in packaging/,
# whose README.md says what each is for.
# Depends: what dpkg-shlibdeps finds the programs and shared objects linked
# against (libc6, liblcm1, libhdf5-103-1, libxxhash0, zlib1g, ...), plus the
# packages listed here by hand: python3 and python3-numpy for the Python
# package, and for libmeshtopo-dev the -dev packages of what a static
# meshtopo leaves its consumers to link (LCM, HDF5, xxHash, zlib).
# Included once from the top-level CMakeLists.txt, after every install rule.

set(MESHTOPO_PACKAGING_DIR ${PROJECT_SOURCE_DIR}/packaging)
set(meshtopo_maintainer_default "meshtopo maintainers <maintainers@meshtopo.org>")
set(MESHTOPO_PACKAGE_MAINTAINER "${meshtopo_maintainer_default}" CACHE STRING
    "Maintainer of the Debian packages: their Maintainer field and changelog entry")
# Build trees configured before this default existed hold the old one, whose
# @localhost lintian rejects (bogus-mail-host).
if(MESHTOPO_PACKAGE_MAINTAINER STREQUAL "meshtopo maintainers <meshtopo@localhost>")
  set_property(CACHE MESHTOPO_PACKAGE_MAINTAINER PROPERTY VALUE "${meshtopo_maintainer_default}")
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME meshtopo)
set(CPACK_PACKAGE_VENDOR meshtopo)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# No CPACK_PACKAGE_DESCRIPTION_SUMMARY: CPack would put it first in every
# package's description, and each package has its own synopsis (below).
set(CPACK_PACKAGE_CONTACT "${MESHTOPO_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${MESHTOPO_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
# Packages are built in the build tree, never from the sources.
set(CPACK_SOURCE_GENERATOR "")

set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_SOURCE meshtopo)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Maintainer scripts 0755, other control files 0644, as dpkg-deb wants them.
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

set(meshtopo_deb_version "${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE}")
set(meshtopo_soversion "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")
set(MESHTOPO_LIBS_PACKAGE libmeshtopo${meshtopo_soversion})

# --- meshtopo: the programs -------------------------------------------------
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME meshtopo)
# The description of every package: a synopsis of its own, then a paragraph that
# says what meshtopo is, then what the package holds (CPack indents it).
set(meshtopo_about
    "meshtopo builds half-edge meshes from the face lists that perception nodes
produce, reports every defect real scans have (holes, non-manifold edges and
vertices, flipped, degenerate and out-of-range faces) with the ids of the
elements involved, and answers adjacency queries (one-rings, face neighbours,
boundary loops, components, genus).
")
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION
    "mesh topology service for robots: daemon and command-line tool
${meshtopo_about}
This package holds meshtopod, the LCM service that builds submitted meshes,
answers batched queries and archives every mesh version to HDF5 (VTKHDF files
that ParaView opens), with its systemd unit; the meshtopo tool, which inspects
OFF, OBJ, PLY and STL files, talks to the daemon, manages and replays the
archive, draws meshes with their defects marked and starts lcm-spy with
meshtopo's message types; meshtopo-bench, the benchmarks; and the LCM message
definitions.")
# meshtopo render and archive export to .vtu run VTK from Debian's python3
# (python3-vtk9, or the same modules from python3-paraview, which conflicts
# with it) in a private Xvfb protected by xauth; meshtopo spy runs lcm-spy
# (liblcm-java, a JRE with a window toolkit); ParaView opens the archive;
# meshtopod's LZ4 archives need HDF5's Blosc filter; h5dump reads archives.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "python3-vtk9 | python3-paraview, xvfb, xauth")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS
    "paraview, liblcm-java, default-jre, hdf5-filter-plugin-blosc-serial, hdf5-tools")
# Its own postinst and postrm: CPack then writes none (it would call ldconfig
# for the archive-commands module, which is no library of the loader's).
# (CPack takes control files by their names: copies named so, mode kept.)
foreach(script postinst prerm postrm)
  configure_file(${MESHTOPO_PACKAGING_DIR}/meshtopo.${script}
                 ${PROJECT_BINARY_DIR}/packaging/meshtopo/${script} COPYONLY)
  list(APPEND CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA
       ${PROJECT_BINARY_DIR}/packaging/meshtopo/${script})
endforeach()

# --- libmeshtopo-dev: building against meshtopo ------------------------------
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libmeshtopo-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_DESCRIPTION
    "half-edge mesh topology library for robots - development files
${meshtopo_about}
This package holds the headers, the libraries, the CMake package
(find_package(meshtopo): meshtopo::core, meshtopo::io, meshtopo::client,
meshtopo::archive) and the pkg-config files (meshtopo-core, meshtopo-io,
meshtopo-client, meshtopo-archive) of the half-edge mesh library, its mesh file
readers, its C client of meshtopod and its HDF5 archive.")
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libc6-dev, liblcm-dev, libhdf5-dev, libxxhash-dev, zlib1g-dev")
set(CPACK_DEBIAN_DEV_PACKAGE_SUGGESTS "pkg-config, cmake")

# --- python3-meshtopo --------------------------------------------------------
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-meshtopo)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_DEBIAN_PYTHON_DESCRIPTION
    "half-edge mesh topology for robots - Python 3 module
${meshtopo_about}
This package holds the Python 3 module meshtopo: half-edge meshes, defect
records and adjacency queries from numpy arrays, through meshtopo's C library
(ctypes, nothing compiled at import time), and a client of the meshtopod LCM
service.")
set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3, python3-numpy")
# Byte-compiled on install (py3compile) and cleaned on removal (py3clean), as
# dh_python3 does: nothing of the package stays behind after a purge.
foreach(script postinst prerm)
  configure_file(${MESHTOPO_PACKAGING_DIR}/python3-meshtopo.${script}
                 ${PROJECT_BINARY_DIR}/packaging/python3-meshtopo/${script} COPYONLY)
  list(APPEND CPACK_DEBIAN_PYTHON_PACKAGE_CONTROL_EXTRA
       ${PROJECT_BINARY_DIR}/packaging/python3-meshtopo/${script})
endforeach()

set(CPACK_COMPONENTS_ALL runtime dev python)

# --- libmeshtopo<M.m>: shared libraries --------------------------------------
if(BUILD_SHARED_LIBS)
  list(APPEND CPACK_COMPONENTS_ALL libs)
  set(CPACK_DEBIAN_LIBS_PACKAGE_NAME ${MESHTOPO_LIBS_PACKAGE})
  set(CPACK_DEBIAN_LIBS_PACKAGE_SECTION libs)
  set(CPACK_DEBIAN_LIBS_DESCRIPTION
      "half-edge mesh topology library for robots - shared libraries
${meshtopo_about}
This package holds the shared libraries of meshtopo: the half-edge mesh
library, the mesh file readers, the C client of meshtopod and the HDF5
archive.")
  # The programs and the Python package link them: exactly this version.
  set(meshtopo_libs_depends "${MESHTOPO_LIBS_PACKAGE} (= ${meshtopo_deb_version})")
  set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "${meshtopo_libs_depends}")
  string(APPEND CPACK_DEBIAN_DEV_PACKAGE_DEPENDS ", ${meshtopo_libs_depends}")
  string(APPEND CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS ", ${meshtopo_libs_depends}")
  # dpkg-shlibdeps finds meshtopo's own libraries in the package being made.
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
      ${PROJECT_BINARY_DIR}/lib/core ${PROJECT_BINARY_DIR}/lib/io
      ${PROJECT_BINARY_DIR}/lib/client
      ${PROJECT_BINARY_DIR}/lib/archive)
  # A shlibs control file, so that programs built against the package depend
  # on it: "libmeshtopo-core 0.1 libmeshtopo0.1 (>= 0.1.0-1)" for each library.
  # (CPack looks at every package; the shared objects without a versioned
  # SONAME, the CLI's module and the Python binding, it skips with a warning.)
  set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
  set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY ">=")
  # dpkg runs ldconfig through the trigger. CPack also writes a postinst and
  # a postrm calling ldconfig into every package with a library in /usr/lib,
  # which Debian no longer wants (lintian: maintscript-calls-ldconfig) and
  # cannot be told not to: packaging/deb-post-build.cmake takes them out of
  # this package again, once made (only these two exact scripts), and adds a
  # symbols file (dpkg-gensymbols) beside the shlibs file.
  configure_file(${MESHTOPO_PACKAGING_DIR}/libmeshtopo.triggers
                 ${PROJECT_BINARY_DIR}/packaging/${MESHTOPO_LIBS_PACKAGE}/triggers COPYONLY)
  set(CPACK_DEBIAN_LIBS_PACKAGE_CONTROL_EXTRA
      ${PROJECT_BINARY_DIR}/packaging/${MESHTOPO_LIBS_PACKAGE}/triggers)
  set(CPACK_MESHTOPO_LIBS_PACKAGE ${MESHTOPO_LIBS_PACKAGE})
  set(CPACK_MESHTOPO_DEV_PACKAGE ${CPACK_DEBIAN_DEV_PACKAGE_NAME})
  set(CPACK_POST_BUILD_SCRIPTS ${MESHTOPO_PACKAGING_DIR}/deb-post-build.cmake)
endif()

# --- Files every package has: copyright, changelog, lintian overrides --------
# /usr/share/doc/<package>/copyright (DEP-5, packaging/copyright) and
# changelog.Debian.gz, an entry for this version written from
# packaging/changelog.in now, so it always names PROJECT_VERSION (date:
# SOURCE_DATE_EPOCH when set, else the time of configuring), compressed with
# gzip -9n (no name or time stamp in it). Only in the packages
# (EXCLUDE_FROM_ALL): `cmake --install` installs LICENSE instead.
file(READ ${MESHTOPO_PACKAGING_DIR}/changelog.in meshtopo_changelog)
string(REGEX REPLACE "^(#[^\n]*\n)+" "" meshtopo_changelog "${meshtopo_changelog}")
set(MESHTOPO_DEB_VERSION ${meshtopo_deb_version})
string(TIMESTAMP MESHTOPO_CHANGELOG_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)
string(CONFIGURE "${meshtopo_changelog}" meshtopo_changelog @ONLY)
set(meshtopo_changelog_file ${PROJECT_BINARY_DIR}/packaging/changelog.Debian)
file(WRITE ${meshtopo_changelog_file} "${meshtopo_changelog}")
find_program(MESHTOPO_GZIP gzip)
mark_as_advanced(MESHTOPO_GZIP)
if(MESHTOPO_GZIP)
  execute_process(COMMAND ${MESHTOPO_GZIP} -9n -c ${meshtopo_changelog_file}
                  OUTPUT_FILE ${meshtopo_changelog_file}.gz RESULT_VARIABLE gzip_result)
endif()
if(NOT MESHTOPO_GZIP OR NOT gzip_result EQUAL 0)
  message(WARNING "gzip failed or was not found: the Debian packages have no changelog")
  file(REMOVE ${meshtopo_changelog_file}.gz)
endif()

# /usr/share/lintian/overrides/<package>: lintian's overrides, each with its
# reason, from packaging/lintian-overrides.in (all packages) and
# packaging/libmeshtopo.lintian-overrides.in (the shared-library package).
foreach(component IN LISTS CPACK_COMPONENTS_ALL)
  string(TOUPPER ${component} component_upper)
  set(package ${CPACK_DEBIAN_${component_upper}_PACKAGE_NAME})
  set(MESHTOPO_OVERRIDES_PACKAGE ${package})
  file(READ ${MESHTOPO_PACKAGING_DIR}/lintian-overrides.in overrides)
  if(component STREQUAL "libs")
    file(READ ${MESHTOPO_PACKAGING_DIR}/libmeshtopo.lintian-overrides.in libs_overrides)
    string(APPEND overrides "\n${libs_overrides}")
  endif()
  file(CONFIGURE OUTPUT ${PROJECT_BINARY_DIR}/packaging/lintian/${package}
       CONTENT "${overrides}" @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/packaging/lintian/${package}
          DESTINATION ${CMAKE_INSTALL_DATADIR}/lintian/overrides COMPONENT ${component}
          EXCLUDE_FROM_ALL)
  install(FILES ${MESHTOPO_PACKAGING_DIR}/copyright
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package} COMPONENT ${component}
          EXCLUDE_FROM_ALL)
  if(EXISTS ${meshtopo_changelog_file}.gz)
    install(FILES ${meshtopo_changelog_file}.gz
            DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package} COMPONENT ${component}
            EXCLUDE_FROM_ALL)
  endif()
endforeach()

# --- meshtopod's system user and archive directory ----------------------------
# The packaged unit (daemon/CMakeLists.txt) runs meshtopod as the system user
# meshtopod with /var/lib/meshtopo: created by these snippets, which the
# postinst applies (packaging/meshtopo.postinst).
install(FILES ${MESHTOPO_PACKAGING_DIR}/meshtopod.sysusers DESTINATION lib/sysusers.d
        RENAME meshtopod.conf COMPONENT runtime EXCLUDE_FROM_ALL)
install(FILES ${MESHTOPO_PACKAGING_DIR}/meshtopod.tmpfiles DESTINATION lib/tmpfiles.d
        RENAME meshtopod.conf COMPONENT runtime EXCLUDE_FROM_ALL)

# --- What cpack checks before it packages --------------------------------------
# The meshtopo package holds meshtopo-bench (README.md's package table, and
# `meshtopo bench` runs it), so a build configured with
# -DMESHTOPO_BUILD_BENCH=OFF must not make packages: packaging/cpack-checks.cmake
# (CPack's project config file, read by every cpack run, also `cpack -G DEB`
# by hand) stops cpack with a FATAL_ERROR saying so. Refusing is chosen over
# building the benchmarks anyway for the package: turning them off is how the
# sanitizer and fuzz builds stay small, and a package must not silently
# differ from what the README lists. Missing man pages (no help2man) only
# warn: tests/install/package_check.sh fails on them.
if(NOT MESHTOPO_BUILD_BENCH)
  message(STATUS "Debian packages: cpack will refuse them (MESHTOPO_BUILD_BENCH is OFF)")
endif()
set(CPACK_MESHTOPO_BUILD_BENCH ${MESHTOPO_BUILD_BENCH})
set(CPACK_MESHTOPO_MAN_PAGES ${MESHTOPO_HAVE_MAN_PAGES})
set(CPACK_PROJECT_CONFIG_FILE ${MESHTOPO_PACKAGING_DIR}/cpack-checks.cmake)

include(CPack)
