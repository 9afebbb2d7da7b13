#include "frontend/ablation.hpp"

#include "frontend/frame_source.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/run_outputs.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <ostream>

namespace hbos::slam {

std::vector<MaskSource> ablation_masks(bool add_person) {
  if (!add_person) return {MaskSource::kNone, MaskSource::kDetector};
  return {MaskSource::kNone, MaskSource::kExact, MaskSource::kDegraded, MaskSource::kDetector};
}

std::vector<AblationRow> run_ablation(const Config& base, const RgbdSequence& sequence,
                                      const CameraModel& camera, std::ostream* progress,
                                      const std::vector<std::string>& screens) {
  if (!sequence.groundtruth) {
    throw InvalidArgument("the ablation needs ground truth: '" + sequence.root +
                          "' has no groundtruth.txt");
  }
  int total_runs = 0;
  for (const bool person : {false, true}) {
    total_runs += static_cast<int>(ablation_masks(person).size() * screens.size());
  }
  std::vector<AblationRow> rows;
  for (const bool person : {false, true}) {
    for (const MaskSource mask : ablation_masks(person)) {
      Config config = base;
      config.scenario.add_person = person;
      config.mask.source = mask;
      config.output.figure_frame = 0;  // no figure is drawn; keep the cheapest
      FrameSource source(sequence, camera.depth_factor, config.scenario, config.mask);
      int n = source.size();
      if (config.dataset.max_frames > 0) n = std::min(n, config.dataset.max_frames);
      std::vector<Frame> frames;
      frames.reserve(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) frames.push_back(source.frame(i));

      for (const std::string& screen : screens) {
        config.screen.select(screen);
        const RunResult run = run_tracker(
            [&](int i) { return frames[static_cast<std::size_t>(i)]; }, n, config, camera, nullptr);
        const Trajectory estimate = estimate_of(run, "hbos-slam");
        std::vector<double> stamps(run.stamps);
        const Evaluation e = evaluate_trajectory(*sequence.groundtruth, estimate, stamps);
        AblationRow row{
            scenario_name(config.scenario),   to_string(mask), screen, run.totals, e.ate.stats.rmse,
            e.rpe ? e.rpe->trans_m.rmse : 0.0};
        rows.push_back(row);
        if (progress != nullptr) {
          *progress << fmt::format(
              "hbos-slam: ablation {:>2}/{}  {:<6} mask {:<8} screen {:<8}  ATE {:6.2f} cm  "
              "RPE {:5.2f} mm/frame\n",
              rows.size(), total_runs, row.scenario, row.mask, row.screen, row.ate_rmse_m * 100.0,
              row.rpe_trans_rmse_m * 1000.0);
          progress->flush();
        }
      }
    }
  }
  return rows;
}

std::string ablation_markdown(const std::vector<AblationRow>& rows, const Config& base,
                              const std::string& camera_name, int frames) {
  std::string md = fmt::format(
      "Sequence `{}` ({} frames, camera {}); rough pose {} ({} px); {} screening rounds; person "
      "at {} m moving {} px/frame.\n\n",
      base.dataset.path, frames, camera_name, to_string(base.rough_pose.method),
      base.rough_pose.ransac_threshold_px, base.screen.rounds, base.scenario.depth_m,
      base.scenario.speed_px_per_frame);
  md +=
      "| scenario | mask | screen | ATE RMSE [cm] | RPE trans [mm/frame] | person matches kept [%] "
      "| static matches lost [%] | screen [µs/frame, median] | mask [ms/frame, median] |\n"
      "|---|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const AblationRow& r : rows) {
    const std::string kept =
        r.totals.person_survival_share
            ? fmt::format("{:.1f} of {}", 100.0 * *r.totals.person_survival_share,
                          r.totals.person_matches)
            : "n/a (0)";
    md += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {} | {:.1f} | {:.0f} | {:.1f} |\n",
                      r.scenario, r.mask, r.screen, r.ate_rmse_m * 100.0,
                      r.rpe_trans_rmse_m * 1000.0, kept, 100.0 * r.totals.static_loss_share,
                      r.totals.median_screen_us, r.totals.median_mask_us / 1000.0);
  }
  return md;
}

std::string ablation_csv(const std::vector<AblationRow>& rows) {
  std::string csv =
      "scenario,mask,screen,ate_rmse_m,rpe_trans_rmse_m_per_frame,matches,person_matches,"
      "person_survivors,static_matches,static_dropped,mean_screen_us,median_screen_us,"
      "mean_refine_us,mean_mask_us,median_mask_us,"
      "frames_tracked\n";
  for (const AblationRow& r : rows) {
    const RunTotals& t = r.totals;
    csv += fmt::format(
        "{},{},{},{:.9g},{:.9g},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{}\n", r.scenario,
        r.mask, r.screen, r.ate_rmse_m, r.rpe_trans_rmse_m, t.matches, t.person_matches,
        t.person_survivors, t.static_matches, t.static_dropped, t.mean_screen_us,
        t.median_screen_us, t.mean_refine_us, t.mean_mask_us, t.median_mask_us, t.frames_tracked);
  }
  return csv;
}

}  // namespace hbos::slam
