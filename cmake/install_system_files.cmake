# Run by `cmake --install` (and CPack) for the imucal component: the files whose place and content depend on
# the prefix chosen at install time, not at configure time. Under /usr (a Debian package) configs go to
# /etc and units and udev rules to /lib, as Debian 12's systemd and udev expect; under any other prefix
# everything stays below it. file(INSTALL) adds DESTDIR and records the files in install_manifest.txt.
# In: IMUCAL_SOURCE_DIR, IMUCAL_BINARY_DIR, IMUCAL_INSTALL_BINDIR (relative to the prefix),
# IMUCAL_SERVICE_UNIT_TEMPLATES (cmake/programs.cmake).
set(prefix "${CMAKE_INSTALL_PREFIX}")
if(prefix STREQUAL "/usr")
  set(etc_dir /etc)
  set(lib_dir /lib)
else()
  set(etc_dir "${prefix}/etc")
  set(lib_dir "${prefix}/lib")
endif()
set(IMUCAL_BINDIR "${prefix}/${IMUCAL_INSTALL_BINDIR}")
set(IMUCAL_CONFDIR "${etc_dir}/imucal")

# imucald.yaml names paper-calibrate.yaml relative to its own directory, so the two travel together.
file(INSTALL ${IMUCAL_SOURCE_DIR}/configs/imucald.yaml ${IMUCAL_SOURCE_DIR}/configs/paper-calibrate.yaml
     ${IMUCAL_SOURCE_DIR}/drivers/configs/icm42688.yaml ${IMUCAL_SOURCE_DIR}/drivers/configs/lis3mdl.yaml
     ${IMUCAL_SOURCE_DIR}/drivers/configs/j1939.yaml
     DESTINATION "${IMUCAL_CONFDIR}" FILE_PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)

# Configured per destination: two installs at once (ctest -j) must not write the same files.
string(MD5 install_tag "$ENV{DESTDIR}|${prefix}")
set(units_dir "${IMUCAL_BINARY_DIR}/systemd/${install_tag}")
set(units)
foreach(template ${IMUCAL_SERVICE_UNIT_TEMPLATES})
  get_filename_component(name "${template}" NAME_WLE)
  configure_file("${template}" "${units_dir}/${name}" @ONLY)
  list(APPEND units "${units_dir}/${name}")
endforeach()
file(INSTALL ${units} DESTINATION "${lib_dir}/systemd/system"
     FILE_PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
file(INSTALL ${IMUCAL_SOURCE_DIR}/packaging/60-imucal.rules DESTINATION "${lib_dir}/udev/rules.d"
     FILE_PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
