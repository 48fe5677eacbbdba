# cmake -DBUILD=<build-wasm> -DWEB=<web> -P assemble.cmake: the npm package
# (BUILD/npm) and the static page (BUILD/page) from the linked module and web/'s files.
set(npm ${BUILD}/npm)
set(page ${BUILD}/page)
file(REMOVE_RECURSE ${npm} ${page})
file(MAKE_DIRECTORY ${npm} ${page})
file(COPY ${WEB}/js/ DESTINATION ${npm})
configure_file(${BUILD}/polyvol.js ${npm}/polyvol.cjs COPYONLY)
configure_file(${BUILD}/polyvol.wasm ${npm}/polyvol.wasm COPYONLY)
# The browsers' entry: the same factory as an ES module.
file(READ ${BUILD}/polyvol.js glue)
file(WRITE ${npm}/polyvol.web.mjs "${glue}\nexport default createPolyvolModule;\n")
file(COPY ${WEB}/page/ DESTINATION ${page})
file(COPY ${npm}/ DESTINATION ${page}/polyvol)
# What the page loads from npm (web/node_modules, `npm ci --prefix web`),
# and the package's own dependency for its tests in place.
if(NOT EXISTS ${WEB}/node_modules/fflate/esm/browser.js)
  message(FATAL_ERROR "web/node_modules is missing: npm ci --prefix web (web/build.sh does)")
endif()
file(MAKE_DIRECTORY ${page}/vendor)
configure_file(${WEB}/node_modules/fflate/esm/browser.js ${page}/vendor/fflate.mjs COPYONLY)
# parse-xml 4 (the last for Node 20) ships its browser build as CommonJS: given a module object and exported.
file(READ ${WEB}/node_modules/@rgrove/parse-xml/dist/browser.js parse_xml)
file(WRITE ${page}/vendor/parse-xml.mjs "const module = { exports: {} };\n${parse_xml}\nconst exported = module.exports.parseXml;\nexport { exported as parseXml };\n")
configure_file(${WEB}/node_modules/three/build/three.module.js ${page}/vendor/three.module.js COPYONLY)
file(CREATE_LINK ${WEB}/node_modules ${npm}/node_modules SYMBOLIC)
