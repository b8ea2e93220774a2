# `cmake --install <build> [--prefix P]` puts the framework in a prefix:
#   P/include/regolith/<module>/...   the headers, included as "core/mpi/Comm.hpp" as in-tree;
#   P/lib/libregolith_<module>.a      the modules, imported as regolith::<module>;
#   P/lib/libregolith_{petsc,hdf5,vtk}.so  the shared modules (core/module/SharedModule.hpp);
#   P/lib/cmake/Regolith/             the package: find_package(Regolith) in a program's own
#                                     CMakeLists.txt finds the modules with their dependencies;
#   P/bin/regolith, P/share/regolith/scenes/  the driver and the scenes.
# examples/ is such a program; tests/install builds it against a fresh prefix.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(REGOLITH_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Regolith)

# regolith_install_module(<name>): the library regolith_<name> as regolith::<name>, with the
# headers of the directory <name>/ (modules that live inside another's directory, as io/render,
# come with that one's headers).
function(regolith_install_module name)
  set_target_properties(regolith_${name} PROPERTIES EXPORT_NAME ${name})
  install(TARGETS regolith_${name} EXPORT RegolithTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
  if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/${name})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${name}/
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/regolith/${name} COMPONENT development
            FILES_MATCHING PATTERN "*.hpp")
  endif()
endfunction()

# After every module: the export set, the package files and what a user runs.
function(regolith_install_package)
  install(EXPORT RegolithTargets NAMESPACE regolith::
          DESTINATION ${REGOLITH_INSTALL_CMAKEDIR} COMPONENT development)
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/RegolithConfig.cmake.in
    ${PROJECT_BINARY_DIR}/RegolithConfig.cmake INSTALL_DESTINATION ${REGOLITH_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/RegolithConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/RegolithConfig.cmake
                ${PROJECT_BINARY_DIR}/RegolithConfigVersion.cmake
          DESTINATION ${REGOLITH_INSTALL_CMAKEDIR} COMPONENT development)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/regolith/scenes
          COMPONENT runtime)
endfunction()
