#include "frontend/camera.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <nlohmann/json.hpp>

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace hbos::slam {

namespace {

// The keys a camera file may set, in the order they are reported.
constexpr const char* kKeys[] = {"fx", "fy", "cx", "cy", "k1",
                                 "k2", "p1", "p2", "k3", "depth_factor"};

// "Camera.fx" and "fx" mean the same; ORB-SLAM2 calls the depth scale DepthMapFactor.
std::string canonical_key(std::string key) {
  if (key.rfind("Camera.", 0) == 0) key = key.substr(7);
  if (key == "DepthMapFactor") key = "depth_factor";
  return key;
}

bool is_known_key(const std::string& key) {
  return std::find_if(std::begin(kKeys), std::end(kKeys),
                      [&](const char* k) { return key == k; }) != std::end(kKeys);
}

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

constexpr double kMinFocalPx = 1.0;        // [px]
constexpr double kMaxFocalPx = 1e6;        // [px]
constexpr double kMaxDistortion = 1000.0;  // [-]
constexpr double kMaxDepthFactor = 1e9;    // [raw units / m]

/// A value as written, in double quotes unless the file already quoted it.
std::string quoted(const std::string& text) {
  const bool has_quotes = text.size() >= 2 && (text.front() == '"' || text.front() == '\'') &&
                          text.back() == text.front();
  return has_quotes ? text : "\"" + text + "\"";
}

/// Throws unless `path` is a readable regular file (a directory would open and then fail).
void require_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InvalidArgument(fmt::format("camera file '{}' is a directory", path));
  }
  const bool exists = std::filesystem::exists(path, error);
  if (error) {  // e.g. a loop of symbolic links: not "does not exist"
    throw InvalidArgument(fmt::format("camera file '{}': {}", path, error.message()));
  }
  if (!exists) {
    throw InvalidArgument(fmt::format("camera file '{}' does not exist", path));
  }
}

// Fills the model from key -> (value, where) and checks it; `where` already names file:line.
CameraModel build_camera(const std::string& name,
                         const std::map<std::string, std::pair<double, std::string>>& values) {
  CameraModel c;
  c.name = name;
  std::map<std::string, double*> fields = {{"fx", &c.fx}, {"fy", &c.fy},
                                           {"cx", &c.cx}, {"cy", &c.cy},
                                           {"k1", &c.k1}, {"k2", &c.k2},
                                           {"p1", &c.p1}, {"p2", &c.p2},
                                           {"k3", &c.k3}, {"depth_factor", &c.depth_factor}};
  for (const char* required : {"fx", "fy", "cx", "cy"}) {
    if (values.count(required) == 0) {
      throw InvalidArgument(
          fmt::format("{}: missing field '{}' (camera files need fx, fy, cx, cy)", name, required));
    }
  }
  for (const auto& [key, entry] : values) {
    const auto& [value, where] = entry;
    if (!std::isfinite(value)) {
      throw InvalidArgument(fmt::format("{}: field '{}' is not finite", where, key));
    }
    if ((key == "fx" || key == "fy") && !(value >= kMinFocalPx && value <= kMaxFocalPx)) {
      throw InvalidArgument(fmt::format(
          "{}: field '{}' = {:g} px is not a plausible focal length (legal: [1, 1e6] px)", where,
          key, value));
    }
    // Below 1 a raw depth unit would be longer than a metre (a 16-bit map would then measure
    // tens of kilometres); 1e-300 made every depth 1e300 m and the run went on.
    if (key == "depth_factor" && !(value >= 1.0 && value <= kMaxDepthFactor)) {
      throw InvalidArgument(fmt::format(
          "{}: field '{}' = {:g} must lie in [1, 1e9] (raw depth units per metre; TUM: 5000)",
          where, key, value));
    }
    if ((key[0] == 'k' || key[0] == 'p') && !(std::abs(value) <= kMaxDistortion)) {
      throw InvalidArgument(fmt::format(
          "{}: distortion coefficient '{}' = {:g} is not plausible (legal: |{}| <= 1000)", where,
          key, value, key));
    }
    *fields.at(key) = value;
  }
  return c;
}

CameraModel load_yaml_camera(const std::string& path) {
  require_file(path);
  std::ifstream in(path);
  if (!in) throw InvalidArgument(fmt::format("cannot open camera file '{}'", path));
  std::map<std::string, std::pair<double, std::string>> values;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    // A UTF-8 byte order mark (some editors write one) is not part of the first key.
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    const std::string where = fmt::format("{}:{}", path, number);
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const std::string text = trim(line);
    if (text.empty() || text[0] == '%' || text.rfind("---", 0) == 0) continue;
    const auto colon = text.find(':');
    if (colon == std::string::npos) {
      throw InvalidArgument(fmt::format("{}: expected 'key: value', got \"{}\"", where, text));
    }
    const std::string key = canonical_key(trim(text.substr(0, colon)));
    if (!is_known_key(key)) continue;  // e.g. ORBextractor.nFeatures in an ORB-SLAM2 file
    const std::string value_text = trim(text.substr(colon + 1));
    char* end = nullptr;
    const double value = std::strtod(value_text.c_str(), &end);
    if (value_text.empty() || end != value_text.c_str() + value_text.size()) {
      throw InvalidArgument(
          fmt::format("{}: field '{}' is not a number: {}", where, key, quoted(value_text)));
    }
    if (values.count(key) != 0) {
      throw InvalidArgument(
          fmt::format("{}: field '{}' repeats {}", where, key, values[key].second));
    }
    values[key] = {value, where};
  }
  return build_camera(path, values);
}

CameraModel load_json_camera(const std::string& path) {
  require_file(path);
  std::ifstream in(path);
  if (!in) throw InvalidArgument(fmt::format("cannot open camera file '{}'", path));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  nlohmann::json j;
  // nlohmann keeps the last of two equal keys without a word; the YAML reader refuses them.
  std::set<std::string> top_keys;
  const auto refuse_duplicates = [&](int depth, nlohmann::json::parse_event_t event,
                                     nlohmann::json& parsed) {
    if (depth == 1 && event == nlohmann::json::parse_event_t::key &&
        !top_keys.insert(parsed.get<std::string>()).second) {
      throw InvalidArgument(
          fmt::format("{}: field '{}' appears twice", path, parsed.get<std::string>()));
    }
    return true;
  };
  try {
    j = nlohmann::json::parse(text, refuse_duplicates);
  } catch (const nlohmann::json::parse_error& e) {
    const auto upto = std::min(text.size(), e.byte == 0 ? std::size_t{0} : e.byte - 1);
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(upto), '\n');
    throw InvalidArgument(fmt::format("{}:{}: not valid JSON: {}", path, line, e.what()));
  } catch (const nlohmann::json::exception& e) {
    // E.g. out_of_range 406 for a number beyond a double (517.3e6408): no byte position.
    throw InvalidArgument(fmt::format("{}: not readable as camera JSON: {}", path, e.what()));
  }
  if (!j.is_object()) throw InvalidArgument(fmt::format("{}: expected a JSON object", path));
  std::map<std::string, std::pair<double, std::string>> values;
  for (const auto& [raw_key, value] : j.items()) {
    const std::string key = canonical_key(raw_key);
    if (!is_known_key(key)) continue;
    const std::string where = fmt::format("{}: field '{}'", path, raw_key);
    if (!value.is_number()) {
      throw InvalidArgument(fmt::format("{} is not a number: {}", where, value.dump()));
    }
    if (values.count(key) != 0) {
      throw InvalidArgument(fmt::format("{} repeats another spelling of '{}'", where, key));
    }
    values[key] = {value.get<double>(), path};
  }
  return build_camera(path, values);
}

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

}  // namespace

bool CameraModel::has_distortion() const {
  return k1 != 0.0 || k2 != 0.0 || p1 != 0.0 || p2 != 0.0 || k3 != 0.0;
}

cv::Matx33d CameraModel::camera_matrix() const { return {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0}; }

cv::Mat CameraModel::distortion_coefficients() const {
  return (cv::Mat_<double>(1, 5) << k1, k2, p1, p2, k3);
}

hbos::PinholeCamerad CameraModel::pinhole() const {
  hbos::PinholeCamerad p;
  p.fx = fx;
  p.fy = fy;
  p.cx = cx;
  p.cy = cy;
  return p;
}

CameraModel camera_preset(const std::string& name) {
  CameraModel c;
  c.name = name;
  if (name == "tum1") {  // ORB-SLAM2 Examples/RGB-D/TUM1.yaml
    c.fx = 517.306408;
    c.fy = 516.469215;
    c.cx = 318.643040;
    c.cy = 255.313989;
    c.k1 = 0.262383;
    c.k2 = -0.953104;
    c.p1 = -0.005358;
    c.p2 = 0.002628;
    c.k3 = 1.163314;
    return c;
  }
  if (name == "tum3") {  // ORB-SLAM2 Examples/RGB-D/TUM3.yaml: the fr3 images are undistorted
    c.fx = 535.4;
    c.fy = 539.2;
    c.cx = 320.1;
    c.cy = 247.6;
    return c;
  }
  throw InvalidArgument("camera preset '" + name + "' is not one of tum1, tum3");
}

CameraModel load_camera(const std::string& preset_or_path) {
  const std::string ext = lower_extension(preset_or_path);
  if (ext == "json") return load_json_camera(preset_or_path);
  if (ext == "yaml" || ext == "yml") return load_yaml_camera(preset_or_path);
  if (ext.empty()) return camera_preset(preset_or_path);
  throw InvalidArgument("camera '" + preset_or_path +
                        "' is neither a preset (tum1, tum3) nor a .yaml/.yml/.json file");
}

void check_camera_fits_image(const CameraModel& camera, int width, int height,
                             const std::string& image) {
  const bool inside =
      camera.cx >= 0.0 && camera.cx <= width && camera.cy >= 0.0 && camera.cy <= height;
  if (!inside) {
    throw InvalidArgument(fmt::format(
        "camera '{}': principal point (cx, cy) = ({:g}, {:g}) px lies outside the {}x{} image "
        "'{}' (legal: [0, {}] x [0, {}])",
        camera.name, camera.cx, camera.cy, width, height, image, width, height));
  }
}

std::vector<cv::Point2f> undistort_pixels(const CameraModel& camera,
                                          const std::vector<cv::Point2f>& distorted) {
  if (!camera.has_distortion() || distorted.empty()) return distorted;
  std::vector<cv::Point2f> undistorted;
  // P = K maps the normalised, undistorted coordinates back to pixels of the same camera.
  cv::undistortPoints(distorted, undistorted, camera.camera_matrix(),
                      camera.distortion_coefficients(), cv::noArray(), camera.camera_matrix());
  return undistorted;
}

}  // namespace hbos::slam
