# imucal-dev: the message headers, find_package(imucal) -> imucal::lcmtypes and imucal-lcmtypes.pc. Both
# live under share/ (the headers are all there is, nothing arch-specific) and find their prefix from where
# they are installed, so the tree works wherever it is unpacked (DESTDIR, --prefix, a .deb).
include(CMakePackageConfigHelpers)
set(imucal_cmake_dir ${CMAKE_INSTALL_DATADIR}/cmake/imucal)

install(FILES ${IMUCAL_LCMTYPES_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/imucal COMPONENT dev)
install(TARGETS imucal_lcmtypes EXPORT imucalTargets COMPONENT dev)
install(EXPORT imucalTargets NAMESPACE imucal:: DESTINATION ${imucal_cmake_dir} COMPONENT dev)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/imucalConfig.cmake.in
  ${PROJECT_BINARY_DIR}/imucalConfig.cmake INSTALL_DESTINATION ${imucal_cmake_dir})
# 0.x: a minor release may change the messages (their fingerprints), so only the same minor matches.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/imucalConfigVersion.cmake COMPATIBILITY SameMinorVersion
  ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/imucalConfig.cmake ${PROJECT_BINARY_DIR}/imucalConfigVersion.cmake
  DESTINATION ${imucal_cmake_dir} COMPONENT dev)

configure_file(${CMAKE_CURRENT_LIST_DIR}/imucal-lcmtypes.pc.in ${PROJECT_BINARY_DIR}/imucal-lcmtypes.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/imucal-lcmtypes.pc DESTINATION ${CMAKE_INSTALL_DATADIR}/pkgconfig COMPONENT dev)
