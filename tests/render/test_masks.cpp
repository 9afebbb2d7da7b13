// Each mask variant does what its name says, on rendered frames and on edge cases.
#include <catch2/catch.hpp>

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "render/masks.hpp"
#include "render/sequence.hpp"

using namespace hbos::render;

namespace {

cv::Mat dynamic(const cv::Mat& mask) { return mask == kMaskDynamic; }
int count(const cv::Mat& m) { return cv::countNonZero(m); }
// a is a subset of b (both 0/255).
bool subset(const cv::Mat& a, const cv::Mat& b) { return count(a & ~b) == 0; }
bool equal(const cv::Mat& a, const cv::Mat& b) { return count(a != b) == 0; }
bool all_static(const cv::Mat& mask) { return count(mask != kMaskStatic) == 0; }

}  // namespace

TEST_CASE("mask variants on rendered frames") {
  SequenceOptions o;
  o.scenario = "walking_xyz";
  o.people = 3;
  o.frames = 60;
  o.seed = 4;
  SequenceRenderer r(o);
  const MaskPlan& plan = r.mask_plan();
  REQUIRE(r.carried_ids() == std::vector<int>{4});  // 3 people, the first carries object id 4
  REQUIRE(plan.missed_person >= 1);
  REQUIRE(plan.missed_person <= 3);
  cv::Mat prev_ids;
  int frames_with_people = 0, frames_with_object = 0;
  for (int i = 0; i < r.frame_count(); i += 3) {
    const cv::Mat ids = r.render_truth(i).object_id;
    const cv::Mat prev = i > 0 ? r.render_truth(i - 1).object_id : cv::Mat();
    auto mask = [&](const char* v) { return make_mask(v, plan, i, ids, prev); };
    const cv::Mat perfect = dynamic(mask("perfect"));
    CHECK(equal(perfect, ids != 0));
    if (count(perfect) == 0) continue;
    ++frames_with_people;
    // eroded < perfect < dilated, strictly (the people are larger than the radii).
    const cv::Mat eroded = dynamic(mask("eroded")), dilated = dynamic(mask("dilated"));
    CHECK(subset(eroded, perfect));
    CHECK(count(eroded) < count(perfect));
    CHECK(subset(perfect, dilated));
    CHECK(count(dilated) > count(perfect));
    // boxes cover the silhouettes, and each id's bounding box is filled.
    const cv::Mat boxes = dynamic(mask("boxes"));
    CHECK(subset(perfect, boxes));
    for (int id = 1; id <= 4; ++id) {
      const cv::Mat sel = ids == id;
      if (count(sel) > 0) CHECK(count(~boxes(cv::boundingRect(sel))) == 0);
    }
    // missing: all static on the plan's frames, perfect elsewhere.
    const bool missing =
        std::binary_search(plan.missing_frames.begin(), plan.missing_frames.end(), i);
    if (missing) {
      CHECK(all_static(mask("missing")));
    } else {
      CHECK(equal(dynamic(mask("missing")), perfect));
    }
    // delayed: the previous frame's perfect mask.
    if (i == 0) {
      CHECK(all_static(mask("delayed")));
    } else {
      CHECK(equal(dynamic(mask("delayed")), prev != 0));
    }
    // object_unmasked: the carried box is never masked, everything else is.
    const cv::Mat unmasked = dynamic(mask("object_unmasked"));
    CHECK(count(unmasked & (ids == 4)) == 0);
    CHECK(equal(unmasked, (ids != 0) & (ids != 4)));
    if (count(ids == 4) > 0) ++frames_with_object;
    // person_missed: that person unmasked inside the stretch, perfect outside it.
    const cv::Mat missed = dynamic(mask("person_missed"));
    if (i >= plan.missed_first && i <= plan.missed_last) {
      CHECK(count(missed & (ids == plan.missed_person)) == 0);
      CHECK(equal(missed, (ids != 0) & (ids != plan.missed_person)));
    } else {
      CHECK(equal(missed, perfect));
    }
  }
  CHECK(frames_with_people >= 15);
  CHECK(frames_with_object >= 1);
}

TEST_CASE("the mask plan: missing frames at the documented rate, a stretch inside the sequence") {
  const MaskPlan p = MaskPlan::make(11, 900, 2, {3});
  // 15 % of 900 frames, within 4 standard deviations of a binomial.
  CHECK(p.missing_frames.size() > 90);
  CHECK(p.missing_frames.size() < 180);
  CHECK(std::is_sorted(p.missing_frames.begin(), p.missing_frames.end()));
  CHECK(p.missed_last - p.missed_first + 1 == 225);
  CHECK(p.missed_first >= 0);
  CHECK(p.missed_last < 900);
  const MaskPlan q = MaskPlan::make(12, 900, 2, {3});
  CHECK(q.missing_frames != p.missing_frames);
  // A short sequence: the stretch is at least 15 frames, never past the end.
  const MaskPlan s = MaskPlan::make(1, 10, 1, {});
  CHECK(s.missed_first == 0);
  CHECK(s.missed_last == 9);
  CHECK(s.missed_person == 1);
  CHECK_THROWS_AS(make_mask("nonsense", p, 0, cv::Mat::zeros(4, 4, CV_8U), cv::Mat()),
                  std::invalid_argument);
}
