# The mini-SLAM front end (hbos-slam). Included from examples/slam/CMakeLists.txt after the
# static library hbos_slam is defined: the front end's stages join that library (so the tests in
# tests/slam reach them), and its commands link it.
include_guard(GLOBAL)
if(NOT TARGET hbos_slam)
  return()
endif()

set(_hbos_frontend_dir ${CMAKE_CURRENT_LIST_DIR})
target_sources(hbos_slam PRIVATE
  ${_hbos_frontend_dir}/ablation.cpp
  ${_hbos_frontend_dir}/camera.cpp
  ${_hbos_frontend_dir}/config.cpp
  ${_hbos_frontend_dir}/dataset.cpp
  ${_hbos_frontend_dir}/figures.cpp
  ${_hbos_frontend_dir}/frame_matching.cpp
  ${_hbos_frontend_dir}/frame_source.cpp
  ${_hbos_frontend_dir}/leverage_guard.cpp
  ${_hbos_frontend_dir}/shared_bias.cpp
  ${_hbos_frontend_dir}/mask_distance.cpp
  ${_hbos_frontend_dir}/mask_files.cpp
  ${_hbos_frontend_dir}/keypoint_spread.cpp
  ${_hbos_frontend_dir}/orb_extraction.cpp
  ${_hbos_frontend_dir}/person_detector.cpp
  ${_hbos_frontend_dir}/person_mask.cpp
  ${_hbos_frontend_dir}/person_scenario.cpp
  ${_hbos_frontend_dir}/pnp_pose.cpp
  ${_hbos_frontend_dir}/pose_refiner.cpp
  ${_hbos_frontend_dir}/residual_screen.cpp
  ${_hbos_frontend_dir}/rough_pose.cpp
  ${_hbos_frontend_dir}/run_outputs.cpp
  ${_hbos_frontend_dir}/sequence_run.cpp
  ${_hbos_frontend_dir}/tracker.cpp)
# The map tracker (--tracker map): one file per stage under map/.
target_sources(hbos_slam PRIVATE
  ${_hbos_frontend_dir}/map/keyframe_policy.cpp
  ${_hbos_frontend_dir}/map/local_bundle_adjustment.cpp
  ${_hbos_frontend_dir}/map/local_mapping.cpp
  ${_hbos_frontend_dir}/map/map.cpp
  ${_hbos_frontend_dir}/map/map_point.cpp
  ${_hbos_frontend_dir}/map/point_noise.cpp
  ${_hbos_frontend_dir}/map/noise_history.cpp
  ${_hbos_frontend_dir}/map/map_report.cpp
  ${_hbos_frontend_dir}/map/map_run.cpp
  ${_hbos_frontend_dir}/map/map_tracker.cpp
  ${_hbos_frontend_dir}/map/projection_matcher.cpp
  ${_hbos_frontend_dir}/map/relocaliser.cpp)
# The variant grid (--variant-grid): the screens ranked over semi-real variants, under grid/.
target_sources(hbos_slam PRIVATE
  ${_hbos_frontend_dir}/grid/grid_command.cpp
  ${_hbos_frontend_dir}/grid/grid_report.cpp
  ${_hbos_frontend_dir}/grid/grid_run.cpp
  ${_hbos_frontend_dir}/grid/parallax.cpp
  ${_hbos_frontend_dir}/grid/run_cache.cpp
  ${_hbos_frontend_dir}/grid/variants.cpp)

# The embedded data (examples/slam/data): the default input of hbos-slam and the tests' input.
get_filename_component(_hbos_slam_data_dir ${_hbos_frontend_dir}/../data ABSOLUTE)
target_compile_definitions(hbos_slam PUBLIC HBOS_SLAM_DATA_DIR="${_hbos_slam_data_dir}")

add_library(hbos_slam_command STATIC ${_hbos_frontend_dir}/slam_command.cpp)
target_link_libraries(hbos_slam_command PUBLIC hbos_slam)
hbos_set_warnings(hbos_slam_command)
add_executable(hbos-slam ${_hbos_frontend_dir}/hbos_slam.cpp)
target_link_libraries(hbos-slam PRIVATE hbos_slam_command)
hbos_set_warnings(hbos-slam)

# Regenerates examples/slam/data from ../shared (see the SOURCE.md files there).
add_executable(hbos-slam-prepare-data ${_hbos_frontend_dir}/prepare_data.cpp)
target_link_libraries(hbos-slam-prepare-data PRIVATE hbos_slam)
hbos_set_warnings(hbos-slam-prepare-data)
