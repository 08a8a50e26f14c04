target_sources(crestline_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/mesh/mesh_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/repair_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/topology_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/frame_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/presmooth_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/cotan_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curvature/shape_operator_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curvature/extremality_smoothing_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/paired_cg_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/parallel_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/uninitialised_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/symmetric_eigen3_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/portable_math_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics/select_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/trace_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/polylines_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/fairing_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/clearance_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/detail_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/creases_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/creases_real_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/pipeline_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/parameters_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/real_meshes_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/invariance_test.cpp
)
# The invariance tests build the quality harness's analytic surfaces.
target_link_libraries(crestline_tests PRIVATE crestline_quality)
# The full invariance matrix (every mesh, every transform, minutes): its own
# CTest test, labelled slow so that the sanitizer run can leave it out.
add_test(NAME invariance_full COMMAND crestline_tests "[invariance-full]")
set_tests_properties(invariance_full PROPERTIES LABELS slow TIMEOUT 1500)
