// The front end's mask distances (examples/slam/frontend/mask_distance.hpp) for 1000 keypoints
// of a 640 x 480 frame, against OpenCV's whole-image exact distance transform in the same run
// (docs/slam_demo.md, "The mask's neighbourhood"). Built only with the SLAM example.
#include <benchmark/benchmark.h>

#include "frontend/mask_distance.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace {

struct Frame {
  cv::Mat mask{480, 640, CV_8U, cv::Scalar(0)};
  std::vector<cv::Point2f> keypoints;
  Frame() {
    // A person-sized mask and keypoints spread over the image, some near it.
    mask(cv::Rect(200, 100, 150, 300)).setTo(255);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> x(0.f, 639.f), y(0.f, 479.f);
    for (int i = 0; i < 1000; ++i) keypoints.emplace_back(x(rng), y(rng));
  }
};

void BM_windowed_scan(benchmark::State& state) {
  const Frame f;
  for (auto _ : state) {
    const hbos::slam::MaskDistance d(f.mask, 10.0);
    double sum = 0.0;
    for (const cv::Point2f& p : f.keypoints) {
      const double v = d.at(p);
      sum += std::isfinite(v) ? v : 0.0;
    }
    benchmark::DoNotOptimize(sum);
  }
}

void BM_distance_transform(benchmark::State& state) {
  const Frame f;
  cv::Mat unmasked, distance;
  for (auto _ : state) {
    cv::compare(f.mask, 0, unmasked, cv::CMP_EQ);
    cv::distanceTransform(unmasked, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    double sum = 0.0;
    for (const cv::Point2f& p : f.keypoints) {
      const float v = distance.at<float>(cvRound(p.y), cvRound(p.x));
      sum += v <= 10.f ? v : 0.0;
    }
    benchmark::DoNotOptimize(sum);
  }
}

}  // namespace

BENCHMARK(BM_windowed_scan)
    ->Name("mask_distance/frame_of_1000/windowed_scan")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_distance_transform)
    ->Name("mask_distance/frame_of_1000/distance_transform")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
