// The screen's centred magnitudes are the formula of residual_field.hpp on the field the screen
// reports, m_i = |r_i - c(p_i)| / sigma_i (with a stereo match's third component), bit for bit:
// every screen that forms them (the default, the magnitude-only screen, the paper's), raw and
// whitened, with octave sigmas, clipping, residuals that overflow (the largest magnitude,
// rejected), float and double. A faster path for them must keep these bits.

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace {

template <class Scalar>
bool same_bits(Scalar a, Scalar b) {
  return std::memcmp(&a, &b, sizeof(Scalar)) == 0;
}

/// The magnitude of match i by the formula, one match at a time, under the screen's field.
template <class Scalar>
Scalar expected_magnitude(const hbos::Matches<Scalar>& m, const hbos::ResidualField<Scalar>& f,
                          Eigen::Index i, const hbos::HbosScreen& s) {
  const Eigen::Matrix<Scalar, 2, 1> c = f.at(m.predicted(i));
  Eigen::Matrix<Scalar, 2, 1> d = m.residual(i) - c;
  const Scalar right = m.has_right(i) ? m.right_residual(i) - c.x() : Scalar(0);
  Scalar mag = std::sqrt(d.squaredNorm() + right * right);
  if (s.residuals.whiten) {
    mag /= m.sigma(i);
    d /= m.sigma(i);
  }
  if (!std::isfinite(mag) || !d.allFinite()) mag = std::numeric_limits<Scalar>::max();
  const auto clip = static_cast<Scalar>(s.magnitude_clip);
  return clip > Scalar(0) ? std::min(mag, clip) : mag;
}

/// A frame of n matches over a 640 x 480 image: a pose error's field (offset, roll and zoom),
/// octave sigmas, a person of 15 % offset by 12 px, 3 % gross mismatches; `stereo` adds a right
/// coordinate to every fourth match, `huge` puts two matches where the residual overflows.
template <class Scalar>
hbos::Matches<Scalar> frame(int n, std::uint32_t seed, bool stereo, bool huge) {
  using V = Eigen::Matrix<Scalar, 2, 1>;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0.0, 640.0), y(0.0, 480.0), unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_int_distribution<int> octave(0, 7);
  const double roll = 0.002 * (unit(rng) - 0.5), zoom = 0.003 * (unit(rng) - 0.5);
  const V offset(static_cast<Scalar>(3.0 * noise(rng)), static_cast<Scalar>(3.0 * noise(rng)));
  hbos::Matches<Scalar> m;
  for (int i = 0; i < n; ++i) {
    const double u = x(rng), v = y(rng);
    const double sigma = std::pow(1.2, octave(rng));
    double ru = offset.x() - roll * (v - 240.0) + zoom * (u - 320.0) + sigma * noise(rng);
    double rv = offset.y() + roll * (u - 320.0) + zoom * (v - 240.0) + sigma * noise(rng);
    const double draw = unit(rng);
    if (draw < 0.15) ru += 12.0;
    if (draw > 0.97) {
      ru += 200.0 * (unit(rng) - 0.5);
      rv += 200.0 * (unit(rng) - 0.5);
    }
    const V p(static_cast<Scalar>(u), static_cast<Scalar>(v));
    const V o(static_cast<Scalar>(u + ru), static_cast<Scalar>(v + rv));
    if (stereo && i % 4 == 0) {
      const auto right = static_cast<Scalar>(u - 20.0);
      m.add_stereo(p, o, right, static_cast<Scalar>(right + ru + noise(rng)),
                   static_cast<Scalar>(sigma));
    } else {
      m.add(p, o, static_cast<Scalar>(sigma));
    }
    m.set_depth(m.size() - 1, static_cast<Scalar>(1.0 + 3.0 * unit(rng)));
  }
  if (huge) {
    const Scalar big = std::numeric_limits<Scalar>::max() / Scalar(2);
    m.add(V(-big, Scalar(10)), V(big, Scalar(10)));  // r = 2 big: overflows to inf
    m.add(V(Scalar(5), -big), V(Scalar(5), big));
  }
  return m;
}

}  // namespace

TEMPLATE_TEST_CASE("centred magnitudes: the reported field's formula bit for bit",
                   "[screen][magnitude]", float, double) {
  using Scalar = TestType;
  struct Named {
    const char* name;
    hbos::HbosScreen screen;
    bool clip_beyond_cut;  // an overflowed match is then rejected
  };
  hbos::HbosScreen raw = hbos::HbosScreen::magnitude_only();
  raw.residuals.whiten = false;
  hbos::HbosScreen tight;
  tight.magnitude_clip = 2.0;  // many matches at the clip
  // (A clip of 2 lies inside the noise gate: clipped, even an overflowed match is kept.)
  const Named screens[] = {{"default", hbos::HbosScreen{}, true},
                           {"magnitude only", hbos::HbosScreen::magnitude_only(), true},
                           {"raw pixels", raw, true},
                           {"paper (raw, uncentred, unclipped)", hbos::HbosScreen::paper(), true},
                           {"default, clip 2", tight, false}};
  int checked = 0;
  for (const Named& named : screens) {
    hbos::ReprojectionScreen<Scalar> screen(hbos::ScreenConfig{named.screen});
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
      const int n = 7 + static_cast<int>(seed) * 83;
      for (const bool stereo : {false, true}) {
        for (const bool huge : {false, true}) {
          const hbos::Matches<Scalar> m = frame<Scalar>(n, seed, stereo, huge);
          const hbos::ScreenResult<Scalar>& r = screen.screen(m);
          int mismatched = 0;
          for (Eigen::Index i = 0; i < m.size(); ++i) {
            const Scalar want = expected_magnitude(m, r.field(), i, named.screen);
            mismatched += same_bits(r.magnitude(i), want) ? 0 : 1;
          }
          INFO(named.name << ", seed " << seed << ", stereo " << stereo << ", huge " << huge);
          CHECK(mismatched == 0);
          ++checked;
          if (huge && named.clip_beyond_cut) {
            // The overflowed match: the largest magnitude, clipped, never NaN; rejected.
            const Eigen::Index last = m.size() - 1;
            const Scalar clip = static_cast<Scalar>(named.screen.magnitude_clip);
            CHECK(r.magnitude(last) ==
                  (clip > Scalar(0) ? clip : std::numeric_limits<Scalar>::max()));
            CHECK_FALSE(r.inlier(last));
          }
        }
      }
    }
  }
  CHECK(checked == 5 * 12 * 4);
}
