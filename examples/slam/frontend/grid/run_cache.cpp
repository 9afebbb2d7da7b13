#include "frontend/grid/run_cache.hpp"

#include "common/atomic_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace hbos::slam {

namespace {

nlohmann::json cached_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

double cached_number_or_nan(const nlohmann::json& j) {
  return j.is_number() ? j.get<double>() : std::nan("");
}

}  // namespace

nlohmann::json to_json(const GridRun& r) {
  return {{"tracker", r.tracker},
          {"variant", r.variant},
          {"mask", r.mask},
          {"screen", r.screen},
          {"ate_rmse_m", cached_number(r.ate_rmse_m)},
          {"rpe_trans_rmse_m_per_frame", cached_number(r.rpe_trans_rmse_m)},
          {"frames", r.frames},
          {"frames_tracked", r.frames_tracked},
          {"matches", r.matches},
          {"person_matches", r.person_matches},
          {"person_survivors", r.person_survivors},
          {"static_matches", r.static_matches},
          {"static_dropped", r.static_dropped},
          {"frame_person_matches", r.frame_person_matches},
          {"frame_person_survivors", r.frame_person_survivors}};
}

std::optional<GridRun> read_cached_run(const std::string& path, const std::string& settings) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("settings", "") != settings) {
    return std::nullopt;
  }
  try {
    const nlohmann::json& r = j.at("run");
    GridRun run;
    run.tracker = r.at("tracker").get<std::string>();
    run.variant = r.at("variant").get<std::string>();
    run.mask = r.at("mask").get<std::string>();
    run.screen = r.at("screen").get<std::string>();
    run.ate_rmse_m = cached_number_or_nan(r.at("ate_rmse_m"));
    run.rpe_trans_rmse_m = cached_number_or_nan(r.at("rpe_trans_rmse_m_per_frame"));
    run.frames = r.at("frames").get<int>();
    run.frames_tracked = r.at("frames_tracked").get<int>();
    run.matches = r.at("matches").get<long>();
    run.person_matches = r.at("person_matches").get<long>();
    run.person_survivors = r.at("person_survivors").get<long>();
    run.static_matches = r.at("static_matches").get<long>();
    run.static_dropped = r.at("static_dropped").get<long>();
    run.frame_person_matches = r.at("frame_person_matches").get<std::vector<int>>();
    run.frame_person_survivors = r.at("frame_person_survivors").get<std::vector<int>>();
    return run;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // an older or damaged file: run it again
  }
}

void write_cached_run(const std::string& path, const GridRun& run, const std::string& settings) {
  const nlohmann::json j = {{"settings", settings}, {"run", to_json(run)}};
  examples::write_file_atomically(path, j.dump(1) + "\n");
}

}  // namespace hbos::slam
