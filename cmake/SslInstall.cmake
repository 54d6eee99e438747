# What `cmake --install` puts where, and the Debian package (CPack DEB) that `./ssl package` builds. The
# layout is the one of a match PC, under the install prefix (default "/", the package's):
#   opt/ssl-stack/bin/             the services and sslctl
#   etc/ssl-stack/                 config/, qos/, sites/ and ssl-stack.env (the units' environment)
#   lib/systemd/system/            the units and targets
#   opt/ssl-stack/share/doc/       README.md
# `cmake --install build --prefix P` puts the same tree under P, with units naming P's paths. The binaries
# find the configs relative to themselves (libs/common/deploy_files.h): no source tree needed.
if(CMAKE_INSTALL_PREFIX_INITIALIZED_TO_DEFAULT)
  set(CMAKE_INSTALL_PREFIX "/" CACHE PATH "install root: / for a match PC" FORCE)
endif()

set(SSL_SERVICE_USER "ssl-stack" CACHE STRING "the system user the units run the services as")
set(SSL_FASTDDS_TOOL /usr/bin/fastdds CACHE FILEPATH "Fast DDS's CLI (fastdds-tools): the discovery server")

set(SSL_INSTALL_BINDIR opt/ssl-stack/bin)
set(SSL_INSTALL_CONFDIR etc/ssl-stack)
set(SSL_INSTALL_UNITDIR lib/systemd/system)
set(SSL_INSTALL_DOCDIR opt/ssl-stack/share/doc)

install(TARGETS simulator vision_gateway referee_gateway world_model planner robot_link console sslctl
        RUNTIME DESTINATION ${SSL_INSTALL_BINDIR})
install(PROGRAMS ${CMAKE_SOURCE_DIR}/deploy/systemd/ssl-restart-backoff DESTINATION ${SSL_INSTALL_BINDIR})
# DDS Security files on a match PC (what ./ssl certs runs): sudo ssl-dds-certs --dir /etc/ssl-stack/certs
install(PROGRAMS ${CMAKE_SOURCE_DIR}/deploy/dds-certs.sh DESTINATION ${SSL_INSTALL_BINDIR} RENAME ssl-dds-certs)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/deploy/config ${CMAKE_SOURCE_DIR}/deploy/qos ${CMAKE_SOURCE_DIR}/deploy/sites
        DESTINATION ${SSL_INSTALL_CONFDIR})
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${SSL_INSTALL_DOCDIR})

# The units name absolute paths of the install they belong to: written at install time, straight into the
# install (DESTDIR included, as CPack stages it), so that an install under any prefix gets units for that
# prefix and installs of one build into several prefixes at once do not share a file.
set(SSL_UNIT_TEMPLATES
    ssl-discovery.service ssl-simulator.service ssl-vision-gateway.service ssl-referee-gateway.service
    ssl-robot-link@.service ssl-world-model@.service ssl-planner@.service ssl-console.service ssl-field.target
    ssl-team@.target ssl-coach.target ssl-latency.slice ssl-bulk.slice)
install(CODE "
  string(REGEX REPLACE \"/+$\" \"\" root \"\${CMAKE_INSTALL_PREFIX}\")
  set(SSL_BIN_DIR \"\${root}/${SSL_INSTALL_BINDIR}\")
  set(SSL_CONF_DIR \"\${root}/${SSL_INSTALL_CONFDIR}\")
  set(SSL_DOC_DIR \"\${root}/${SSL_INSTALL_DOCDIR}\")
  set(SSL_SERVICE_USER \"${SSL_SERVICE_USER}\")
  set(FASTDDS \"${SSL_FASTDDS_TOOL}\")
  set(staged \"\$ENV{DESTDIR}\${root}\")
  foreach(unit ${SSL_UNIT_TEMPLATES})
    message(STATUS \"Installing: \${staged}/${SSL_INSTALL_UNITDIR}/\${unit}\")
    configure_file(\"${CMAKE_SOURCE_DIR}/deploy/systemd/\${unit}.in\" \"\${staged}/${SSL_INSTALL_UNITDIR}/\${unit}\" @ONLY)
  endforeach()
  message(STATUS \"Installing: \${staged}/${SSL_INSTALL_CONFDIR}/ssl-stack.env\")
  configure_file(\"${CMAKE_SOURCE_DIR}/deploy/systemd/ssl-stack.env.in\" \"\${staged}/${SSL_INSTALL_CONFDIR}/ssl-stack.env\" @ONLY)
")

# The Debian package.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ssl-stack)
set(CPACK_PACKAGE_VENDOR ssl-stack)
set(CPACK_PACKAGE_VERSION 0.1.0)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "RoboCup SSL team stack: vision and referee gateways, world model, planner, robot link, simulator")
set(CPACK_PACKAGE_CONTACT "ssl-stack maintainers <ssl-stack@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # the shared libraries (Fast DDS, Bullet, ...) found by dpkg-shlibdeps
set(CPACK_DEBIAN_PACKAGE_DEPENDS "fastdds-tools, adduser, systemd")
# Every file under /etc/ssl-stack is a conffile: an upgrade keeps what the team edited.
file(GLOB_RECURSE _ssl_conffiles RELATIVE ${CMAKE_SOURCE_DIR}/deploy
     ${CMAKE_SOURCE_DIR}/deploy/config/* ${CMAKE_SOURCE_DIR}/deploy/qos/* ${CMAKE_SOURCE_DIR}/deploy/sites/*)
list(SORT _ssl_conffiles)
set(_ssl_conffile_list "/${SSL_INSTALL_CONFDIR}/ssl-stack.env\n")
foreach(file ${_ssl_conffiles})
  string(APPEND _ssl_conffile_list "/${SSL_INSTALL_CONFDIR}/${file}\n")
endforeach()
file(WRITE ${CMAKE_BINARY_DIR}/debian/conffiles "${_ssl_conffile_list}")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    "${CMAKE_BINARY_DIR}/debian/conffiles;${CMAKE_SOURCE_DIR}/deploy/debian/postinst;${CMAKE_SOURCE_DIR}/deploy/debian/postrm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
