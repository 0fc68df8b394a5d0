# Installing and packaging syncap (docs/guide/deploy.md).
#
# Three install components become three Debian packages (CPack's DEB generator,
# scripts/package.sh):
#   trigger -> syncap-trigger: syncap-trigger, syncap-gpiosim, the unit, the udev rule for GPIO
#   edge    -> syncap-edge:    syncap-edge, syncap-segment-eval, syncap-mask, the unit syncap-edge@
#   host    -> syncap-host:    syncap-host, syncap (only in a build with SYNCAP_BUILD_HOST)
# each with an example config in /etc/syncap (a conffile), its docs, copyright and changelog,
# and the maintainer scripts of packaging/deb/<component>. Depends come from dpkg-shlibdeps at
# packaging time (SyncapCPackProject.cmake.in); in an arm64 cross build from the sysroot's
# shlibs files (scripts/arm64-sysroot.sh), the same information dpkg holds on a board.
# Packages install to /usr whatever the build's CMAKE_INSTALL_PREFIX (CPACK_PACKAGING_INSTALL_PREFIX).

# Configuration lives in /etc/syncap whatever the prefix: the units read it there.
set(SYNCAP_CONFIG_DIR /etc/syncap)
set(_syncap_packaging_dir ${CMAKE_CURRENT_LIST_DIR}/../packaging)

# syncap_install_unit(<template.service.in> <component>): the unit with @SYNCAP_BINDIR@ (where
# its program is installed) and @SYNCAP_DOCDIR@ (its package's docs) filled in at install time,
# from the prefix installed to (cmake --install --prefix, or CPack's /usr), then installed to
# lib/systemd/system under it. So one build makes /usr/local units for `cmake --install` and /usr
# units for the packages.
function(syncap_install_unit template component)
  get_filename_component(name ${template} NAME)
  string(REGEX REPLACE "\\.in$" "" name "${name}")
  set(source ${CMAKE_CURRENT_SOURCE_DIR}/${template})
  set(unit ${CMAKE_BINARY_DIR}/systemd/${name})
  install(CODE "
    set(SYNCAP_BINDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}\")
    set(SYNCAP_DOCDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATAROOTDIR}/doc/syncap-${component}\")
    configure_file(\"${source}\" \"${unit}\" @ONLY)"
    COMPONENT ${component})
  install(FILES ${unit} DESTINATION lib/systemd/system COMPONENT ${component})
endfunction()

# The changelog as Debian wants it in every package: gzip -9n (no name, no time stamp).
set(_syncap_changelog_gz ${CMAKE_BINARY_DIR}/packaging/changelog.gz)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/packaging)
execute_process(COMMAND gzip -9nc ${_syncap_packaging_dir}/changelog
                OUTPUT_FILE ${_syncap_changelog_gz} RESULT_VARIABLE _syncap_gzip_status)
if(NOT _syncap_gzip_status EQUAL 0)
  message(FATAL_ERROR "gzip of packaging/changelog failed (${_syncap_gzip_status})")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_syncap_packaging_dir}/changelog)

# syncap_install_docs(<component> files...): the files, copyright and changelog.gz into
# share/doc/syncap-<component>.
function(syncap_install_docs component)
  install(FILES ${ARGN} ${_syncap_packaging_dir}/copyright ${_syncap_changelog_gz}
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/syncap-${component} COMPONENT ${component})
endfunction()

# Called at the end of the top-level CMakeLists.txt, when every target exists.
function(syncap_configure_cpack)
  set(components trigger edge)
  if(SYNCAP_BUILD_HOST)
    list(APPEND components host)
  endif()
  set(CPACK_GENERATOR DEB)
  set(CPACK_DEB_COMPONENT_INSTALL ON)
  set(CPACK_COMPONENTS_ALL ${components})
  set(CPACK_PACKAGE_NAME syncap)
  set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
  set(CPACK_PACKAGE_CONTACT "syncap developers <syncap@users.noreply.github.com>")
  set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
  set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
  set(CPACK_STRIP_FILES ON)
  set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
  set(CPACK_DEBIAN_PACKAGE_SECTION science)
  set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
  if(CMAKE_CROSSCOMPILING AND CMAKE_SYSTEM_PROCESSOR STREQUAL "aarch64")
    set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
  endif()

  set(CPACK_DEBIAN_TRIGGER_PACKAGE_NAME syncap-trigger)
  set(CPACK_COMPONENT_TRIGGER_DESCRIPTION
      "syncap trigger module: exposes all cameras at the same instant\n\
Drives GPIO lines through libgpiod (0.01-1000 Hz, pulse width, phases,\n\
start and stop input lines) and announces every trigger with its frame\n\
number over LCM. A systemd unit (syncap-trigger, real-time, unprivileged)\n\
and an example configuration in /etc/syncap; nothing is enabled until a\n\
configuration is written.")
  set(CPACK_DEBIAN_EDGE_PACKAGE_NAME syncap-edge)
  set(CPACK_COMPONENT_EDGE_DESCRIPTION
      "syncap edge process: one per camera, on the board it hangs on\n\
Acquires frames (Aravis for GigE and USB3 Vision, V4L2 for UVC, replay\n\
from files), finds bright markers with sub-pixel centroids and the\n\
person's silhouette (medi-picture masking), and streams compact LCM\n\
messages to the host. A systemd unit per camera (syncap-edge@N) and an\n\
example configuration in /etc/syncap.")
  set(CPACK_DEBIAN_HOST_PACKAGE_NAME syncap-host)
  set(CPACK_COMPONENT_HOST_DESCRIPTION
      "syncap host: aggregation, calibration and live reconstruction\n\
Groups the edges' messages by frame number, calibrates the camera network\n\
from a moving wand (bundle adjustment with statistics), and reconstructs\n\
markers, the visual hull, the body and the surface live; syncap is the\n\
command-line front end (record, calibrate, control the edges).")

  foreach(component trigger edge)
    string(TOUPPER ${component} upper)
    set(scripts "")
    foreach(script postinst prerm postrm conffiles)
      if(EXISTS ${_syncap_packaging_dir}/deb/${component}/${script})
        list(APPEND scripts ${_syncap_packaging_dir}/deb/${component}/${script})
      endif()
    endforeach()
    set(CPACK_DEBIAN_${upper}_PACKAGE_CONTROL_EXTRA ${scripts})
  endforeach()

  # Depends: computed when cpack runs (SyncapCPackProject.cmake.in), from the built programs.
  set(SYNCAP_PACKAGE_PROGRAMS_TRIGGER syncap-trigger syncap-gpiosim)
  set(SYNCAP_PACKAGE_PROGRAMS_EDGE syncap-edge syncap-segment-eval syncap-mask)
  set(SYNCAP_PACKAGE_PROGRAMS_HOST syncap-host syncap)
  set(SYNCAP_PACKAGE_BIN_DIR ${CMAKE_RUNTIME_OUTPUT_DIRECTORY})
  set(SYNCAP_PACKAGE_SYSROOT "")
  if(CMAKE_CROSSCOMPILING)
    set(SYNCAP_PACKAGE_SYSROOT "${CMAKE_SYSROOT}")
  endif()
  set(SYNCAP_PACKAGE_COMPONENTS ${components})
  configure_file(${CMAKE_CURRENT_FUNCTION_LIST_DIR}/SyncapCPackProject.cmake.in
                 ${CMAKE_BINARY_DIR}/SyncapCPackProject.cmake @ONLY)
  set(CPACK_PROJECT_CONFIG_FILE ${CMAKE_BINARY_DIR}/SyncapCPackProject.cmake)
  include(CPack)
endfunction()
