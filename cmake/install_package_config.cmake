# trs_install_package_config(NAME COMPATIBILITY [PATH_VARS VAR...]): what find_package(NAME)
# reads, installed into LIBDIR/cmake/NAME: NAMEConfig.cmake made from cmake/NAMEConfig.cmake.in
# (the PATH_VARS given to configure_package_config_file), and its version file.
include(CMakePackageConfigHelpers)
function(trs_install_package_config name compatibility)
  set(dir ${CMAKE_INSTALL_LIBDIR}/cmake/${name})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/${name}Config.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/${name}Config.cmake
    INSTALL_DESTINATION ${dir} ${ARGN})
  write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/${name}ConfigVersion.cmake
    COMPATIBILITY ${compatibility})
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/${name}Config.cmake ${CMAKE_CURRENT_BINARY_DIR}/${name}ConfigVersion.cmake
    DESTINATION ${dir})
endfunction()
