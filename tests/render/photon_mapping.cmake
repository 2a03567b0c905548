# Photon mapping tests (issue 6). The comparisons with radiosity run the radiosity pipeline;
# photon_command_test runs the radkit binary (`radkit photons`).
target_sources(render_test PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/photon_tracer_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_map_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_estimate_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/photon_command_test.cpp
)
target_link_libraries(render_test PRIVATE radkit_radiosity nlohmann_json::nlohmann_json)
add_dependencies(render_test radkit)
