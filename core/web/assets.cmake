# The web UI (web/ in the source tree), gzipped with Debian's gzip at build
# time and compiled into rotord_web (the web layer of rotord_core) as
# constant byte arrays (web_assets.cpp), for both the Linux daemon and the
# Pico firmware. Included from core/CMakeLists.txt after rotord_web is defined.
find_program(ROTORD_GZIP gzip REQUIRED)
set(ROTORD_WEB_DIR ${CMAKE_CURRENT_LIST_DIR}/../../web)  # the repo's web/, also when included from ports/pico_w
file(GLOB ROTORD_WEB_FILES CONFIGURE_DEPENDS
  ${ROTORD_WEB_DIR}/*.html ${ROTORD_WEB_DIR}/*.css ${ROTORD_WEB_DIR}/*.js ${ROTORD_WEB_DIR}/*.svg)
include(${CMAKE_CURRENT_LIST_DIR}/world_map.cmake)  # world.js, the map's coastlines
# settings_help.js: the settings table's help column, served gzipped rather
# than compiled into the core (web/tools/settings_help.mjs says why).
set(ROTORD_SETTINGS_TABLE ${CMAKE_CURRENT_LIST_DIR}/../settings/settings_table.def)
# The per-axis rows it expands (settings_table.def includes them).
set(ROTORD_AXIS_SETTINGS ${CMAKE_CURRENT_LIST_DIR}/../settings/axis_settings.def)
set(ROTORD_SETTINGS_HELP_JS ${ROTORD_WEB_GENERATED_DIR}/settings_help.js)
add_custom_command(
  OUTPUT ${ROTORD_SETTINGS_HELP_JS}
  COMMAND ${ROTORD_NODE_FOR_MAP} ${ROTORD_WEB_DIR}/tools/settings_help.mjs ${ROTORD_SETTINGS_TABLE}
          ${ROTORD_SETTINGS_HELP_JS}
  DEPENDS ${ROTORD_SETTINGS_TABLE} ${ROTORD_AXIS_SETTINGS} ${ROTORD_WEB_DIR}/tools/settings_help.mjs
  COMMENT "Writing the settings' help for the web UI"
  VERBATIM)
set(ROTORD_WEB_ASSETS_CPP ${CMAKE_CURRENT_BINARY_DIR}/web_assets.cpp)
add_custom_command(
  OUTPUT ${ROTORD_WEB_ASSETS_CPP}
  COMMAND ${CMAKE_COMMAND} -DGZIP=${ROTORD_GZIP} -DWEB_DIR=${ROTORD_WEB_DIR}
          -DEXTRA_DIR=${ROTORD_WEB_GENERATED_DIR}
          -DOUT=${ROTORD_WEB_ASSETS_CPP} -P ${CMAKE_CURRENT_LIST_DIR}/embed_assets.cmake
  DEPENDS ${ROTORD_WEB_FILES} ${ROTORD_WORLD_JS} ${ROTORD_SETTINGS_HELP_JS}
          ${CMAKE_CURRENT_LIST_DIR}/embed_assets.cmake
  COMMENT "Embedding the web UI (gzip)"
  VERBATIM)
target_sources(rotord_web PRIVATE ${ROTORD_WEB_ASSETS_CPP})
