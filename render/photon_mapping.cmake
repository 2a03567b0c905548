# Photon mapping (issue 6): tracing, the kd-tree photon map, per-patch estimates, images,
# the comparison with radiosity and the speed references.
target_sources(radkit_render PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/photon_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_tracer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_estimate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_image.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_comparison.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_benchmark.cpp
)
