# CPack's project config file for meshtopo (CPACK_PROJECT_CONFIG_FILE, set in
# cmake/MeshtopoPackage.cmake): read by every cpack run before it installs
# anything. It refuses to make the Debian packages of a build configured
# with -DMESHTOPO_BUILD_BENCH=OFF, whose meshtopo package would lack
# meshtopo-bench (and so `meshtopo bench`), and warns when the build has no
# man pages (help2man was not found).
if(CPACK_GENERATOR STREQUAL "DEB")
  if(NOT CPACK_MESHTOPO_BUILD_BENCH)
    message(FATAL_ERROR
      "meshtopo: this build was configured with -DMESHTOPO_BUILD_BENCH=OFF, so its meshtopo "
      "package would lack meshtopo-bench. Configure the build directory with "
      "-DMESHTOPO_BUILD_BENCH=ON, build it and package again.")
  endif()
  if(NOT CPACK_MESHTOPO_MAN_PAGES)
    message(WARNING
      "meshtopo: this build has no man pages (help2man was not found when CMake configured, "
      "or -DMESHTOPO_BUILD_MAN_PAGES=OFF): the meshtopo package will have none. "
      "Install help2man, configure again and build.")
  endif()
endif()
