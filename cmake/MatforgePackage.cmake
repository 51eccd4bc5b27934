# `cmake --install` and the Debian package (scripts/package.sh runs CPack's DEB generator).
# Installs the matforge binary and its image module (presets and the OpenColorIO config are compiled in), the
# README, docs/ and the shipped presets as reference files.
include(GNUInstallDirs)
install(TARGETS matforge RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The image decoders and encoders, loaded at run time (lib/CMakeLists.txt, matforge_oiio).
install(TARGETS matforge_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/matforge)
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY presets/ DESTINATION ${CMAKE_INSTALL_DATADIR}/matforge/presets)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME matforge)
set(CPACK_PACKAGE_VENDOR "matforge")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "PBR material sets to engine-ready textures, CI checks and previews")
set(CPACK_PACKAGE_DESCRIPTION
    "matforge finds each map's role in downloaded PBR material sets (ambientCG, Poly Haven, \
Textures.com, Megascans, Substance exports), converts and packs them per engine preset with a \
manifest.json, validates them for CI (text, JSON, JUnit, SARIF) and renders physically based \
previews with Vulkan (a GPU, or Mesa's lavapipe on the CPU).")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "matforge developers <dev@matforge.local>")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # matforge_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)   # dpkg-shlibdeps: every library the binary links
# Loaded at run time with dlopen (lib/render: a clear error instead of a failed start when
# absent), so dpkg-shlibdeps cannot see them: the Vulkan loader, and Mesa's drivers for preview
# without a GPU (lavapipe).
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libvulkan1, mesa-vulkan-drivers")
# The Python module (MATFORGE_PYTHON, python/CMakeLists.txt) is built for Debian 12's python3;
# the command never needs it.
if(MATFORGE_PYTHON)
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3 (>= 3.11), python3 (<< 3.12)")
endif()
set(CPACK_STRIP_FILES ON)
include(CPack)
