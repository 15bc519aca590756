# The web view (services/bridge/web): three.js and the page's sources bundled by esbuild at build time into
# ${TWINSLAM_WEB_DIR} (app.js, index.html), which the bridge serves on its WebSocket port. No CDN: the page works
# offline. Needs node and the packages `npm ci` put in services/bridge/web/node_modules (scripts/setup.sh does it);
# without them the bridge answers http://HOST:PORT/ with "web view not built".
set(TWINSLAM_WEB_DIR ${CMAKE_BINARY_DIR}/web CACHE INTERNAL "the built web view")
set(web_src ${CMAKE_CURRENT_SOURCE_DIR}/web)
find_program(TWINSLAM_WEB_NODE node)
if(TWINSLAM_WEB_NODE AND EXISTS ${web_src}/build.mjs AND EXISTS ${web_src}/node_modules/esbuild
   AND EXISTS ${web_src}/node_modules/three)
  file(GLOB web_sources CONFIGURE_DEPENDS ${web_src}/src/*.js ${web_src}/*.html ${web_src}/*.css)
  add_custom_command(
    OUTPUT ${TWINSLAM_WEB_DIR}/app.js ${TWINSLAM_WEB_DIR}/index.html ${TWINSLAM_WEB_DIR}/style.css
    COMMAND ${TWINSLAM_WEB_NODE} ${web_src}/build.mjs ${TWINSLAM_WEB_DIR}
    DEPENDS ${web_sources} ${web_src}/build.mjs ${web_src}/package-lock.json
    WORKING_DIRECTORY ${web_src}
    COMMENT "web view: bundling three.js and the page with esbuild")
  add_custom_target(twinslam_web_view ALL DEPENDS ${TWINSLAM_WEB_DIR}/app.js ${TWINSLAM_WEB_DIR}/index.html
                    ${TWINSLAM_WEB_DIR}/style.css)
else()
  message(STATUS "twinslam: web view not built (needs node and `npm ci` in services/bridge/web: scripts/setup.sh)")
endif()
