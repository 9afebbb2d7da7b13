#include "render/writer.hpp"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

namespace hbos::render {
namespace fs = std::filesystem;

std::string format_stamp(double stamp) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", stamp);
  return buf;
}

namespace {

void write_png(const fs::path& p, const cv::Mat& m) {
  if (!cv::imwrite(p.string(), m, {cv::IMWRITE_PNG_COMPRESSION, 1})) {
    throw OutputError("cannot write image " + p.string());
  }
}

void write_text(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
  f.close();
  if (!f) throw OutputError("cannot write " + p.string());
}

std::string pose_line(double stamp, const Pose& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %.6f %.6f %.6f %.7f %.7f %.7f %.7f\n",
                format_stamp(stamp).c_str(), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  return buf;
}

nlohmann::json describe(const SequenceRenderer& r) {
  const auto& o = r.options();
  const auto& s = r.scenario();
  nlohmann::json j;
  j["renderer"] = "hbos-render";
  j["renderer_version"] = kRendererVersion;
  j["scenario"] = s.name;
  j["description"] = s.description;
  j["seed"] = o.seed;
  j["frames"] = r.frame_count();
  j["rate_hz"] = o.rate;
  j["first_stamp"] = format_stamp(r.poses().front().stamp);
  j["trajectory"] = {
      {"source", "TUM RGB-D fr3 ground truth, data/trajectories/" + s.trajectory_file},
      {"resampling", "linear position, slerp rotation between ground-truth stamps"},
      {"pose_convention", "camera-to-world, room frame (z up, floor z = 0)"}};
  const Pose& off = r.room_from_mocap();
  const Eigen::Quaterniond q(off.linear());
  j["room_from_mocap"] = {
      {"translation", {off.translation().x(), off.translation().y(), off.translation().z()}},
      {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
  j["intrinsics"] = {{"fx", o.K.fx}, {"fy", o.K.fy},       {"cx", o.K.cx},
                     {"cy", o.K.cy}, {"width", o.K.width}, {"height", o.K.height}};
  j["depth"] = {
      {"scale_units_per_m", o.kinect.depth_scale},
      {"noise", "sigma_z = 0.0012 + 0.0019 (z - 0.4)^2 m (Nguyen et al. 2012)"},
      {"range_m", {o.kinect.min_range, o.kinect.max_range}},
      {"holes", "0 = no return: out of range, grazing incidence, projector shadow, edges"}};
  nlohmann::json people = nlohmann::json::array();
  for (std::size_t i = 0; i < s.people.size(); ++i) {
    const auto& p = s.people[i];
    people.push_back({{"id", i + 1},
                      {"role", p.role},
                      {"carries_object", p.carries},
                      {"speed_m_s", p.speed},
                      {"outfit", p.look}});
  }
  j["people"] = people;
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t c = 0; c < r.carried_ids().size(); ++c) {
    int by = 0;
    for (std::size_t i = 0, n = 0; i < s.people.size(); ++i) {
      if (s.people[i].carries && n++ == c) by = static_cast<int>(i) + 1;
    }
    objects.push_back({{"id", r.carried_ids()[c]}, {"kind", "carried box"}, {"carried_by", by}});
  }
  j["objects"] = objects;
  j["object_ids"] =
      "objects/<stamp>.png, 8-bit: 0 static background, 1..k people, k+1.. carried objects";
  const MaskPlan& m = r.mask_plan();
  j["masks"] = {
      {"convention", "DynaSLAM: 8-bit, 0 = dynamic, 255 = static (any non-zero = static)"},
      {"variants",
       {{"perfect", "every pixel of a person or carried object (object id != 0)"},
        {"eroded", {{"radius_px", {m.erode_min_px, m.erode_max_px}}, {"per_frame", "seeded"}}},
        {"dilated", {{"radius_px", {m.dilate_min_px, m.dilate_max_px}}, {"per_frame", "seeded"}}},
        {"missing", {{"rate", m.missing_rate}, {"frames", m.missing_frames}}},
        {"delayed", "the previous frame's perfect mask (frame 0: all static)"},
        {"boxes", "each object id's bounding box filled"},
        {"object_unmasked", {{"ids_never_masked", m.carried_ids}}},
        {"person_missed",
         {{"person_id", m.missed_person},
          {"first_frame", m.missed_first},
          {"last_frame", m.missed_last}}}}}};
  return j;
}

// True when `dir` is a folder holding nothing but what write_sequence writes: the only kind of
// folder it ever deletes (a finished output it replaces, or its own unfinished temporary one).
bool only_render_output(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec) || fs::is_symlink(dir, ec)) return false;
  static const std::set<std::string> kNames = {
      "rgb",       "depth",           "objects",          "masks",        "rgb.txt",
      "depth.txt", "groundtruth.txt", "associations.txt", "scenario.json"};
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (kNames.count(it->path().filename().string()) == 0) return false;
  return !ec;
}

// Refuses an output path whose replacement could delete what is not ours.
void check_output_path(const fs::path& out, bool overwrite) {
  fs::path normal = out.lexically_normal();
  if (!normal.has_filename()) normal = normal.parent_path();  // "a/b/" names the folder b
  const std::string name = normal.filename().string();
  if (out.empty() || name.empty() || name == "." || name == ".." || normal == normal.root_path())
    throw OutputError("output folder '" + out.string() +
                      "' names no folder of its own: give a new folder's name");
  std::error_code ec;
  if (fs::exists(out, ec)) {
    if (!overwrite)
      throw OutputError("output folder " + out.string() +
                        " already exists (pass --overwrite to replace it)");
    if (!fs::is_directory(out, ec))
      throw OutputError("cannot replace " + out.string() + ": it is not a folder");
    if (fs::exists(out / "scenario.json", ec) == false || !only_render_output(out))
      throw OutputError("refusing to replace " + out.string() +
                        ": it holds files hbos-render did not write (only a previous "
                        "hbos-render output is replaced by --overwrite)");
    if (fs::equivalent(out, fs::current_path(ec), ec))
      throw OutputError("refusing to replace " + out.string() + ": it is the current folder");
  }
  fs::path tmp = out;
  tmp += ".tmp";
  if (fs::exists(tmp, ec) && !only_render_output(tmp))
    throw OutputError("cannot use " + tmp.string() +
                      " for the unfinished output: it exists and holds files hbos-render did "
                      "not write; move it away");
}

// Renders every frame into `tmp`, then replaces `out` with it.
WriteStats write_into(SequenceRenderer& r, const fs::path& tmp, const fs::path& out,
                      const Progress& progress, const volatile std::sig_atomic_t* stop,
                      std::chrono::steady_clock::time_point t0) {
  using Clock = std::chrono::steady_clock;
  std::error_code ec;
  const auto& variants = mask_variant_names();
  for (const char* d : {"rgb", "depth", "objects"}) {
    fs::create_directories(tmp / d, ec);
    if (ec) throw OutputError("cannot create " + (tmp / d).string() + ": " + ec.message());
  }
  for (const auto& v : variants) {
    fs::create_directories(tmp / "masks" / v, ec);
    if (ec)
      throw OutputError("cannot create " + (tmp / "masks" / v).string() + ": " + ec.message());
  }
  const std::string origin = "hbos-render " + std::string(kRendererVersion) + " scenario " +
                             r.scenario().name + " seed " + std::to_string(r.options().seed);
  std::string rgb_txt = "# color images\n# file: '" + origin + "'\n# timestamp filename\n";
  std::string depth_txt = "# depth maps\n# file: '" + origin + "'\n# timestamp filename\n";
  std::string gt_txt =
      "# ground truth trajectory\n# file: '" + origin + "'\n# timestamp tx ty tz qx qy qz qw\n";
  std::string assoc;
  WriteStats stats;
  cv::Mat previous_ids;
  const int n = r.frame_count();
  for (int i = 0; i < n; ++i) {
    if (stop != nullptr && *stop != 0)
      throw Interrupted("interrupted after " + std::to_string(i) + " of " + std::to_string(n) +
                        " frames; nothing was written to " + out.string());
    const auto tr = Clock::now();
    Frame f = r.render(i);
    stats.render_seconds += std::chrono::duration<double>(Clock::now() - tr).count();
    const std::string st = format_stamp(f.stamp);
    write_png(tmp / "rgb" / (st + ".png"), f.rgb);
    write_png(tmp / "depth" / (st + ".png"), f.depth);
    write_png(tmp / "objects" / (st + ".png"), f.truth.object_id);
    for (const auto& v : variants) {
      write_png(tmp / "masks" / v / (st + ".png"),
                make_mask(v, r.mask_plan(), i, f.truth.object_id, previous_ids));
    }
    previous_ids = f.truth.object_id;
    rgb_txt += st + " rgb/" + st + ".png\n";
    depth_txt += st + " depth/" + st + ".png\n";
    assoc += st + " rgb/" + st + ".png " + st + " depth/" + st + ".png\n";
    gt_txt += pose_line(f.stamp, f.pose);
    ++stats.frames;
    if (progress) progress(i + 1, n);
  }
  // The index files last: a reader that finds rgb.txt finds every image it lists.
  write_text(tmp / "groundtruth.txt", gt_txt);
  write_text(tmp / "depth.txt", depth_txt);
  write_text(tmp / "associations.txt", assoc);
  nlohmann::json j = describe(r);
  j["gl_renderer"] = r.gl_name();
  write_text(tmp / "scenario.json", j.dump(2) + "\n");
  write_text(tmp / "rgb.txt", rgb_txt);
  if (fs::exists(out, ec)) {
    fs::remove_all(out, ec);
    if (ec) throw OutputError("cannot replace " + out.string() + ": " + ec.message());
  }
  fs::rename(tmp, out, ec);
  if (ec)
    throw OutputError("cannot rename " + tmp.string() + " to " + out.string() + ": " +
                      ec.message());
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return stats;
}

}  // namespace

WriteStats write_sequence(SequenceRenderer& r, const fs::path& out, bool overwrite,
                          const Progress& progress, const volatile std::sig_atomic_t* stop) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  check_output_path(out, overwrite);
  std::error_code ec;
  fs::path tmp = out;
  tmp += ".tmp";
  fs::remove_all(tmp, ec);
  if (ec) throw OutputError("cannot remove stale " + tmp.string() + ": " + ec.message());
  try {
    return write_into(r, tmp, out, progress, stop, t0);
  } catch (...) {
    // Nothing half-written stays behind: <out> is either absent, the old one, or complete.
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace hbos::render
