// measure_orb_noise: how precise are ORB keypoints, in units of their scale sigma = 1.2^octave?
//
// The synthetic scenes of the screening study draw keypoint noise as noise_px * sigma per axis;
// this program measures noise_px on real frames. For each consecutive pair of the TUM fr1/xyz
// frames: ORB (1000 features, scale 1.2, 8 levels, as ORB-SLAM2), brute-force Hamming matching
// with cross-check, back-projection of the first frame's keypoints through its depth, a pose from
// solvePnPRansac (3 px) refined by Levenberg-Marquardt on the RANSAC inliers, then the residuals
// of all matches under that pose, whitened by 1.2^octave. Gross errors (> 6 px/sigma) are dropped
// and the noise is the robust sigma 1.4826 * median |component|, per octave and overall.
//
//   measure_orb_noise [DATA_DIR]    (default ../shared/data/tum_fr1_xyz_first37)

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> read_list(const std::string& path) {
  std::vector<std::string> files;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') files.push_back(line.substr(line.find(' ') + 1));
  return files;
}

double robust_sigma(std::vector<double> components) {
  for (double& c : components) c = std::fabs(c);
  const auto mid = components.begin() + static_cast<std::ptrdiff_t>(components.size() / 2);
  std::nth_element(components.begin(), mid, components.end());
  return 1.4826 * *mid;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir =
      (argc > 1 ? std::string(argv[1]) : "../shared/data/tum_fr1_xyz_first37") + "/";
  const std::vector<std::string> rgb = read_list(dir + "rgb.txt");
  const std::vector<std::string> depth = read_list(dir + "depth.txt");
  if (rgb.size() < 2 || rgb.size() != depth.size()) {
    std::fprintf(stderr, "measure_orb_noise: no frame lists in %s\n", dir.c_str());
    return 1;
  }
  // TUM fr1 intrinsics and distortion (ORB-SLAM2's TUM1.yaml); depth scale 5000 per metre.
  const double fx = 517.306408, fy = 516.469215, cx = 318.643040, cy = 255.313989;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << fx, 0, cx, 0, fy, cy, 0, 0, 1);
  const cv::Mat D = (cv::Mat_<double>(1, 5) << 0.262383, -0.953104, -0.005358, 0.002628, 1.163314);
  auto orb = cv::ORB::create(1000, 1.2f, 8);
  std::vector<std::vector<double>> per_octave(8);

  for (std::size_t f = 0; f + 1 < rgb.size(); ++f) {
    const cv::Mat g0 = cv::imread(dir + rgb[f], cv::IMREAD_GRAYSCALE);
    const cv::Mat g1 = cv::imread(dir + rgb[f + 1], cv::IMREAD_GRAYSCALE);
    const cv::Mat d0 = cv::imread(dir + depth[f], cv::IMREAD_UNCHANGED);
    if (g0.empty() || g1.empty() || d0.empty()) {
      std::fprintf(stderr, "measure_orb_noise: cannot read frame %zu\n", f);
      return 1;
    }
    std::vector<cv::KeyPoint> k0, k1;
    cv::Mat x0, x1;
    orb->detectAndCompute(g0, cv::noArray(), k0, x0);
    orb->detectAndCompute(g1, cv::noArray(), k1, x1);
    std::vector<cv::DMatch> matches;
    cv::BFMatcher(cv::NORM_HAMMING, true).match(x0, x1, matches);

    std::vector<cv::Point2f> p0, p1;
    for (const auto& m : matches) {
      p0.push_back(k0[static_cast<std::size_t>(m.queryIdx)].pt);
      p1.push_back(k1[static_cast<std::size_t>(m.trainIdx)].pt);
    }
    std::vector<cv::Point2f> u0, u1;
    cv::undistortPoints(p0, u0, K, D, cv::noArray(), K);
    cv::undistortPoints(p1, u1, K, D, cv::noArray(), K);
    std::vector<cv::Point3f> points;
    std::vector<cv::Point2f> observed;
    std::vector<int> octave;
    for (std::size_t i = 0; i < matches.size(); ++i) {
      const int x = cvRound(p0[i].x), y = cvRound(p0[i].y);
      if (x < 0 || y < 0 || x >= d0.cols || y >= d0.rows) continue;
      const double z = d0.at<std::uint16_t>(y, x) / 5000.0;
      if (z <= 0.1) continue;
      points.emplace_back(static_cast<float>((u0[i].x - cx) * z / fx),
                          static_cast<float>((u0[i].y - cy) * z / fy), static_cast<float>(z));
      observed.push_back(u1[i]);
      octave.push_back(k1[static_cast<std::size_t>(matches[i].trainIdx)].octave);
    }
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    if (points.size() < 10 || !cv::solvePnPRansac(points, observed, K, cv::noArray(), rvec, tvec,
                                                  false, 200, 3.0f, 0.99, inliers))
      continue;
    std::vector<cv::Point3f> in_points;
    std::vector<cv::Point2f> in_observed;
    for (int i : inliers) {
      in_points.push_back(points[static_cast<std::size_t>(i)]);
      in_observed.push_back(observed[static_cast<std::size_t>(i)]);
    }
    cv::solvePnPRefineLM(in_points, in_observed, K, cv::noArray(), rvec, tvec);
    std::vector<cv::Point2f> projected;
    cv::projectPoints(points, rvec, tvec, K, cv::noArray(), projected);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double sigma = std::pow(1.2, octave[i]);
      const double ex = (observed[i].x - projected[i].x) / sigma;
      const double ey = (observed[i].y - projected[i].y) / sigma;
      if (std::hypot(ex, ey) > 6.0) continue;
      auto& bucket = per_octave[static_cast<std::size_t>(std::clamp(octave[i], 0, 7))];
      bucket.push_back(ex);
      bucket.push_back(ey);
    }
  }
  std::vector<double> all;
  std::printf("| octave | matches | noise [px/sigma] |\n|---|---|---|\n");
  for (std::size_t o = 0; o < per_octave.size(); ++o) {
    if (per_octave[o].size() < 20) continue;
    std::printf("| %zu | %zu | %.3f |\n", o, per_octave[o].size() / 2, robust_sigma(per_octave[o]));
    all.insert(all.end(), per_octave[o].begin(), per_octave[o].end());
  }
  if (all.empty()) return 1;
  std::printf("| all | %zu | %.3f |\n", all.size() / 2, robust_sigma(all));
  return 0;
}
