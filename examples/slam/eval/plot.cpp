#include "eval/plot.hpp"

#include "common/atomic_file.hpp"
#include "common/index.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>

namespace hbos::slam {

namespace {

using examples::at;

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTextScale = 0.5;
constexpr double kTitleScale = 0.6;
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(228, 228, 228);
const cv::Scalar kGtColour(110, 110, 110);
const cv::Scalar kSeriesColour(190, 100, 30);  // BGR: a dark blue
const cv::Scalar kRmseColour(40, 40, 215);     // red
const cv::Scalar kMeanColour(50, 150, 50);     // green
const cv::Scalar kMedianColour(0, 140, 250);   // orange

struct Range {
  double lo = 0.0;
  double hi = 1.0;
  [[nodiscard]] double span() const { return hi - lo; }
};

// A linear map from data coordinates to the pixels of a plot area, y pointing up.
struct Axes {
  cv::Rect area;
  Range x;
  Range y;
  [[nodiscard]] cv::Point to_pixel(double u, double v) const {
    const double px = area.x + (u - x.lo) / x.span() * area.width;
    const double py = area.y + area.height - (v - y.lo) / y.span() * area.height;
    return {cvRound(px), cvRound(py)};
  }
};

// Tick spacing of 1, 2 or 5 times a power of ten giving about `target` ticks.
double nice_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double normalised = raw / magnitude;
  const double nice = normalised < 1.5   ? 1.0
                      : normalised < 3.0 ? 2.0
                      : normalised < 7.0 ? 5.0
                                         : 10.0;
  return nice * magnitude;
}

std::string tick_label(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  if (std::abs(value) < 1e-6 * step) value = 0.0;  // no "-0.00"
  // Sub-micrometre ticks only occur for (near-)perfect estimates; keep their labels short.
  if (decimals > 6) return fmt::format("{:.1e}", value);
  return fmt::format("{:.{}f}", value, decimals);
}

cv::Size text_size(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline);
}

void put_text(cv::Mat& image, const std::string& text, cv::Point origin, double scale,
              const cv::Scalar& colour) {
  cv::putText(image, text, origin, kFont, scale, colour, 1, cv::LINE_AA);
}

// OpenCV cannot draw rotated text: draw it on a patch and rotate the patch.
void put_vertical_text(cv::Mat& image, const std::string& text, cv::Point centre) {
  const cv::Size size = text_size(text, kTextScale);
  cv::Mat patch(size.height + 8, size.width + 4, CV_8UC3, kWhite);
  put_text(patch, text, {2, size.height + 2}, kTextScale, kBlack);
  cv::Mat rotated;
  cv::rotate(patch, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect wanted(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols,
                        rotated.rows);
  const cv::Rect target = wanted & cv::Rect(0, 0, image.cols, image.rows);
  if (target.empty()) return;  // entirely outside the image: nothing to draw
  rotated(cv::Rect(target.tl() - wanted.tl(), target.size())).copyTo(image(target));
}

void draw_dashed_line(cv::Mat& image, cv::Point a, cv::Point b, const cv::Scalar& colour) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  constexpr double kDash = 10.0;
  constexpr double kGap = 6.0;
  for (double s = 0.0; s < length; s += kDash + kGap) {
    const double e = std::min(length, s + kDash);
    const cv::Point p(cvRound(a.x + (b.x - a.x) * s / length),
                      cvRound(a.y + (b.y - a.y) * s / length));
    const cv::Point q(cvRound(a.x + (b.x - a.x) * e / length),
                      cvRound(a.y + (b.y - a.y) * e / length));
    cv::line(image, p, q, colour, 2, cv::LINE_AA);
  }
}

// Grid, ticks, tick labels, frame and axis labels of one plot area.
void draw_axes(cv::Mat& image, const Axes& axes, const std::string& x_label,
               const std::string& y_label) {
  const int x_ticks = std::max(2, axes.area.width / 110);
  const int y_ticks = std::max(2, axes.area.height / 80);
  const double x_step = nice_step(axes.x.span(), x_ticks);
  const double y_step = nice_step(axes.y.span(), y_ticks);
  int widest_y_label = 0;
  for (auto k = static_cast<long long>(std::ceil(axes.x.lo / x_step));
       static_cast<double>(k) * x_step <= axes.x.hi; ++k) {
    const double u = static_cast<double>(k) * x_step;
    const int px = axes.to_pixel(u, axes.y.lo).x;
    cv::line(image, {px, axes.area.y}, {px, axes.area.br().y}, kGrid, 1);
    cv::line(image, {px, axes.area.br().y}, {px, axes.area.br().y + 5}, kBlack, 1);
    const std::string label = tick_label(u, x_step);
    const cv::Size size = text_size(label, kTextScale);
    put_text(image, label, {px - size.width / 2, axes.area.br().y + 10 + size.height}, kTextScale,
             kBlack);
  }
  for (auto k = static_cast<long long>(std::ceil(axes.y.lo / y_step));
       static_cast<double>(k) * y_step <= axes.y.hi; ++k) {
    const double v = static_cast<double>(k) * y_step;
    const int py = axes.to_pixel(axes.x.lo, v).y;
    cv::line(image, {axes.area.x, py}, {axes.area.br().x, py}, kGrid, 1);
    cv::line(image, {axes.area.x - 5, py}, {axes.area.x, py}, kBlack, 1);
    const std::string label = tick_label(v, y_step);
    const cv::Size size = text_size(label, kTextScale);
    widest_y_label = std::max(widest_y_label, size.width);
    put_text(image, label, {axes.area.x - 9 - size.width, py + size.height / 2}, kTextScale,
             kBlack);
  }
  cv::rectangle(image, axes.area, kBlack, 1);
  const cv::Size x_size = text_size(x_label, kTextScale);
  put_text(
      image, x_label,
      {axes.area.x + (axes.area.width - x_size.width) / 2, axes.area.br().y + 28 + x_size.height},
      kTextScale, kBlack);
  put_vertical_text(image, y_label,
                    {axes.area.x - 9 - widest_y_label - 14, axes.area.y + axes.area.height / 2});
}

// 256 colours of the Turbo map (dark blue → red), visible on white at both ends.
cv::Mat colour_table() {
  cv::Mat ramp(256, 1, CV_8UC1);
  for (int i = 0; i < 256; ++i) ramp.at<unsigned char>(i) = static_cast<unsigned char>(i);
  cv::Mat table;
  cv::applyColorMap(ramp, table, cv::COLORMAP_TURBO);
  return table;
}

cv::Scalar colour_of(const cv::Mat& table, double value, double max_value) {
  const double t = max_value > 0.0 ? std::clamp(value / max_value, 0.0, 1.0) : 0.0;
  const cv::Vec3b c = table.at<cv::Vec3b>(cvRound(t * 255.0));
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

void draw_colour_bar(cv::Mat& image, const cv::Rect& bar, const cv::Mat& table, double max_value,
                     const std::string& label) {
  for (int r = 0; r < bar.height; ++r) {
    const double value = max_value * (1.0 - static_cast<double>(r) / (bar.height - 1));
    cv::line(image, {bar.x, bar.y + r}, {bar.x + bar.width - 1, bar.y + r},
             colour_of(table, value, max_value), 1);
  }
  cv::rectangle(image, bar, kBlack, 1);
  const double step = nice_step(max_value, 6);
  for (long long k = 0; static_cast<double>(k) * step <= max_value * (1.0 + 1e-9); ++k) {
    const double value = static_cast<double>(k) * step;
    const int py = bar.br().y - 1 - cvRound(value / max_value * (bar.height - 1));
    cv::line(image, {bar.br().x, py}, {bar.br().x + 5, py}, kBlack, 1);
    const std::string text = tick_label(value, step);
    put_text(image, text, {bar.br().x + 8, py + text_size(text, kTextScale).height / 2}, kTextScale,
             kBlack);
  }
  const cv::Size size = text_size(label, kTextScale);
  put_text(image, label, {bar.x + bar.width / 2 - size.width / 2, bar.y - 10}, kTextScale, kBlack);
}

// Indices k where the series breaks: poses k and k+1 are further apart in time than gap_factor
// median periods, e.g. where tracking was lost.
std::vector<bool> breaks_after(const std::vector<double>& times, double gap_factor) {
  std::vector<bool> breaks(times.size(), false);
  if (times.size() < 3) return breaks;
  std::vector<double> periods;
  for (std::size_t k = 0; k + 1 < times.size(); ++k) periods.push_back(times[k + 1] - times[k]);
  std::vector<double> sorted = periods;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                   sorted.end());
  const double limit = gap_factor * sorted[sorted.size() / 2];
  for (std::size_t k = 0; k < periods.size(); ++k) breaks[k] = periods[k] > limit;
  return breaks;
}

void check_plot_params(const PlotParams& params) {
  detail::require(params.width >= 400 && params.width <= 10000, "PlotParams::width must lie in ",
                  "[400, 10000] px, got ", params.width);
  detail::require(params.height >= 300 && params.height <= 10000,
                  "PlotParams::height must lie in [300, 10000] px, got ", params.height);
  detail::require(std::isfinite(params.gap_factor) && params.gap_factor > 1.0,
                  "PlotParams::gap_factor must be finite and > 1, got ", params.gap_factor);
}

const char* alignment_name(const AteResult& ate) {
  return ate.alignment_kind == AlignmentKind::kSe3 ? "SE(3)" : "Sim(3)";
}

// Stamps (relative to the first ground-truth stamp) of the ATE's matches.
std::vector<double> match_times(const Trajectory& gt, const AteResult& ate) {
  detail::require(ate.n_gt_poses == gt.size(), "plot: the evaluation was made with a ground truth",
                  " of ", ate.n_gt_poses, " poses, but '", gt.name, "' has ", gt.size());
  std::vector<double> times;
  times.reserve(ate.matches.size());
  for (const Match& m : ate.matches) times.push_back(gt.stamps[at(m.gt)] - gt.stamps.front());
  return times;
}

Range padded(double lo, double hi, double fraction, double minimum_span) {
  const double span = std::max(hi - lo, minimum_span);
  const double centre = (lo + hi) / 2.0;
  return {centre - span * (0.5 + fraction), centre + span * (0.5 + fraction)};
}

void draw_legend_entry(cv::Mat& image, cv::Point& cursor, const std::string& text,
                       const cv::Scalar& colour, bool dashed) {
  const cv::Point a(cursor.x, cursor.y - 5);
  const cv::Point b(cursor.x + 30, cursor.y - 5);
  if (dashed) {
    draw_dashed_line(image, a, b, colour);
  } else {
    cv::line(image, a, b, colour, 2, cv::LINE_AA);
  }
  put_text(image, text, {cursor.x + 36, cursor.y}, kTextScale, kBlack);
  cursor.x += 36 + text_size(text, kTextScale).width + 24;
}

void draw_series(cv::Mat& image, const Axes& axes, const std::vector<double>& times,
                 const Eigen::VectorXd& values, double gap_factor, const cv::Scalar& colour) {
  const std::vector<bool> breaks = breaks_after(times, gap_factor);
  for (std::size_t k = 0; k + 1 < times.size(); ++k) {
    if (breaks[k]) continue;
    cv::line(image, axes.to_pixel(times[k], values(static_cast<Eigen::Index>(k))),
             axes.to_pixel(times[k + 1], values(static_cast<Eigen::Index>(k + 1))), colour, 1,
             cv::LINE_AA);
  }
  for (std::size_t k = 0; k < times.size(); ++k) {
    cv::circle(image, axes.to_pixel(times[k], values(static_cast<Eigen::Index>(k))), 2, colour,
               cv::FILLED, cv::LINE_AA);
  }
}

void draw_statistic_line(cv::Mat& image, const Axes& axes, double value, const cv::Scalar& colour) {
  draw_dashed_line(image, axes.to_pixel(axes.x.lo, value), axes.to_pixel(axes.x.hi, value), colour);
}

// One panel of errors over time with its RMSE, mean and median lines and a legend row above it.
void draw_error_panel(cv::Mat& image, const cv::Rect& area, const std::vector<double>& times,
                      const Eigen::VectorXd& values, const ErrorStatistics& stats, double t_end,
                      const std::string& quantity, const std::string& unit,
                      const std::string& series_label, const PlotParams& params) {
  Axes axes{area, {0.0, std::max(t_end, 1e-3)}, {0.0, std::max(stats.max * 1.08, 1e-9)}};
  draw_axes(image, axes, "time since the first ground-truth pose [s]",
            quantity + " [" + unit + "]");
  draw_statistic_line(image, axes, stats.median, kMedianColour);
  draw_statistic_line(image, axes, stats.mean, kMeanColour);
  draw_statistic_line(image, axes, stats.rmse, kRmseColour);
  draw_series(image, axes, times, values, params.gap_factor, kSeriesColour);
  cv::Point cursor(area.x + 4, area.y - 10);
  draw_legend_entry(image, cursor, series_label, kSeriesColour, false);
  draw_legend_entry(image, cursor, fmt::format("RMSE {:#.4g} {}", stats.rmse, unit), kRmseColour,
                    true);
  draw_legend_entry(image, cursor, fmt::format("mean {:#.4g} {}", stats.mean, unit), kMeanColour,
                    true);
  draw_legend_entry(image, cursor, fmt::format("median {:#.4g} {}", stats.median, unit),
                    kMedianColour, true);
}

}  // namespace

cv::Mat draw_top_view(const Trajectory& gt, const Evaluation& evaluation,
                      const PlotParams& params) {
  check_plot_params(params);
  const AteResult& ate = evaluation.main_ate();
  const std::vector<double> times = match_times(gt, ate);
  int u_row = 0;
  int v_row = 1;
  std::string u_name = "x";
  std::string v_name = "y";
  if (params.plane == PlotPlane::kXZ) {
    v_row = 2;
    v_name = "z";
  } else if (params.plane == PlotPlane::kYZ) {
    u_row = 1;
    v_row = 2;
    u_name = "y";
    v_name = "z";
  }

  cv::Mat image(params.height, params.width, CV_8UC3, kWhite);
  const cv::Rect area(90, 70, params.width - 90 - 130, params.height - 70 - 70);

  // Equal scales on both axes: a top view distorted by unequal scales misleads.
  const Eigen::Index u = u_row;
  const Eigen::Index v = v_row;
  const double u_lo =
      std::min(gt.positions.row(u).minCoeff(), ate.aligned_positions.row(u).minCoeff());
  const double u_hi =
      std::max(gt.positions.row(u).maxCoeff(), ate.aligned_positions.row(u).maxCoeff());
  const double v_lo =
      std::min(gt.positions.row(v).minCoeff(), ate.aligned_positions.row(v).minCoeff());
  const double v_hi =
      std::max(gt.positions.row(v).maxCoeff(), ate.aligned_positions.row(v).maxCoeff());
  const Range u_range = padded(u_lo, u_hi, 0.04, 1e-3);
  const Range v_range = padded(v_lo, v_hi, 0.04, 1e-3);
  const double metres_per_pixel =
      std::max(u_range.span() / area.width, v_range.span() / area.height);
  const double u_centre = (u_range.lo + u_range.hi) / 2.0;
  const double v_centre = (v_range.lo + v_range.hi) / 2.0;
  const Axes axes{area,
                  {u_centre - metres_per_pixel * area.width / 2.0,
                   u_centre + metres_per_pixel * area.width / 2.0},
                  {v_centre - metres_per_pixel * area.height / 2.0,
                   v_centre + metres_per_pixel * area.height / 2.0}};
  draw_axes(image, axes, u_name + " [m]", v_name + " [m]");

  std::vector<cv::Point> gt_line;
  gt_line.reserve(gt.stamps.size());
  for (Eigen::Index k = 0; k < gt.size(); ++k) {
    gt_line.push_back(axes.to_pixel(gt.positions(u, k), gt.positions(v, k)));
  }
  cv::polylines(image, gt_line, false, kGtColour, 2, cv::LINE_AA);

  const cv::Mat table = colour_table();
  // A perfect estimate still needs a colour scale with a non-zero span.
  const double max_error = std::max(ate.stats.max, 1e-9);
  const std::vector<bool> breaks = breaks_after(times, params.gap_factor);
  const Eigen::Matrix3Xd& est = ate.aligned_positions;
  for (Eigen::Index k = 0; k + 1 < est.cols(); ++k) {
    if (breaks[at(k)]) continue;
    const double error = (ate.errors(k) + ate.errors(k + 1)) / 2.0;
    cv::line(image, axes.to_pixel(est(u, k), est(v, k)),
             axes.to_pixel(est(u, k + 1), est(v, k + 1)), colour_of(table, error, max_error), 2,
             cv::LINE_AA);
  }
  for (Eigen::Index k = 0; k < est.cols(); ++k) {
    cv::circle(image, axes.to_pixel(est(u, k), est(v, k)), 3,
               colour_of(table, ate.errors(k), max_error), cv::FILLED, cv::LINE_AA);
  }
  // Where the ground truth starts, so the direction of travel can be read.
  cv::circle(image, gt_line.front(), 6, kBlack, 2, cv::LINE_AA);

  draw_colour_bar(image, {area.br().x + 30, area.y + 20, 20, area.height - 20}, table, max_error,
                  "ATE [m]");
  put_text(image,
           fmt::format("Top view {}-{}: ground truth vs {}-aligned estimate, ATE RMSE {:.4g} m ({} "
                       "poses)",
                       u_name, v_name, alignment_name(ate), ate.stats.rmse, ate.stats.count),
           {area.x, 26}, kTitleScale, kBlack);
  cv::Point cursor(area.x + 4, 54);
  draw_legend_entry(image, cursor, "ground truth (circle: start)", kGtColour, false);
  draw_legend_entry(image, cursor, "estimate, coloured by ATE",
                    colour_of(table, 0.5 * max_error, max_error), false);
  return image;
}

cv::Mat draw_ate_over_time(const Trajectory& gt, const Evaluation& evaluation,
                           const PlotParams& params) {
  check_plot_params(params);
  const AteResult& ate = evaluation.main_ate();
  const std::vector<double> times = match_times(gt, ate);
  cv::Mat image(params.height, params.width, CV_8UC3, kWhite);
  const cv::Rect area(90, 76, params.width - 90 - 30, params.height - 76 - 70);
  draw_error_panel(image, area, times, ate.errors, ate.stats, gt.stamps.back() - gt.stamps.front(),
                   "ATE", "m", "per evaluated pose", params);
  put_text(image,
           fmt::format("ATE over time: {} poses after {} alignment, {:.1f} s of ground truth",
                       ate.stats.count, alignment_name(ate), gt.stamps.back() - gt.stamps.front()),
           {area.x, 28}, kTitleScale, kBlack);
  return image;
}

cv::Mat draw_rpe_over_time(const Trajectory& gt, const Trajectory& est,
                           const Evaluation& evaluation, const PlotParams& params) {
  check_plot_params(params);
  detail::require(evaluation.rpe.has_value(), "draw_rpe_over_time: the evaluation has no RPE");
  const RpeResult& rpe = *evaluation.rpe;
  detail::require(rpe.n_est_poses == est.size() && rpe.n_gt_poses == gt.size(),
                  "draw_rpe_over_time: the evaluation was made with other trajectories");
  const auto n = static_cast<Eigen::Index>(rpe.pairs.size());
  std::vector<double> times;
  Eigen::VectorXd trans(n);
  Eigen::VectorXd rot(n);
  constexpr double kDegreesPerRadian = 180.0 / 3.141592653589793;
  for (Eigen::Index k = 0; k < n; ++k) {
    const RpePair& pair = rpe.pairs[at(k)];
    times.push_back(est.stamps[at(pair.est0)] + evaluation.params.association.offset -
                    gt.stamps.front());
    trans(k) = pair.trans_error;
    rot(k) = pair.rot_error * kDegreesPerRadian;
  }
  cv::Mat image(params.height, params.width, CV_8UC3, kWhite);
  const int top = 76;
  const int gap = 90;
  const int panel_height = (params.height - top - gap - 64) / 2;
  const cv::Rect upper(90, top, params.width - 90 - 30, panel_height);
  const cv::Rect lower(90, top + panel_height + gap, params.width - 90 - 30, panel_height);
  const double t_end = gt.stamps.back() - gt.stamps.front();
  draw_error_panel(image, upper, times, trans, rpe.trans_m, t_end, "RPE transl.", "m",
                   "per pose pair", params);
  draw_error_panel(image, lower, times, rot, rpe.rot_deg, t_end, "RPE rot.", "deg", "per pose pair",
                   params);
  put_text(image,
           fmt::format("RPE over time: fixed delta {} {}, {} pairs", evaluation.params.rpe_delta,
                       evaluation.params.rpe_unit == RpeDeltaUnit::kSeconds  ? "s"
                       : evaluation.params.rpe_unit == RpeDeltaUnit::kFrames ? "frames"
                                                                             : "m along the GT",
                       rpe.trans_m.count),
           {upper.x, 28}, kTitleScale, kBlack);
  return image;
}

std::vector<std::string> write_plots(const std::string& dir, const Trajectory& gt,
                                     const Trajectory& est, const Evaluation& evaluation,
                                     const PlotParams& params) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("cannot create plot directory '" + dir +
                             "': " + (error ? error.message() : "not a directory"));
  }
  std::vector<std::pair<std::string, cv::Mat>> images = {
      {"top_view.png", draw_top_view(gt, evaluation, params)},
      {"ate_over_time.png", draw_ate_over_time(gt, evaluation, params)}};
  if (evaluation.rpe) {
    images.emplace_back("rpe_over_time.png", draw_rpe_over_time(gt, est, evaluation, params));
  }
  std::vector<std::string> written;
  for (const auto& [name, image] : images) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image, png, {cv::IMWRITE_PNG_COMPRESSION, 9})) {
      throw std::runtime_error("cannot encode " + name + " as PNG");
    }
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    examples::write_file_atomically(
        path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    written.push_back(path.string());
  }
  return written;
}

}  // namespace hbos::slam
