# Project-wide warning and sanitizer flags, applied to our own targets only.
add_library(fovea_options INTERFACE)
target_compile_options(fovea_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow=local
                       -Wnon-virtual-dtor -Wno-deprecated-enum-enum-conversion)
if(FOVEA_WERROR)
  target_compile_options(fovea_options INTERFACE -Werror)
endif()
if(FOVEA_SANITIZE)
  # UBSan without its null and alignment checks: they instrument every reference binding and
  # every load and store, and were half of the ASan tree's compile time (a model unity batch:
  # 78.5 s of CPU with address,undefined; 41.8 s without these two; 35.1 s with address alone;
  # GCC 12, -O1 -g1, 2026-12-06). What they would catch is caught here anyway: a null
  # dereference is a SEGV that ASan reports with its stack; a misaligned access is harmless on
  # x86-64, and Eigen's own unaligned-array and aligned_malloc asserts are live in this
  # NDEBUG-free tree. The rest of -fsanitize=undefined (signed overflow, shifts, integer division
  # by zero, array bounds, object size, enum and bool loads, vptr, pointer overflow, a missing
  # return, ...) stays on and stops the test.
  target_compile_options(fovea_options INTERFACE -fsanitize=address,undefined -fno-sanitize=null,alignment
                         -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(fovea_options INTERFACE -fsanitize=address,undefined)
  # One Eigen heap ABI in both trees: Eigen assumes glibc's malloc 16-byte aligned, but not
  # when __SANITIZE_ADDRESS__ is defined (Eigen/src/Core/util/Memory.h); it then over-allocates
  # and offsets every block, so a matrix allocated in a sanitized library and freed by an
  # unsanitized test executable (or the reverse) is a bad free. ASan's malloc is 16-byte aligned
  # on x86-64 (alignof(max_align_t), as the C standard asks of malloc), and Eigen's own check of
  # that (eigen_assert in aligned_malloc, live in this NDEBUG-free tree) stays on.
  target_compile_definitions(fovea_options INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)
  # A shared library's calls to its own inline and template functions bind to its own
  # (instrumented) copies, never to the copies an uninstrumented executable exports: the ASan
  # tree runs the default tree's test executables against its libraries (tests/CMakeLists.txt).
  target_link_options(fovea_options INTERFACE
                      $<$<STREQUAL:$<TARGET_PROPERTY:TYPE>,SHARED_LIBRARY>:-Wl,-Bsymbolic-functions>)
endif()
target_include_directories(fovea_options INTERFACE ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)

# fovea_glob_sources(<out-var> <dir>): every .cpp below <dir>. Each module globs its own
# folder so that adding a file never touches a shared CMakeLists (parallel work).
function(fovea_glob_sources out dir)
  file(GLOB_RECURSE _src CONFIGURE_DEPENDS "${dir}/*.cpp" "${dir}/*.h")
  set(${out} ${_src} PARENT_SCOPE)
endfunction()
