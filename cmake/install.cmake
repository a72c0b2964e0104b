# `cmake --install build --prefix P`: the public headers, the static libraries, the CLI and a
# CMake package, so that a consumer's find_package(floorgrid) and
# target_link_libraries(app floorgrid::floorgrid) work. The dependencies' headers are not
# copied: floorgridConfig.cmake finds the same Debian packages (find_dependency).
include(CMakePackageConfigHelpers)
set(FLOORGRID_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/floorgrid")

install(TARGETS floorgrid_core floorgrid_io floorgrid_api floorgrid_opencv
        EXPORT floorgridTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(TARGETS floorgrid RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
# Every library header (server/ is the CLI's, not the library's).
install(DIRECTORY "${CMAKE_SOURCE_DIR}/floorgrid/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/floorgrid"
        FILES_MATCHING PATTERN "*.hpp" PATTERN "server" EXCLUDE)
install(EXPORT floorgridTargets NAMESPACE floorgrid:: DESTINATION "${FLOORGRID_CMAKE_DIR}")
configure_package_config_file("${CMAKE_SOURCE_DIR}/cmake/floorgridConfig.cmake.in"
                              "${CMAKE_BINARY_DIR}/floorgridConfig.cmake"
                              INSTALL_DESTINATION "${FLOORGRID_CMAKE_DIR}")
write_basic_package_version_file("${CMAKE_BINARY_DIR}/floorgridConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_BINARY_DIR}/floorgridConfig.cmake"
              "${CMAKE_BINARY_DIR}/floorgridConfigVersion.cmake"
        DESTINATION "${FLOORGRID_CMAKE_DIR}")
