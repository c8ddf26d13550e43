# Every Debian package carries its copyright and changelog in /usr/share/doc/<package>/ (policy 12.5, 12.7):
# one copy per package, named after it. The changelog is gzip -9n as policy asks; a native version (no
# Debian revision), hence changelog.gz rather than changelog.Debian.gz.
# No project address exists yet: a placeholder maintainer address, also the packages' (cmake/packaging.cmake).
set(IMUCAL_MAINTAINER "imucal developers <imucal@example.org>")
string(TIMESTAMP changelog_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE ${PROJECT_BINARY_DIR}/packaging/changelog
"imucal (${PROJECT_VERSION}) unstable; urgency=medium

  * Built with CPack from the imucal source tree.

 -- ${IMUCAL_MAINTAINER}  ${changelog_date}
")
execute_process(COMMAND gzip -n -9 -c ${PROJECT_BINARY_DIR}/packaging/changelog
                OUTPUT_FILE ${PROJECT_BINARY_DIR}/packaging/changelog.gz COMMAND_ERROR_IS_FATAL ANY)
foreach(component_package imucal:imucal tools:imucal-tools dev:imucal-dev)
  string(REPLACE ":" ";" pair ${component_package})
  list(GET pair 0 component)
  list(GET pair 1 package)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright ${PROJECT_BINARY_DIR}/packaging/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package} COMPONENT ${component})
endforeach()
