# Project-wide warning and sanitizer flags, applied to our own targets only.
add_library(fovea_options INTERFACE)
target_compile_options(fovea_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow=local
                       -Wnon-virtual-dtor -Wno-deprecated-enum-enum-conversion)
if(FOVEA_WERROR)
  target_compile_options(fovea_options INTERFACE -Werror)
endif()
if(FOVEA_SANITIZE)
  target_compile_options(fovea_options INTERFACE -fsanitize=address,undefined
                         -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(fovea_options INTERFACE -fsanitize=address,undefined)
endif()
target_include_directories(fovea_options INTERFACE ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)

# fovea_glob_sources(<out-var> <dir>): every .cpp below <dir>. Each module globs its own
# folder so that adding a file never touches a shared CMakeLists (parallel work).
function(fovea_glob_sources out dir)
  file(GLOB_RECURSE _src CONFIGURE_DEPENDS "${dir}/*.cpp" "${dir}/*.h")
  set(${out} ${_src} PARENT_SCOPE)
endfunction()
