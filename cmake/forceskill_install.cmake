# Installation and the CMake package of the firmware libraries a consumer links:
#   find_package(forceskill) -> forceskill::base (codes and types, header only),
#   forceskill::core (double), forceskill::core_f32 (float32), forceskill::fixed, forceskill::proto
# and forceskill.pc for pkg-config (core, fixed and proto). The same names exist as aliases
# when the tree is added with add_subdirectory. tests/consumer/ builds a program both ways.
include(CMakePackageConfigHelpers)

set(FS_EXPORTED fs_base fs_core fs_core_f32 fs_fixed fs_proto)
foreach(t ${FS_EXPORTED})
  string(REGEX REPLACE "^fs_" "" short ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${short})
  add_library(forceskill::${short} ALIAS ${t})
endforeach()

install(TARGETS ${FS_EXPORTED} EXPORT forceskillTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/forceskill)
file(GLOB FS_PUBLIC_HEADERS
     ${PROJECT_SOURCE_DIR}/firmware/base/*.h ${PROJECT_SOURCE_DIR}/firmware/core/*.h
     ${PROJECT_SOURCE_DIR}/firmware/fixed/*.h ${PROJECT_SOURCE_DIR}/firmware/proto/*.h
     ${PROJECT_SOURCE_DIR}/firmware/proto/generated/*.h)
install(FILES ${FS_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/forceskill)

set(FS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/forceskill)
install(EXPORT forceskillTargets NAMESPACE forceskill:: DESTINATION ${FS_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/forceskillConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/forceskillConfig.cmake
                              INSTALL_DESTINATION ${FS_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/forceskillConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/forceskillConfig.cmake
              ${PROJECT_BINARY_DIR}/forceskillConfigVersion.cmake
        DESTINATION ${FS_CMAKE_DIR})

configure_file(${PROJECT_SOURCE_DIR}/cmake/forceskill.pc.in ${PROJECT_BINARY_DIR}/forceskill.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/forceskill.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
