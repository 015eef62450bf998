# `cmake --install`: the library as a CMake package (find_package(hmblur CONFIG), target
# hmblur::hmblur), a pkg-config file, the public headers (include/hmblur/, with the umbrella
# <hmblur/hmblur.h>), and the hmblur command. The layers are static libraries, so the
# package config finds what they link.
include(CMakePackageConfigHelpers)

# The one target an engine links: the public headers alone (include/hmblur/) and what they need,
# every layer of the library linked but the layers' own headers out of reach.
add_library(hmblur_library INTERFACE)
target_include_directories(hmblur_library INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(hmblur_library INTERFACE $<LINK_ONLY:hmb> Vulkan::Vulkan glm::glm nlohmann_json::nlohmann_json)
set_target_properties(hmblur_library PROPERTIES EXPORT_NAME hmblur)
add_library(hmblur::hmblur ALIAS hmblur_library)

set(HMB_LAYERS hmb hmb_image hmb_scenes hmb_bvh hmb_kernels)
install(TARGETS ${HMB_LAYERS} hmblur_library EXPORT hmblurTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
if(HMB_BUILD_TOOLS)
  install(TARGETS hmblur RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT hmblurTargets NAMESPACE hmblur:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/hmblur)

# The public API is include/hmblur/, installed as it is and alone. Its headers include only each
# other ("hmblur/scene.h"): one that reaches into the library's own stops the configure.
file(GLOB HMB_PUBLIC_HEADERS RELATIVE ${PROJECT_SOURCE_DIR}/include CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/include/hmblur/*.h)
foreach(header IN LISTS HMB_PUBLIC_HEADERS)
  file(STRINGS ${PROJECT_SOURCE_DIR}/include/${header} lines REGEX "^#include \"[^\"]+\"")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
    if(NOT included IN_LIST HMB_PUBLIC_HEADERS)
      message(FATAL_ERROR "public header include/${header} includes \"${included}\", which is not in include/hmblur/")
    endif()
  endforeach()
endforeach()
install(DIRECTORY include/hmblur DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

configure_package_config_file(cmake/hmblurConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/hmblurConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/hmblur)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/hmblurConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/hmblurConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/hmblurConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/hmblur)

# The .pc file finds its prefix from where it lies (pkg-config's ${pcfiledir}), so an install
# under any --prefix describes itself.
file(RELATIVE_PATH HMB_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(cmake/hmblur.pc.in ${CMAKE_CURRENT_BINARY_DIR}/hmblur.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/hmblur.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
