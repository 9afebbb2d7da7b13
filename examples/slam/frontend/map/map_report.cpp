#include "frontend/map/map_report.hpp"

#include "common/atomic_file.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace hbos::slam {

namespace {

double tracked_share(const MapRun& r) {
  const auto frames = r.run.stats.size();
  return frames > 0 ? static_cast<double>(frames - static_cast<std::size_t>(r.lost_frames)) /
                          static_cast<double>(frames)
                    : 0.0;
}

}  // namespace

nlohmann::json map_report_json(const MapRun& r) {
  const StageTimes& t = r.stages;
  nlohmann::json j;
  j["frames"] = r.run.stats.size();
  j["frames_tracked"] = r.run.stats.size() - static_cast<std::size_t>(r.lost_frames);
  j["tracked_share"] = tracked_share(r);
  j["relocalisations"] = r.relocalisations;
  j["map"] = {{"keyframes", r.keyframes},
              {"points_created", r.map_points},
              {"points_culled", r.culled_points},
              {"points_live", r.map_points - r.culled_points}};
  j["table_iii_ms_per_frame"] = {{"segmentation", t.segmentation_ms},
                                 {"motion_estimation", t.motion_estimation_ms},
                                 {"dynamic_point_detection_and_removal", t.dynamic_removal_ms}};
  j["stages_ms_per_frame"] = {{"decode", t.decode_ms},         {"segmentation", t.segmentation_ms},
                              {"orb", t.extraction_ms},        {"tracking", t.tracking_ms},
                              {"rough_pose", t.rough_pose_ms}, {"local_map", t.local_map_ms},
                              {"screen", t.screen_ms},         {"refine", t.refine_ms},
                              {"map_upkeep", t.map_ms},        {"sum", t.sum_ms}};
  j["wall_ms_per_frame"] = t.wall_ms;
  j["fps"] = t.fps;
  return j;
}

std::string map_frames_csv(const MapRun& r) {
  std::string csv =
      "frame,source,tracked,last_frame_matches,local_map_matches,keyframe,keyframes,live_points,"
      "culled_points,decode_us,mask_us,orb_us,tracking_us,rough_us,local_map_us,screen_us,"
      "refine_us,map_us,bundle_us,bundle_outliers\n";
  for (std::size_t i = 0; i < r.reports.size(); ++i) {
    const MapFrameReport& m = r.reports[i];
    const FrameStats& s = r.run.stats[i];
    csv += fmt::format(
        "{},{},{},{},{},{},{},{},{},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},"
        "{:.1f},{:.1f},{}\n",
        s.index, to_string(m.source), s.tracked ? 1 : 0, m.last_frame_matches, m.local_map_matches,
        m.keyframe_inserted ? 1 : 0, m.keyframes, m.live_points, m.culled_points,
        i < r.decode_us.size() ? r.decode_us[i] : 0.0, s.mask_us, m.extract_us, m.tracking_us,
        m.rough_us, m.local_map_us, m.screen_us, m.refine_us, m.map_us, m.bundle_us,
        m.bundle_outliers);
  }
  return csv;
}

std::string map_summary_text(const MapRun& r) {
  const StageTimes& t = r.stages;
  std::string s = fmt::format(
      "  map tracker: {} of {} frames tracked ({:.1f} %), {} relocalisations; map: {} keyframes, "
      "{} points ({} culled by their screening history)\n",
      r.run.stats.size() - static_cast<std::size_t>(r.lost_frames), r.run.stats.size(),
      100.0 * tracked_share(r), r.relocalisations, r.keyframes, r.map_points, r.culled_points);
  s += fmt::format(
      "  Table III [ms/frame]: segmentation {:.2f}, motion estimation {:.2f}, dynamic point "
      "detection and removal {:.2f}\n",
      t.segmentation_ms, t.motion_estimation_ms, t.dynamic_removal_ms);
  s += fmt::format(
      "  stages [ms/frame]: decode {:.2f}, ORB {:.2f}, tracking {:.2f}, rough pose {:.2f}, local "
      "map {:.2f}, screen {:.2f}, refine {:.2f}, map {:.2f}; wall {:.2f} ms/frame = {:.1f} fps\n",
      t.decode_ms, t.extraction_ms, t.tracking_ms, t.rough_pose_ms, t.local_map_ms, t.screen_ms,
      t.refine_ms, t.map_ms, t.wall_ms, t.fps);
  return s;
}

std::vector<std::string> write_map_outputs(const std::string& dir, const MapRun& run) {
  const auto path = [&](const char* name) { return (std::filesystem::path(dir) / name).string(); };
  examples::write_file_atomically(path("map.json"), map_report_json(run).dump(1) + "\n");
  examples::write_file_atomically(path("map_frames.csv"), map_frames_csv(run));
  return {path("map.json"), path("map_frames.csv")};
}

}  // namespace hbos::slam
