# Build speed on a cold two-core machine (issue 25; docs/platform.md, "Timings"):
#  - precompiled headers per target for the heavy, stable headers (the standard library,
#    nlohmann/json, Eigen, OpenCV core, CLI11, Qt, VTK). A model unit reads ~140 000
#    preprocessed lines, a test ~235 000; parsing is ~40 % of a unit's time at -O2 -g;
#  - unity builds (FOVEA_UNITY) for the libraries and fovea-cli: one compilation per batch
#    instantiates and optimises the shared json/Eigen templates once.
# Each can be switched off (-DFOVEA_PCH=OFF, -DFOVEA_UNITY=OFF; the linker: cmake/FoveaLinker.cmake), e.g. to
# check that every file includes what it uses (a PCH forces its headers into every unit; the
# lint's clang-tidy runs without it, so model/ is checked for that on every change).
option(FOVEA_PCH "Precompiled headers for the heavy third-party headers" ON)
option(FOVEA_UNITY "Unity (jumbo) builds of the libraries and fovea-cli" ON)
set(FOVEA_UNITY_BATCH 8 CACHE STRING "Sources per unity batch")
set(FOVEA_PCH_STD <algorithm> <array> <atomic> <chrono> <cmath> <cstdint> <cstdio> <cstring>
    <functional> <map> <memory> <mutex> <optional> <set> <sstream> <stdexcept> <string>
    <string_view> <thread> <unordered_map> <utility> <variant> <vector>)
set(FOVEA_PCH_MODEL ${FOVEA_PCH_STD} <Eigen/Dense> <nlohmann/json.hpp> <opencv2/core.hpp>)
set(FOVEA_PCH_CLI ${FOVEA_PCH_MODEL} <CLI/CLI.hpp>)
set(FOVEA_PCH_QT <QObject> <QString> <QStringList> <QVariant> <QWidget> <QLabel>
    <QPushButton> <QVBoxLayout> <QHBoxLayout> <QFormLayout> <QComboBox> <QSpinBox>
    <QDoubleSpinBox> <QCheckBox> <QTimer> <QImage> <QPainter>)
set(FOVEA_PCH_VTK <vtkSmartPointer.h> <vtkNew.h> <vtkActor.h> <vtkRenderer.h>
    <vtkPolyData.h> <vtkPolyDataMapper.h> <vtkProperty.h> <vtkPoints.h> <vtkCellArray.h>)

# GLM and Eigen never in one file (architecture): viz's PCH has no Eigen.
set(FOVEA_PCH_VIZ ${FOVEA_PCH_STD} ${FOVEA_PCH_QT} ${FOVEA_PCH_VTK})
set(FOVEA_PCH_WIDGETS ${FOVEA_PCH_STD} <nlohmann/json.hpp> ${FOVEA_PCH_QT})

# fovea_speed_up(<target> <header-list-variable>): the target's PCH and unity build.
function(fovea_speed_up target headers)
  if(FOVEA_PCH)
    target_precompile_headers(${target} PRIVATE ${${headers}})
  endif()
  if(FOVEA_UNITY)
    fovea_unity_batches(${target})
  endif()
endfunction()

# fovea_unity_batches(<target>): compiles the target's .cpp files in batches of
# FOVEA_UNITY_BATCH, each batch one generated file that includes its sources by their path
# relative to the project root. Not CMake's UNITY_BUILD: its batch files include every source
# by absolute path, so a batch compiled in one clone never matches the ccache entry of the same
# batch in another (the preprocessed text differs), and CI clones afresh. A source with
# SKIP_UNITY_BUILD_INCLUSION (own compile flags) is compiled alone, as with UNITY_BUILD.
function(fovea_unity_batches target)
  get_target_property(_sources ${target} SOURCES)
  get_target_property(_dir ${target} SOURCE_DIR)
  set(_includes "")
  foreach(_src IN LISTS _sources)
    if(NOT IS_ABSOLUTE "${_src}")
      set(_src "${_dir}/${_src}")
    endif()
    get_source_file_property(_skip "${_src}" SKIP_UNITY_BUILD_INCLUSION)
    if(NOT _src MATCHES "\\.cpp$" OR _skip)
      continue()
    endif()
    file(RELATIVE_PATH _rel "${PROJECT_SOURCE_DIR}" "${_src}")
    list(APPEND _includes "#include \"${_rel}\"\n")
    set_source_files_properties("${_src}" PROPERTIES HEADER_FILE_ONLY ON)
  endforeach()
  list(LENGTH _includes _n)
  set(_index 0)
  set(_outputs "")
  foreach(_first RANGE 0 ${_n} ${FOVEA_UNITY_BATCH})
    if(_first EQUAL _n)
      break()
    endif()
    list(SUBLIST _includes ${_first} ${FOVEA_UNITY_BATCH} _batch)
    string(JOIN "" _batch ${_batch})
    set(_out "${CMAKE_CURRENT_BINARY_DIR}/unity/${target}_${_index}.cpp")
    file(CONFIGURE OUTPUT "${_out}" CONTENT "// Generated (cmake/FoveaBuildSpeed.cmake)\n${_batch}" @ONLY)
    list(APPEND _outputs "${_out}")
    math(EXPR _index "${_index} + 1")
  endforeach()
  target_sources(${target} PRIVATE ${_outputs})
endfunction()

# fovea_vtk_autoinit(<target>...): vtk_module_autoinit (VTK's object-factory registration),
# without the absolute path it puts in a -D define (<module>_AUTOINIT_INCLUDE="<build
# folder>/CMakeFiles/vtkModuleAutoInit_<hash>.h"), which made every unit that gets it a ccache
# miss in another clone. The define names instead a forwarding header under generated/ (on the
# include path) that includes VTK's by a relative path.
function(fovea_vtk_autoinit)
  vtk_module_autoinit(TARGETS ${ARGN} MODULES ${VTK_LIBRARIES})
  set(_prefix "\"${CMAKE_BINARY_DIR}/CMakeFiles/")
  foreach(_target IN LISTS ARGN)
    get_target_property(_defs ${_target} COMPILE_DEFINITIONS)
    set(_rewritten "")
    foreach(_def IN LISTS _defs)
      string(FIND "${_def}" "_AUTOINIT_INCLUDE=${_prefix}" _at)
      if(_at GREATER 0)
        string(REPLACE "_AUTOINIT_INCLUDE=${_prefix}" ";" _parts "${_def}")
        list(GET _parts 0 _module)
        list(GET _parts 1 _header)
        string(REPLACE "\"" "" _header "${_header}")
        get_property(_done GLOBAL PROPERTY "fovea_autoinit_${_header}")
        if(NOT _done)  # one generate command per file, whichever folder asks first
          file(GENERATE OUTPUT "${PROJECT_BINARY_DIR}/generated/fovea/${_header}"
               CONTENT "// Generated (cmake/FoveaBuildSpeed.cmake): VTK's autoinit header, by a relative path.\n#include \"../../CMakeFiles/${_header}\"\n")
          set_property(GLOBAL PROPERTY "fovea_autoinit_${_header}" TRUE)
        endif()
        set(_def "${_module}_AUTOINIT_INCLUDE=\"fovea/${_header}\"")
      endif()
      list(APPEND _rewritten "${_def}")
    endforeach()
    set_target_properties(${_target} PROPERTIES COMPILE_DEFINITIONS "${_rewritten}")
  endforeach()
endfunction()
