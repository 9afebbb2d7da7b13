// Plots: images of the requested size that actually show the data (ground truth in grey, the
// estimate in colour-map colours, the colour bar, the statistic lines), written atomically as
// PNGs that decode.
#include "eval/evaluate.hpp"
#include "eval/plot.hpp"
#include "eval/trajectory_io.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

using Catch::Matchers::Contains;
using hbos::slam::Evaluation;
using hbos::slam::PlotParams;
using hbos::slam::Trajectory;

namespace {

struct Fixture {
  Trajectory gt = hbos::slam::read_tum_trajectory(
      hbos::slam::test::eval_data("data/tum_trajectories_evo/freiburg1_xyz-groundtruth.txt"));
  Trajectory est = hbos::slam::read_tum_trajectory(
      hbos::slam::test::eval_data("data/tum_trajectories_evo/freiburg1_xyz-rgbdslam.txt"));
  Evaluation evaluation = hbos::slam::evaluate(gt, est);
};

int count_colour(const cv::Mat& image, const cv::Vec3b& colour, int tolerance) {
  int n = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b p = image.at<cv::Vec3b>(r, c);
      if (std::abs(p[0] - colour[0]) <= tolerance && std::abs(p[1] - colour[1]) <= tolerance &&
          std::abs(p[2] - colour[2]) <= tolerance) {
        ++n;
      }
    }
  }
  return n;
}

// Pixels far from grey: only the estimate, the colour bar and coloured lines are.
int count_saturated(const cv::Mat& image) {
  int n = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b p = image.at<cv::Vec3b>(r, c);
      const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      if (spread > 80) ++n;
    }
  }
  return n;
}

cv::Vec3b turbo(int index) {
  cv::Mat one(1, 1, CV_8UC1, cv::Scalar(index));
  cv::Mat coloured;
  cv::applyColorMap(one, coloured, cv::COLORMAP_TURBO);
  return coloured.at<cv::Vec3b>(0, 0);
}

}  // namespace

TEST_CASE("top view shows ground truth, coloured estimate and colour bar", "[eval][plot]") {
  const Fixture f;
  PlotParams params;
  const cv::Mat image = hbos::slam::draw_top_view(f.gt, f.evaluation, params);
  REQUIRE(image.type() == CV_8UC3);
  CHECK(image.cols == params.width);
  CHECK(image.rows == params.height);
  CHECK(count_colour(image, {110, 110, 110}, 4) > 300);  // the ground-truth line
  CHECK(count_saturated(image) > 5000);                  // estimate + colour bar
  // The colour bar: a column right of the plot whose pixels run through the whole colour map,
  // from its low end to its high end.
  std::vector<cv::Vec3b> map;
  for (int i = 0; i < 256; ++i) map.push_back(turbo(i));
  const auto map_index = [&](const cv::Vec3b& p) {
    for (int i = 0; i < 256; ++i) {
      if (cv::norm(p, map[static_cast<std::size_t>(i)]) < 8.0) return i;
    }
    return -1;
  };
  bool found_bar = false;
  for (int c = params.width - 130; c < params.width && !found_bar; ++c) {
    int in_map = 0;
    int lowest = 255;
    int highest = 0;
    for (int r = 0; r < params.height; ++r) {
      const int i = map_index(image.at<cv::Vec3b>(r, c));
      if (i < 0) continue;
      ++in_map;
      lowest = std::min(lowest, i);
      highest = std::max(highest, i);
    }
    found_bar = in_map > 300 && lowest <= 5 && highest >= 250;
  }
  CHECK(found_bar);
}

TEST_CASE("error-over-time plots show the series and the RMSE / mean / median lines",
          "[eval][plot]") {
  const Fixture f;
  const cv::Mat ate = hbos::slam::draw_ate_over_time(f.gt, f.evaluation);
  CHECK(count_colour(ate, {190, 100, 30}, 10) > 1000);  // the series
  CHECK(count_colour(ate, {40, 40, 215}, 10) > 300);    // RMSE, dashed
  CHECK(count_colour(ate, {50, 150, 50}, 10) > 300);    // mean
  CHECK(count_colour(ate, {0, 140, 250}, 10) > 300);    // median
  const cv::Mat rpe = hbos::slam::draw_rpe_over_time(f.gt, f.est, f.evaluation);
  CHECK(count_colour(rpe, {190, 100, 30}, 10) > 1000);
  CHECK(count_colour(rpe, {40, 40, 215}, 10) > 600);  // one RMSE line per panel
}

TEST_CASE("write_plots writes decodable PNGs atomically into a new directory", "[eval][plot]") {
  const Fixture f;
  hbos::slam::test::ScratchDir scratch;
  const std::string dir = scratch.file("nested/plots");
  const std::vector<std::string> written = hbos::slam::write_plots(dir, f.gt, f.est, f.evaluation);
  REQUIRE(written.size() == 3);
  for (const std::string& path : written) {
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    INFO(path);
    CHECK(image.cols == 1000);
    CHECK(image.rows == 760);
  }
  CHECK(std::distance(std::filesystem::directory_iterator(dir),
                      std::filesystem::directory_iterator()) == 3);  // no temporaries left

  hbos::slam::EvaluationParams no_rpe;
  no_rpe.rpe = false;
  const Evaluation without = hbos::slam::evaluate(f.gt, f.est, no_rpe);
  CHECK(hbos::slam::write_plots(scratch.file("ate_only"), f.gt, f.est, without).size() == 2);
  CHECK_THROWS_WITH(hbos::slam::draw_rpe_over_time(f.gt, f.est, without), Contains("no RPE"));

  std::ofstream(scratch.file("a_file")) << "x";
  CHECK_THROWS_AS(hbos::slam::write_plots(scratch.file("a_file"), f.gt, f.est, f.evaluation),
                  std::runtime_error);
}

TEST_CASE("plots of a perfect estimate (all errors 0) are drawn too", "[eval][plot]") {
  const Trajectory gt = hbos::slam::test::synthetic_trajectory(300, 0.0, 0.01);
  const Evaluation perfect = hbos::slam::evaluate(gt, gt);
  REQUIRE(perfect.ate.stats.max < 1e-12);
  hbos::slam::test::ScratchDir scratch;
  CHECK(hbos::slam::write_plots(scratch.file("p"), gt, gt, perfect).size() == 3);
  PlotParams side;
  side.plane = hbos::slam::PlotPlane::kYZ;
  const cv::Mat yz = hbos::slam::draw_top_view(gt, perfect, side);
  const cv::Mat xy = hbos::slam::draw_top_view(gt, perfect);
  CHECK(cv::norm(yz, xy, cv::NORM_L1) > 0.0);  // another projection, another picture
}

TEST_CASE("plots refuse bad parameters and mismatched trajectories", "[eval][plot]") {
  const Fixture f;
  PlotParams tiny;
  tiny.width = 10;
  CHECK_THROWS_WITH(hbos::slam::draw_top_view(f.gt, f.evaluation, tiny), Contains("width"));
  PlotParams no_gaps;
  no_gaps.gap_factor = 0.5;
  CHECK_THROWS_WITH(hbos::slam::draw_ate_over_time(f.gt, f.evaluation, no_gaps),
                    Contains("gap_factor"));
  CHECK_THROWS_WITH(hbos::slam::draw_top_view(f.est, f.evaluation),
                    Contains("ground truth of 3000 poses"));
}
