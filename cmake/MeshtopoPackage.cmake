# Debian packages of meshtopo, made by CPack's DEB generator from the
# install components of cmake/MeshtopoInstall.cmake and the other install
# rules: `cmake --build BUILD --target package` (or `cpack -G DEB` in BUILD)
# writes into BUILD
#
#   meshtopo           meshtopo and meshtopod, the systemd unit, the LCM
#                      message definitions and their jar for lcm-spy, the docs
#   libmeshtopo-dev    headers, the libraries (static ones, or the link names
#                      of shared ones), the CMake package and pkg-config files
#   python3-meshtopo   the Python package with libmeshtopo-python.so
#   libmeshtopo<M.m>   the shared libraries, in a -DBUILD_SHARED_LIBS=ON build
#
# The packages install under /usr whatever prefix was configured (paths the
# programs use are found relative to them or chosen when installing).
# Depends: what dpkg-shlibdeps finds the programs and shared objects linked
# against (libc6, liblcm1, libhdf5-103-1, libxxhash0, zlib1g, ...), plus the
# packages listed here by hand: python3 and python3-numpy for the Python
# package, and for libmeshtopo-dev the -dev packages of what a static
# meshtopo leaves its consumers to link (LCM, HDF5, xxHash, zlib).
# Included once from the top-level CMakeLists.txt, after every install rule.

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME meshtopo)
set(CPACK_PACKAGE_VENDOR meshtopo)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "mesh topology service for robots over LCM")
set(MESHTOPO_PACKAGE_MAINTAINER "meshtopo maintainers <meshtopo@localhost>" CACHE STRING
    "Maintainer field of the Debian packages (cpack)")
set(CPACK_PACKAGE_CONTACT "${MESHTOPO_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
# Packages are built in the build tree, never from the sources.
set(CPACK_SOURCE_GENERATOR "")

set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)

set(meshtopo_deb_version "${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE}")
set(meshtopo_soversion "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")

# --- meshtopo: the programs -------------------------------------------------
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME meshtopo)
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION
    "mesh topology service for robots over LCM
 meshtopod builds half-edge meshes from face lists submitted over LCM, reports
 every defect, answers adjacency and manifold queries and archives every mesh
 to HDF5 (VTKHDF files ParaView opens). The meshtopo tool inspects mesh files
 (OFF, OBJ, PLY, STL), talks to the daemon, manages and replays the archive
 and starts lcm-spy with meshtopo's message types.")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS "liblcm-java, default-jre, hdf5-tools")

# --- libmeshtopo-dev: building against meshtopo ------------------------------
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libmeshtopo-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_COMPONENT_DEV_DESCRIPTION
    "meshtopo libraries: development files
 Headers, libraries, CMake package (find_package(meshtopo): meshtopo::core,
 meshtopo::io, meshtopo::client, meshtopo::archive) and pkg-config files
 (meshtopo-core, meshtopo-io, meshtopo-client, meshtopo-archive) of meshtopo's
 half-edge mesh library, its mesh file readers, its C client of meshtopod and
 its HDF5 archive.")
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libc6-dev, liblcm-dev, libhdf5-dev, libxxhash-dev, zlib1g-dev")
set(CPACK_DEBIAN_DEV_PACKAGE_SUGGESTS "pkg-config, cmake")

# --- python3-meshtopo --------------------------------------------------------
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-meshtopo)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_COMPONENT_PYTHON_DESCRIPTION
    "meshtopo for Python 3
 The meshtopo package: half-edge meshes, defect records and adjacency queries
 from numpy face lists, through meshtopo's C library (ctypes, nothing compiled
 at import time), and a client of the meshtopod LCM service.")
set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3, python3-numpy")

set(CPACK_COMPONENTS_ALL runtime dev python)

# --- libmeshtopo<M.m>: shared libraries --------------------------------------
if(BUILD_SHARED_LIBS)
  list(APPEND CPACK_COMPONENTS_ALL libs)
  set(CPACK_DEBIAN_LIBS_PACKAGE_NAME libmeshtopo${meshtopo_soversion})
  set(CPACK_DEBIAN_LIBS_PACKAGE_SECTION libs)
  set(CPACK_COMPONENT_LIBS_DESCRIPTION
      "meshtopo shared libraries
 The half-edge mesh library, mesh file readers, C client of meshtopod, HDF5
 archive and JSON reports of meshtopo.")
  # The programs and the Python package link them: exactly this version.
  set(meshtopo_libs_depends "libmeshtopo${meshtopo_soversion} (= ${meshtopo_deb_version})")
  set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "${meshtopo_libs_depends}")
  string(APPEND CPACK_DEBIAN_DEV_PACKAGE_DEPENDS ", ${meshtopo_libs_depends}")
  string(APPEND CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS ", ${meshtopo_libs_depends}")
  # dpkg-shlibdeps finds meshtopo's own libraries in the package being made.
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
      ${PROJECT_BINARY_DIR}/lib/core ${PROJECT_BINARY_DIR}/lib/io
      ${PROJECT_BINARY_DIR}/lib/json ${PROJECT_BINARY_DIR}/lib/client
      ${PROJECT_BINARY_DIR}/lib/archive)
endif()

include(CPack)
