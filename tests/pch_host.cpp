// Compiled only to build the precompiled header that every test of an area reuses
// (tests/CMakeLists.txt, cmake/FoveaBuildSpeed.cmake). Intentionally empty.
