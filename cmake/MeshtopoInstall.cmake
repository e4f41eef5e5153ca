# Install rules: the libraries (static by default, shared with
# -DBUILD_SHARED_LIBS=ON), their headers under include/meshtopo/ (and the
# message types' under include/lcmtypes/), a CMake package
# (find_package(meshtopo) gives meshtopo::core, meshtopo::io,
# meshtopo::client, with meshtopo::msgs beneath it, and meshtopo::archive,
# with meshtopo::ident beneath both) and pkg-config files. Included once from the top-level CMakeLists.txt after
# every library target exists; the installed tree is relocatable.
#
# Every rule names its install component, which cmake/MeshtopoPackage.cmake
# turns into a Debian package: runtime (the programs, their data and
# documentation: meshtopo), libs (the shared libraries of a shared build),
# dev (headers, static libraries and link names, CMake and pkg-config
# files: libmeshtopo-dev) and python (lib/python: python3-meshtopo); license
# (the LICENSE file) is for `cmake --install` only.
include(CMakePackageConfigHelpers)

set(MESHTOPO_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/meshtopo)

# --- Libraries and headers ------------------------------------------------
# Exported as meshtopo::core, meshtopo::io, meshtopo::ident, meshtopo::msgs,
# meshtopo::client and meshtopo::archive, the same names as the aliases the
# build tree uses, so consumer code reads the same either way. meshtopo::msgs
# (the LCM message types, always static) comes with meshtopo::client, whose
# API uses them; meshtopo::ident (the mesh-id rule and the content hash,
# always static) with meshtopo::archive and meshtopo::msgs, which share it.
set_target_properties(meshtopo_core PROPERTIES EXPORT_NAME core)
set_target_properties(meshtopo_ident PROPERTIES EXPORT_NAME ident)
set_target_properties(meshtopo_io PROPERTIES EXPORT_NAME io)
set_target_properties(meshtopo_msgs PROPERTIES EXPORT_NAME msgs)
set_target_properties(meshtopo_client PROPERTIES EXPORT_NAME client)
set_target_properties(meshtopo_archive PROPERTIES EXPORT_NAME archive)
foreach(lib meshtopo_core meshtopo_io meshtopo_client meshtopo_archive)
  set_target_properties(${lib} PROPERTIES VERSION ${PROJECT_VERSION}
                        SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
endforeach()

install(TARGETS meshtopo_core meshtopo_io meshtopo_ident meshtopo_msgs meshtopo_client
                meshtopo_archive
  EXPORT meshtopoTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT libs NAMELINK_COMPONENT dev
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT libs)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/core/include/meshtopo
                  ${PROJECT_SOURCE_DIR}/lib/io/include/meshtopo
                  ${PROJECT_SOURCE_DIR}/lib/ident/include/meshtopo
                  ${PROJECT_SOURCE_DIR}/lib/client/include/meshtopo
                  ${PROJECT_SOURCE_DIR}/lib/archive/include/meshtopo
                  ${PROJECT_SOURCE_DIR}/msgs/include/meshtopo
                  ${MESHTOPO_MSGS_GENERATED_INCLUDE}/meshtopo
                  ${MESHTOPO_MSGS_GENERATED_INCLUDE}/lcmtypes
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev
  FILES_MATCHING PATTERN "*.h")

# The LCM message definitions, for lcm-gen in other languages, and the
# READMEs: the project's, and msgs/README.md (the channels and the message
# types) as msgs.md beside it, as the daemon's is meshtopod.md.
file(GLOB MESHTOPO_LCM_DEFINITIONS ${PROJECT_SOURCE_DIR}/msgs/*.lcm)
install(FILES ${MESHTOPO_LCM_DEFINITIONS} DESTINATION ${CMAKE_INSTALL_DATADIR}/meshtopo/lcm
        COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}
        COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/msgs/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}
        RENAME msgs.md COMPONENT runtime)
# The licence, for `cmake --install`. Its own component, which no Debian
# package holds: each package has it in its copyright file instead
# (cmake/MeshtopoPackage.cmake), where Debian wants it.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR}
        COMPONENT license)

# --- CMake package ----------------------------------------------------------
# A static install carries its private dependencies in the exported link
# interface ($<LINK_ONLY:ZLIB::ZLIB>, Threads::Threads, hdf5::hdf5, m), so the
# config file must find them; a shared install hides them and needs nothing.
if(BUILD_SHARED_LIBS)
  set(MESHTOPO_CONFIG_STATIC OFF)
else()
  set(MESHTOPO_CONFIG_STATIC ON)
endif()

install(EXPORT meshtopoTargets
  NAMESPACE meshtopo::
  FILE meshtopoTargets.cmake
  DESTINATION ${MESHTOPO_INSTALL_CMAKEDIR} COMPONENT dev)

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/meshtopoConfig.cmake.in
  ${PROJECT_BINARY_DIR}/meshtopoConfig.cmake
  INSTALL_DESTINATION ${MESHTOPO_INSTALL_CMAKEDIR})

# 0.x releases may break the API between minor versions.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/meshtopoConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)

install(FILES ${PROJECT_BINARY_DIR}/meshtopoConfig.cmake
              ${PROJECT_BINARY_DIR}/meshtopoConfigVersion.cmake
  DESTINATION ${MESHTOPO_INSTALL_CMAKEDIR} COMPONENT dev)

# --- pkg-config -------------------------------------------------------------
# One .pc per library, named like the CMake targets (meshtopo-core,
# meshtopo-io, meshtopo-client, meshtopo-archive), so a program that only
# builds meshes does not drag in zlib or HDF5, plus meshtopo.pc for "core and
# io". Paths are relative to the .pc
# file's own directory (${pcfiledir}), so `cmake --install --prefix` anywhere
# works. For a static install the private dependencies go into Libs/Requires:
# there is no shared library to carry them, and plain `pkg-config --libs`
# must give a command line that links (no --static needed).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(MESHTOPO_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH MESHTOPO_PC_UP "/meshtopo-prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig"
       "/meshtopo-prefix")
  set(MESHTOPO_PC_PREFIX "\${pcfiledir}/${MESHTOPO_PC_UP}")
endif()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(MESHTOPO_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(MESHTOPO_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()

# meshtopo-client names LCM and xxHash as plain -llcm -lxxhash (Debian's
# lcm.pc requires glib-2.0, which liblcm-dev does not install); -llcm is
# public in both kinds, as the client's options take an lcm_t.
# meshtopo-archive names no LCM at all: the archive shares the mesh-id rule
# and the content hash with the messages through libmeshtopo-ident (static
# only, like libmeshtopo-msgs, so listed where a static link needs it).
if(BUILD_SHARED_LIBS)
  set(MESHTOPO_PC_CORE_LIBS "")
  set(MESHTOPO_PC_CORE_LIBS_PRIVATE "-lm -pthread")
  set(MESHTOPO_PC_IO_REQUIRES "meshtopo-core = ${PROJECT_VERSION}")
  set(MESHTOPO_PC_IO_REQUIRES_PRIVATE "zlib")
  set(MESHTOPO_PC_CLIENT_LIBS " -llcm")
  set(MESHTOPO_PC_CLIENT_LIBS_PRIVATE "-lmeshtopo-msgs -lmeshtopo-ident -lxxhash -pthread")
  set(MESHTOPO_PC_ARCHIVE_REQUIRES_PRIVATE "hdf5")
  set(MESHTOPO_PC_ARCHIVE_LIBS "")
  set(MESHTOPO_PC_ARCHIVE_LIBS_PRIVATE "-lmeshtopo-ident -lxxhash")
else()
  set(MESHTOPO_PC_CORE_LIBS " -lm -pthread")
  set(MESHTOPO_PC_CORE_LIBS_PRIVATE "")
  set(MESHTOPO_PC_IO_REQUIRES "meshtopo-core = ${PROJECT_VERSION}, zlib")
  set(MESHTOPO_PC_IO_REQUIRES_PRIVATE "")
  set(MESHTOPO_PC_CLIENT_LIBS " -lmeshtopo-msgs -lmeshtopo-ident -llcm -lxxhash -pthread")
  set(MESHTOPO_PC_CLIENT_LIBS_PRIVATE "")
  set(MESHTOPO_PC_ARCHIVE_REQUIRES_PRIVATE "")
  set(MESHTOPO_PC_ARCHIVE_LIBS " -lmeshtopo-ident -lxxhash")
  set(MESHTOPO_PC_ARCHIVE_LIBS_PRIVATE "")
endif()
# HDF5 through its own hdf5.pc (Debian's libhdf5-dev): public for a static
# install, whose consumers link it.
if(BUILD_SHARED_LIBS)
  set(MESHTOPO_PC_ARCHIVE_REQUIRES "meshtopo-core = ${PROJECT_VERSION}")
else()
  set(MESHTOPO_PC_ARCHIVE_REQUIRES "meshtopo-core = ${PROJECT_VERSION}, hdf5")
endif()

foreach(pc meshtopo-core meshtopo-io meshtopo-client meshtopo-archive meshtopo)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/${pc}.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc
                 @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
endforeach()

# --- Manual pages -------------------------------------------------------------
# meshtopo(1), meshtopo-COMMAND(1), meshtopod(1), meshtopo-bench(1), written by
# help2man at build time (component runtime).
include(${CMAKE_CURRENT_LIST_DIR}/MeshtopoManPages.cmake)
