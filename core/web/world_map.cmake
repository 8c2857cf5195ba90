# The map page's coastlines and borders (issue 26): world-atlas' Natural
# Earth TopoJSON (npm, pinned in web/map/package-lock.json, installed by
# scripts/install-deps.sh) converted at build time by web/map/build_world.mjs
# into ${ROTORD_WEB_GENERATED_DIR}/world.js, which embed_assets.cmake embeds
# beside web/. Nothing is fetched at run time. Included from assets.cmake.
set(ROTORD_WORLD_TOPOJSON ${ROTORD_WEB_DIR}/map/node_modules/world-atlas/countries-110m.json)
if(NOT EXISTS ${ROTORD_WORLD_TOPOJSON})
  message(FATAL_ERROR "the map's data is missing (${ROTORD_WORLD_TOPOJSON}): "
                      "run scripts/install-deps.sh (npm ci in web/map)")
endif()
find_program(ROTORD_NODE_FOR_MAP node REQUIRED)
set(ROTORD_WEB_GENERATED_DIR ${CMAKE_CURRENT_BINARY_DIR}/web_generated)
set(ROTORD_WORLD_JS ${ROTORD_WEB_GENERATED_DIR}/world.js)
file(MAKE_DIRECTORY ${ROTORD_WEB_GENERATED_DIR})
add_custom_command(
  OUTPUT ${ROTORD_WORLD_JS}
  COMMAND ${ROTORD_NODE_FOR_MAP} ${ROTORD_WEB_DIR}/map/build_world.mjs ${ROTORD_WORLD_TOPOJSON}
          ${ROTORD_WORLD_JS}
  DEPENDS ${ROTORD_WORLD_TOPOJSON} ${ROTORD_WEB_DIR}/map/build_world.mjs
  COMMENT "Converting the map's coastlines (world-atlas) for the web UI"
  VERBATIM)
