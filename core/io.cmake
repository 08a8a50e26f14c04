# Input and output. Readers (core/readers.cmake) and writers
# (core/writers.cmake) are separate libraries; crestline_io is both.
include(${CMAKE_CURRENT_LIST_DIR}/readers.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/writers.cmake)
add_library(crestline_io INTERFACE)
target_link_libraries(crestline_io INTERFACE crestline_readers crestline_writers)
