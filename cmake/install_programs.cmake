# What `cmake --install` puts where, in three components that are also the Debian packages
# (cmake/packaging.cmake): imucal (the daemon and the hardware drivers, their configs, units and udev
# rule), tools (the imucal CLI, the simulator publisher, the trigger, lcm-spy with our types) and dev.
# Which program goes where: cmake/programs.cmake.
install(TARGETS ${IMUCAL_SERVICE_PROGRAMS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT imucal)
install(CODE "set(IMUCAL_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")
set(IMUCAL_BINARY_DIR \"${PROJECT_BINARY_DIR}\")
set(IMUCAL_INSTALL_BINDIR \"${CMAKE_INSTALL_BINDIR}\")
set(IMUCAL_SERVICE_UNIT_TEMPLATES \"${IMUCAL_SERVICE_UNIT_TEMPLATES}\")" COMPONENT imucal)
install(SCRIPT ${CMAKE_CURRENT_LIST_DIR}/install_system_files.cmake COMPONENT imucal)

install(TARGETS ${IMUCAL_TOOL_PROGRAMS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
# Debian's own /usr/bin/lcm-spy cannot start under Java 17 (see the script), hence a name of our own.
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/lcm-spy DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME imucal-lcm-spy
        COMPONENT tools)
# Debian's Java policy: the jar named with its version, and an unversioned link that users name.
set(jar imucal-lcmtypes-${PROJECT_VERSION}.jar)
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/packaging)
file(CREATE_LINK ${jar} ${PROJECT_BINARY_DIR}/packaging/imucal-lcmtypes.jar SYMBOLIC)
install(FILES ${IMUCAL_LCMTYPES_JAR} DESTINATION ${CMAKE_INSTALL_DATADIR}/java RENAME ${jar} COMPONENT tools)
install(FILES ${PROJECT_BINARY_DIR}/packaging/imucal-lcmtypes.jar DESTINATION ${CMAKE_INSTALL_DATADIR}/java
        COMPONENT tools)

include(${CMAKE_CURRENT_LIST_DIR}/install_dev.cmake)

include(${CMAKE_CURRENT_LIST_DIR}/install_docs.cmake)
