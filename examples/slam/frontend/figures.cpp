#include "frontend/figures.hpp"

#include "common/atomic_file.hpp"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace hbos::slam {

namespace {

const cv::Scalar kKept(60, 200, 60);             // green
const cv::Scalar kRejected(40, 40, 230);         // red
const cv::Scalar kPersonKept(0, 160, 255);       // orange
const cv::Scalar kPersonRejected(200, 60, 200);  // magenta
const cv::Scalar kLabel(0, 200, 240);            // amber (plain yellow is unreadable on white)
const cv::Scalar kMask(220, 190, 0);             // dark cyan
const cv::Scalar kBox(255, 120, 40);             // blue
const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kWhite(255, 255, 255);

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale,
          const cv::Scalar& colour, int thickness = 1) {
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

void outline(cv::Mat& image, const cv::Mat& mask, const cv::Scalar& colour, int thickness) {
  if (mask.empty()) return;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(image, contours, -1, colour, thickness, cv::LINE_AA);
}

cv::Point pixel(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

}  // namespace

cv::Mat draw_match_figure(const FigureFrame& figure, const std::string& title) {
  const Frame& f = figure.frame;
  constexpr int kBar = 80;  // legend above the image
  cv::Mat canvas(f.bgr.rows + kBar, f.bgr.cols, CV_8UC3, kWhite);
  cv::Mat image = canvas(cv::Rect(0, kBar, f.bgr.cols, f.bgr.rows));
  // Dimmed so that the markers stand out.
  f.bgr.convertTo(image, -1, 0.75, 20);
  outline(image, f.mask, kMask, 1);
  for (const PersonBox& b : f.detections) cv::rectangle(image, b.box, kBox, 2);
  outline(image, f.person_label, kLabel, 2);

  const TrackResult& r = figure.result;
  int kept = 0, person = 0, person_kept = 0;
  // Rejected last, so they are drawn on top.
  for (const bool draw_kept : {true, false}) {
    for (const MatchRecord& m : r.matches) {
      if (m.kept != draw_kept) continue;
      const cv::Scalar& colour = m.kept ? kKept : kRejected;
      cv::line(image, pixel(m.previous_px), pixel(m.current_px), colour, 1, cv::LINE_AA);
      cv::circle(image, pixel(m.current_px), 2, colour, cv::FILLED, cv::LINE_AA);
      if (m.on_person) cv::circle(image, pixel(m.current_px), 5, colour, 1, cv::LINE_AA);
    }
  }
  for (const MatchRecord& m : r.matches) {
    kept += m.kept ? 1 : 0;
    person += m.on_person ? 1 : 0;
    person_kept += (m.on_person && m.kept) ? 1 : 0;
  }
  const int total = static_cast<int>(r.matches.size());
  text(canvas, title, {8, 22}, 0.55, kInk, 1);
  // Legend pieces laid out left to right, each in its own colour.
  const auto legend = [&](int y, const std::vector<std::pair<std::string, cv::Scalar>>& pieces) {
    int x = 8;
    for (const auto& [words, colour] : pieces) {
      text(canvas, words, {x, y}, 0.5, colour, 1);
      int baseline = 0;
      x += cv::getTextSize(words, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline).width + 12;
    }
  };
  legend(46,
         {{fmt::format("kept {}", kept), kKept},
          {fmt::format("rejected {}", total - kept), kRejected},
          {fmt::format("| ringed: on the person {}, of them kept {}", person, person_kept), kInk}});
  std::vector<std::pair<std::string, cv::Scalar>> outlines = {
      {"outlines:", kInk}, {"person label", kLabel}, {"extraction mask", kMask}};
  if (!f.detections.empty()) outlines.emplace_back("detector boxes", kBox);
  legend(70, outlines);
  return canvas;
}

cv::Mat draw_residual_histogram(const FigureFrame& figure, const std::string& title) {
  const TrackResult& r = figure.result;
  const ScreenOutcome& s = r.screen;
  std::vector<double> finite;
  double smallest_rejected = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.magnitude.size(); ++i) {
    if (!std::isfinite(s.magnitude[i])) continue;
    finite.push_back(s.magnitude[i]);
    if (s.inlier[i] == 0) smallest_rejected = std::min(smallest_rejected, s.magnitude[i]);
  }
  const bool gate = std::isfinite(s.magnitude_cut);
  const double cut = gate ? s.magnitude_cut : smallest_rejected;

  // The axis: up to the 98th percentile (a few gross mismatches would squash the rest), and at
  // least twice the cut so the decision is visible.
  double axis = 1.0;
  if (!finite.empty()) {
    std::vector<double> sorted = finite;
    std::sort(sorted.begin(), sorted.end());
    axis = sorted[static_cast<std::size_t>(0.98 * static_cast<double>(sorted.size() - 1))];
  }
  if (std::isfinite(cut)) axis = std::max(axis, 2.0 * cut);
  axis = std::max(axis, 1e-6);

  constexpr int kBins = 40;
  // Per bin: static kept, static rejected, person kept, person rejected.
  std::vector<std::array<int, 4>> counts(kBins, {0, 0, 0, 0});
  for (std::size_t i = 0; i < s.magnitude.size(); ++i) {
    if (!std::isfinite(s.magnitude[i])) continue;
    const int bin = std::min(kBins - 1, static_cast<int>(s.magnitude[i] / axis * kBins));
    const bool person = i < r.matches.size() && r.matches[i].on_person;
    counts[static_cast<std::size_t>(bin)]
          [static_cast<std::size_t>((person ? 2 : 0) + (s.inlier[i] ? 0 : 1))]++;
  }
  int tallest = 1;
  for (const auto& c : counts) tallest = std::max(tallest, c[0] + c[1] + c[2] + c[3]);

  const int width = 960, height = 540, left = 70, right = 30, top = 70, bottom = 60;
  cv::Mat canvas(height, width, CV_8UC3, kWhite);
  const int plot_w = width - left - right, plot_h = height - top - bottom;
  const auto x_of = [&](double v) {
    return left + static_cast<int>(std::lround(v / axis * plot_w));
  };
  const auto y_of = [&](double c) {
    return top + plot_h - static_cast<int>(std::lround(c / tallest * plot_h));
  };
  const std::array<cv::Scalar, 4> colours = {kKept, kRejected, kPersonKept, kPersonRejected};
  for (int b = 0; b < kBins; ++b) {
    double base = 0;
    const int x0 = x_of(axis * b / kBins) + 1, x1 = x_of(axis * (b + 1) / kBins) - 1;
    for (std::size_t k = 0; k < 4; ++k) {
      const int c = counts[static_cast<std::size_t>(b)][k];
      if (c == 0) continue;
      cv::rectangle(canvas, cv::Point(x0, y_of(base + c)), cv::Point(x1, y_of(base)), colours[k],
                    cv::FILLED);
      base += c;
    }
  }
  // Axes with ticks.
  cv::line(canvas, {left, top + plot_h}, {left + plot_w, top + plot_h}, kInk, 1);
  cv::line(canvas, {left, top}, {left, top + plot_h}, kInk, 1);
  for (int t = 0; t <= 5; ++t) {
    const double v = axis * t / 5.0;
    cv::line(canvas, {x_of(v), top + plot_h}, {x_of(v), top + plot_h + 5}, kInk, 1);
    text(canvas, fmt::format("{:.3g}", v), {x_of(v) - 14, top + plot_h + 22}, 0.45, kInk);
    const double c = tallest * t / 5.0;
    text(canvas, fmt::format("{:.0f}", c), {10, y_of(c) + 5}, 0.45, kInk);
  }
  text(canvas, fmt::format("{} [{}]; last bin holds everything beyond", s.statistic, s.unit),
       {left, height - 12}, 0.5, kInk);
  text(canvas, "matches", {8, top - 12}, 0.45, kInk);
  if (std::isfinite(cut)) {
    const int x = x_of(std::min(cut, axis));
    for (int y = top; y < top + plot_h; y += 10) cv::line(canvas, {x, y}, {x, y + 6}, kInk, 2);
    const std::string label =
        gate ? fmt::format("threshold {:.3g}", cut)
             : fmt::format("smallest rejected {:.3g} (score cut {:.3g})", cut, s.threshold);
    text(canvas, label, {std::min(x + 6, width - 330), top + 16}, 0.5, kInk, 1);
  }
  text(canvas, title, {left, 24}, 0.55, kInk, 1);
  const std::array<const char*, 4> names = {"static kept", "static rejected", "person kept",
                                            "person rejected"};
  for (std::size_t k = 0; k < 4; ++k) {
    const int x = left + static_cast<int>(k) * 190;
    cv::rectangle(canvas, cv::Point(x, 38), cv::Point(x + 14, 52), colours[k], cv::FILLED);
    text(canvas, names[k], {x + 20, 51}, 0.5, kInk);
  }
  return canvas;
}

void write_png(const std::string& path, const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", image, bytes)) {
    throw std::runtime_error("cannot encode PNG '" + path + "'");
  }
  examples::write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace hbos::slam
