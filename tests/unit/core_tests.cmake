target_sources(crestline_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/mesh/repair_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh/presmooth_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curvature/shape_operator_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curvature/extremality_smoothing_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/trace_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/polylines_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lines/fairing_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/pipeline_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline/real_meshes_test.cpp
)
