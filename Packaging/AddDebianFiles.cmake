# Run by CPack (CPACK_PRE_BUILD_SCRIPTS) after it installed the project into its staging folder:
# adds /usr/bin/paraview.conf and the plugin's PointCloudBilateral.plugins.xml, which only the
# Debian package installs (see CMakeLists.txt beside this file).
set(staging "${CPACK_TEMPORARY_INSTALL_DIRECTORY}${CPACK_PACKAGING_INSTALL_PREFIX}")
if (NOT EXISTS "${staging}/${CPACK_PCB_PLUGIN_DIR}/PointCloudBilateral.so")
  message(FATAL_ERROR "No plugin in the package's staging folder: ${staging}/${CPACK_PCB_PLUGIN_DIR}")
endif ()
file(COPY "${CPACK_PCB_DEBIAN_FILES}/" DESTINATION "${staging}")
