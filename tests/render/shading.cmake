# Tests of BRDF models, two-pass shading, path tracing, HDR output and the render / brdf
# commands (issue 7).
target_sources(render_test PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_microfacet_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_models_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/path_tracer_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading_two_pass_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading_cornell_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading_hdr_io_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading_cli_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/smooth_radiosity_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sampler_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/light_sampling_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/image_comparison_test.cpp
)
target_link_libraries(render_test PRIVATE nlohmann_json::nlohmann_json)
