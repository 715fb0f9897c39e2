# The editor's layering rules (editor/CMakeLists.txt), checked on the sources' include lines:
#   render/      includes nothing from scene/, interaction/, tools/, ui/ or app/, and no ImGui;
#   scene/       includes nothing from interaction/, tools/, ui/ or app/, and no ImGui;
#   interaction/ includes nothing from tools/, ui/ or app/, and no ImGui;
#   tools/       includes nothing from ui/ or app/, and no ImGui (tool panels are in ui/).
# Run with -DEDITOR_DIR=<editor folder>: at configure time and as the test editor_layers.
if(NOT EDITOR_DIR)
  message(FATAL_ERROR "check_layers.cmake: EDITOR_DIR is not set")
endif()
set(_violations "")
foreach(_layer render scene interaction tools)
  if(_layer STREQUAL "render")
    set(_forbidden "scene|interaction|tools|ui|app")
  elseif(_layer STREQUAL "scene")
    set(_forbidden "interaction|tools|ui|app")
  elseif(_layer STREQUAL "interaction")
    set(_forbidden "tools|ui|app")
  else()
    set(_forbidden "ui|app")
  endif()
  file(GLOB _files ${EDITOR_DIR}/${_layer}/*.h ${EDITOR_DIR}/${_layer}/*.cpp)
  foreach(_f ${_files})
    file(STRINGS ${_f} _bad REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](((${_forbidden})/)|imgui)")
    foreach(_line ${_bad})
      string(APPEND _violations "\n  ${_f}: ${_line}")
    endforeach()
  endforeach()
endforeach()
if(_violations)
  message(FATAL_ERROR "editor layering violated (docs/editor.md, editor/CMakeLists.txt):${_violations}")
endif()
