#pragma once
/// \file
/// The ablation: every screen strategy under every mask, on the static sequence and with the
/// composited person, each run tracked and evaluated like a single run. Frames are read and
/// masked once per (scenario, mask) and shared by the strategies.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/dataset.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/sequence_run.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace hbos::slam {

struct AblationRow {
  std::string scenario;  ///< static | person
  std::string mask;
  std::string screen;
  RunTotals totals;
  double ate_rmse_m = 0.0;
  double rpe_trans_rmse_m = 0.0;  ///< per frame
};

/// The masks run for each scenario: the static sequence has no composited person, so only the
/// masks that do not depend on it (none, detector) are run there.
[[nodiscard]] std::vector<MaskSource> ablation_masks(bool add_person);

/// Runs the grid on `sequence` (which needs ground truth): `screens` (by default every strategy,
/// screen_strategy_names()) under every mask of ablation_masks(). `base` supplies every other
/// setting. With `progress`, one line per run.
[[nodiscard]] std::vector<AblationRow> run_ablation(
    const Config& base, const RgbdSequence& sequence, const CameraModel& camera,
    std::ostream* progress, const std::vector<std::string>& screens = screen_strategy_names());

/// The rows as a Markdown table (ATE RMSE cm, RPE trans mm/frame, person matches kept %, static
/// matches lost %, screen us/frame), preceded by a line on the settings.
[[nodiscard]] std::string ablation_markdown(const std::vector<AblationRow>& rows,
                                            const Config& base, const std::string& camera_name,
                                            int frames);

/// The rows as CSV, full precision, for scripts.
[[nodiscard]] std::string ablation_csv(const std::vector<AblationRow>& rows);

}  // namespace hbos::slam
