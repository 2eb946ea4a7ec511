# `cmake --install`: the library (headers, one static library per module,
# the hba::hba target), the hba tool, and a package config so that another
# project's `find_package(hba)` + `target_link_libraries(app hba::hba)`
# works. CPack makes a Debian package of the same files.
include(CMakePackageConfigHelpers)

get_property(module_targets GLOBAL PROPERTY HBA_MODULE_TARGETS)
set_target_properties(hba_stb PROPERTIES EXPORT_NAME stb)
install(TARGETS ${module_targets} hba hba_stb
        EXPORT hbaTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/hba DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/generated/hba/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hba)
install(TARGETS hba_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/README.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/hba)
install(EXPORT hbaTargets NAMESPACE hba:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hbaConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/hbaConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hbaConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hbaConfig.cmake ${PROJECT_BINARY_DIR}/hbaConfigVersion.cmake
        DESTINATION ${config_dir})

# cpack -G DEB (in the build folder): hba_<version>_<arch>.deb.
set(CPACK_PACKAGE_NAME hba)
set(CPACK_PACKAGE_VENDOR "The hba authors")
set(CPACK_PACKAGE_CONTACT "The hba authors <hba@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Hierarchical LiDAR bundle adjustment: a drifting LiDAR sequence into a consistent map")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The tool's shared libraries (Ceres, TBB, yaml-cpp, ...) from dpkg-shlibdeps;
# building against the library needs the -dev packages its config finds.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libeigen3-dev, libceres-dev, libtbb-dev, libspdlog-dev, libfmt-dev, libyaml-cpp-dev, nlohmann-json3-dev, libnanoflann-dev, liblzf-dev, liblz4-dev, libzstd-dev, libbz2-dev, libsqlite3-dev, libstb-dev, libpng-dev")
set(CPACK_GENERATOR DEB)
include(CPack)
