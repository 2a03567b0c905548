# BRDF models, two-pass Phong / Cook-Torrance shading, path tracing and HDR output (issue 7).
target_sources(radkit_render PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/microfacet.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_lambert.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_phong.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_cook_torrance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_mirror.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_glass.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sampler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/spherical_rectangle.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading_context.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading.cpp
  ${CMAKE_CURRENT_LIST_DIR}/path_tracer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/final_gather.cpp
  ${CMAKE_CURRENT_LIST_DIR}/path_benchmark.cpp
  ${CMAKE_CURRENT_LIST_DIR}/hdr_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/image_comparison.cpp
)
# Two-pass shading reads the radiosity solution (render/ may depend on radiosity/ results).
target_link_libraries(radkit_render PUBLIC radkit_radiosity)
