// Tests of hbos/model.hpp: properties on many seeded data sets, input forms, threading and every
// bad input.

#include <hbos/model.hpp>
#include <hbos/threshold.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

// Every member of the class template compiles for both scalar types.
template class hbos::Hbos<float>;
template class hbos::Hbos<double>;

namespace {

using Matrix = Eigen::MatrixXd;

/// A seeded data set with features of different shapes and scales.
Matrix make_data(std::uint32_t seed, Eigen::Index n, Eigen::Index d) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::exponential_distribution<double> expo(0.5);
  std::uniform_real_distribution<double> uniform(-3.0, 7.0);
  Matrix x(n, d);
  for (Eigen::Index j = 0; j < d; ++j)
    for (Eigen::Index i = 0; i < n; ++i)
      x(i, j) = j % 3 == 0 ? normal(rng) * 4.0 + 1.0 : j % 3 == 1 ? expo(rng) : uniform(rng);
  return x;
}

/// The specs every property is checked under.
std::vector<hbos::HbosParams> all_modes() {
  std::vector<hbos::HbosParams> modes;
  modes.emplace_back();  // default: 5 bins x 5 shifts
  hbos::HbosParams p;
  p.feature.binning.shifts = 1;
  p.feature.binning.bins = 10;
  modes.push_back(p);  // classic static
  p.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  modes.push_back(p);  // dynamic
  p = {};
  p.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
  modes.push_back(p);
  p.feature.binning.rule = hbos::BinCountRule::FreedmanDiaconis;
  p.feature.tail = hbos::Tail::Upper;
  modes.push_back(p);
  return modes;
}

}  // namespace

TEST_CASE("contributions sum to the score", "[model][property]") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const Matrix x = make_data(seed, 200 + 37 * seed, 1 + seed % 5);
    for (const auto& params : all_modes()) {
      const auto model = hbos::Hbosd::fit(x, params);
      const Eigen::VectorXd scores = model.score(x);
      const Eigen::MatrixXd contributions = model.contributions(x);
      CHECK((contributions.rowwise().sum() - scores).cwiseAbs().maxCoeff() < 1e-12);
      CHECK(contributions.minCoeff() >= 0.0);
    }
  }
}

TEST_CASE("permuting features leaves the scores unchanged", "[model][property]") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const Matrix x = make_data(seed, 300, 4);
    Eigen::VectorXi order(4);
    order << 2, 0, 3, 1;
    Matrix permuted(x.rows(), 4);
    for (Eigen::Index j = 0; j < 4; ++j) permuted.col(j) = x.col(order(j));
    for (const auto& params : all_modes()) {
      const Eigen::VectorXd a = hbos::Hbosd::fit(x, params).score(x);
      const Eigen::VectorXd b = hbos::Hbosd::fit(permuted, params).score(permuted);
      CHECK((a - b).cwiseAbs().maxCoeff() < 1e-12);
    }
  }
}

TEST_CASE("scores are invariant under positive affine maps of any feature", "[model][property]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  std::uniform_real_distribution<double> offset(-50.0, 50.0);  // in units of the new scale
  for (std::uint32_t seed = 1; seed <= 25; ++seed) {
    const Matrix x = make_data(seed, 500, 3);
    Matrix mapped = x;
    for (Eigen::Index j = 0; j < 3; ++j) {
      const double a = std::pow(10.0, log_scale(rng));
      const double b = offset(rng) * a;  // larger offsets would round the data itself
      mapped.col(j) = (x.col(j).array() * a + b).matrix();
    }
    for (const auto& params : all_modes()) {
      const auto fitted = hbos::Hbosd::fit(x, params);
      const auto fitted_mapped = hbos::Hbosd::fit(mapped, params);
      const Eigen::VectorXd a = fitted.score(x);
      const Eigen::VectorXd b = fitted_mapped.score(mapped);
      INFO("seed " << seed);
      CHECK((a - b).cwiseAbs().maxCoeff() < 1e-9);
    }
  }
}

TEST_CASE("a sample in every feature's modal bin scores lowest", "[model][property]") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const Matrix x = make_data(seed, 400, 3);
    for (const auto& params : all_modes()) {
      const auto model = hbos::Hbosd::fit(x, params);
      const Eigen::VectorXd scores = model.score(x);
      bool any_modal = false;
      for (Eigen::Index i = 0; i < x.rows(); ++i) {
        bool modal = true;
        for (Eigen::Index j = 0; j < x.cols(); ++j)
          modal = modal && model.histogram(j).bin_of(x(i, j)) == model.histogram(j).mode();
        if (modal) {
          any_modal = true;
          CHECK(scores(i) == 0.0);
        }
      }
      CHECK(scores.minCoeff() >= 0.0);
      if (any_modal) CHECK(scores.minCoeff() == 0.0);
    }
  }
}

TEST_CASE("float and double agree", "[model][property]") {
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    const Matrix x = make_data(seed, 1000, 3);
    const Eigen::MatrixXf xf = x.cast<float>();
    for (const auto& params : all_modes()) {
      const Eigen::VectorXd sd = hbos::Hbosd::fit(x, params).score(x);
      const Eigen::VectorXf sf = hbos::Hbosf::fit(xf, params).score(xf);
      // Values within float rounding of a bin edge may land in the neighbouring bin; everything
      // else must agree to float precision.
      Eigen::Index differ = 0;
      for (Eigen::Index i = 0; i < x.rows(); ++i)
        differ += std::abs(sd(i) - static_cast<double>(sf(i))) > 1e-4 * (1.0 + sd(i)) ? 1 : 0;
      CHECK(differ <= 2);
    }
  }
}

TEST_CASE("maps, blocks and row-major buffers give the same scores", "[model]") {
  const Matrix x = make_data(5, 250, 3);
  const auto reference = hbos::Hbosd::fit(x).score(x);

  const Eigen::Map<const Matrix> map(x.data(), x.rows(), x.cols());
  CHECK(hbos::Hbosd::fit(map).score(map) == reference);

  Matrix wide(300, 5);
  wide.setZero();
  wide.block(10, 1, 250, 3) = x;
  const auto block = wide.block(10, 1, 250, 3);
  CHECK(hbos::Hbosd::fit(block).score(block) == reference);

  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = x;
  const auto model = hbos::Hbosd::fit_row_major(row_major.data(), 250, 3);
  CHECK(model.score_row_major(row_major.data(), 250, 3) == reference);

  Eigen::VectorXd into(250);
  model.score_into(x, into);
  CHECK(into == reference);
}

TEST_CASE("fit_and_score gives exactly fit + score, in every mode and input form",
          "[model][fit_and_score]") {
  // The fast path scores each training value from the bin it was counted in; the reference
  // looks every value up again. Bitwise equality is the "one interval convention" in action.
  auto modes = all_modes();
  hbos::HbosParams p;
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 0.37;
  p.feature.binning.shifts = 1;
  p.feature.tail = hbos::Tail::Lower;
  modes.push_back(p);  // fixed width anchored at 0, one-sided
  p = {};
  p.features = {hbos::angle_feature(12), hbos::default_feature(), hbos::default_feature()};
  modes.push_back(p);  // a periodic feature takes the lookup path, the others the indices
  p = {};
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 1e-4;
  p.feature.binning.shifts = 1;
  p.feature.binning.max_bins = 1 << 20;
  modes.push_back(p);  // > 65536 bins: too many for 16-bit indices, falls back to the lookup
  p = {};
  p.feature.binning.rule = hbos::BinCountRule::Sqrt;
  modes.push_back(p);

  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    const Eigen::Index n = 1 + static_cast<Eigen::Index>(seed * 97 % 1500);
    const Matrix x = make_data(seed, n, 3);
    for (std::size_t m = 0; m < modes.size(); ++m) {
      INFO("seed " << seed << ", mode " << m << ", n " << n);
      Eigen::VectorXd training(n);
      const auto model = hbos::Hbosd::fit_and_score(x, training, modes[m]);
      CHECK(training == model.score(x));
      CHECK(training == hbos::Hbosd::fit(x, modes[m]).score(x));
      for (Eigen::Index j = 0; j < 3; ++j)
        CHECK(model.histogram(j).counts() == hbos::Hbosd::fit(x, modes[m]).histogram(j).counts());
    }
  }

  // Blocks (strided columns), row-major buffers and float.
  const Matrix x = make_data(77, 300, 2);
  Matrix wide = Matrix::Zero(310, 4);
  wide.block(5, 1, 300, 2) = x;
  const Eigen::VectorXd reference = hbos::Hbosd::fit(x).score(x);
  Eigen::VectorXd training(300);
  (void)hbos::Hbosd::fit_and_score(wide.block(5, 1, 300, 2), training);
  CHECK(training == reference);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = x;
  (void)hbos::Hbosd::fit_and_score(row_major, training);
  CHECK(training == reference);
  const Eigen::MatrixXf xf = x.cast<float>();
  Eigen::VectorXf training_f(300);
  const auto model_f = hbos::Hbosf::fit_and_score(xf, training_f);
  CHECK(training_f == model_f.score(xf));

  Eigen::VectorXd wrong_size(7);
  CHECK_THROWS_WITH(hbos::Hbosd::fit_and_score(x, wrong_size),
                    Catch::Contains("7 entries for 300 rows"));
  Matrix bad = x;
  bad(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(hbos::Hbosd::fit_and_score(bad, training),
                    Catch::Contains("X(3, 1) is not finite"));
}

TEMPLATE_TEST_CASE("row-major data is fitted by rows, bit for bit the column-major fit",
                   "[model][fit_and_score][row_major]", float, double) {
  // Row-major data (numpy's C order) takes fit_rows_at_once: ranges in one sweep over the rows,
  // then every feature counted per block of rows. Its histograms, bin indices and scores must
  // be the per-feature fit's, for every feature count (the flat packet scan covers d dividing
  // its step, the row loop the rest), several blocks, padded rows, and every spec it accepts;
  // specs it refuses must still agree (they take the per-feature path).
  using Scalar = TestType;
  using ColMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  auto modes = all_modes();
  hbos::HbosParams p;
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 0.37;
  p.feature.binning.shifts = 3;
  modes.push_back(p);
  p = {};
  p.feature.binning.bins = 300;  // more bins than one byte indexes
  p.feature.binning.shifts = 1;
  modes.push_back(p);
  p = {};
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 2e-3;
  p.feature.binning.shifts = 1;
  p.feature.binning.max_bins = 1 << 20;
  modes.push_back(p);  // thousands of bins: counted a whole column at a time
  for (const Eigen::Index d : {2, 3, 4, 5, 8, 9, 16}) {
    for (const Eigen::Index n : {Eigen::Index{1}, Eigen::Index{7}, Eigen::Index{333},
                                 70001 / d + 13}) {  // the last spans several row blocks
      const ColMajor x = make_data(static_cast<std::uint32_t>(d * 31 + n), n, d).cast<Scalar>();
      const RowMajor rows = x;
      // Rows padded to a longer stride, as a slice of a wider C-order array.
      Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> wide(n, d + 3);
      wide.setConstant(Scalar(1e30));
      wide.leftCols(d) = x;
      const auto padded = wide.leftCols(d);
      for (std::size_t m = 0; m < modes.size(); ++m) {
        INFO("d " << d << ", n " << n << ", mode " << m);
        Vector reference(n), by_rows(n), by_padded_rows(n);
        const auto model = hbos::Hbos<Scalar>::fit_and_score(x, reference, modes[m]);
        const auto row_model = hbos::Hbos<Scalar>::fit_and_score(rows, by_rows, modes[m]);
        const auto padded_model =
            hbos::Hbos<Scalar>::fit_and_score(padded, by_padded_rows, modes[m]);
        CHECK(by_rows == reference);
        CHECK(by_padded_rows == reference);
        CHECK(reference == model.score(x));
        for (Eigen::Index j = 0; j < d; ++j) {
          CHECK(row_model.histogram(j).counts() == model.histogram(j).counts());
          CHECK(row_model.histogram(j).edges() == model.histogram(j).edges());
          CHECK(padded_model.histogram(j).counts() == model.histogram(j).counts());
        }
      }
    }
  }
  SECTION("a non-finite value is named as in the per-feature fit") {
    RowMajor rows = make_data(3, 500, 2).cast<Scalar>();
    rows(417, 1) = std::numeric_limits<Scalar>::infinity();
    Vector out(500);
    CHECK_THROWS_WITH(hbos::Hbos<Scalar>::fit_and_score(rows, out),
                      Catch::Contains("X(417, 1) is not finite"));
  }
}

namespace {

/// n x d values whose column j is of kind (j + offset) % 6: normal; a grid of the integers 0..10
/// and their neighbours one ulp away (on and beside the edges of 1, 2, 5 and 10 bins over
/// [0, 10]); a constant; ties of three values; values near the largest finite one (their range
/// overflows: binned scaled); subnormals (binned scaled too).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> awkward_data(std::uint32_t seed,
                                                                   Eigen::Index n, Eigen::Index d,
                                                                   Eigen::Index offset) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> pick(0, 10), side(-1, 1);
  std::uniform_real_distribution<double> unit(-0.9, 0.9);
  const Scalar big = std::numeric_limits<Scalar>::max();
  const Scalar tiny = std::numeric_limits<Scalar>::denorm_min();
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(n, d);
  for (Eigen::Index j = 0; j < d; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      Scalar v = 0;
      switch ((j + offset) % 6) {
        case 0:
          v = static_cast<Scalar>(normal(rng));
          break;
        case 1: {
          // 0 and 10 first, so that the range is [0, 10] whenever n >= 2.
          const int at = i < 2 ? static_cast<int>(10 * i) : pick(rng);
          v = static_cast<Scalar>(at);
          const int s = i < 2 ? 0 : side(rng);
          if (s != 0 && at + s >= 0 && at + s <= 10)
            v = std::nextafter(v, static_cast<Scalar>(at + s));
          break;
        }
        case 2:
          v = Scalar(3.25);
          break;
        case 3:
          v = static_cast<Scalar>(pick(rng) % 3) * Scalar(0.5);
          break;
        case 4:
          v = static_cast<Scalar>(unit(rng)) * big;
          break;
        default:
          v = static_cast<Scalar>(pick(rng)) * tiny;
      }
      x(i, j) = v;
    }
  }
  return x;
}

}  // namespace

TEMPLATE_TEST_CASE("C-order data gives the column-major fit and scores on awkward shapes",
                   "[model][fit_and_score][row_major]", float, double) {
  // numpy's C order reaches the library as a column-major map with an inner stride of d (the
  // Python module's Map) or as a row-major matrix; two features with few bins each take the
  // interleaved kernel (detail::interleaved_byte_bins_2), everything else the per-block or
  // per-feature paths. Every one must give the column-major fit's histograms and scores bit for
  // bit: feature counts 1, 2, 3, 5; row counts around the 16-row vectors and the 4080-row
  // chunks; values on the bin edges; constant, scaled and mixed columns; 1 to 300 bins.
  using Scalar = TestType;
  using Model = hbos::Hbos<Scalar>;
  using ColMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Strided = Eigen::Map<const ColMajor, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  auto fixed = [](Eigen::Index bins, Eigen::Index shifts) {
    hbos::HbosParams p;
    p.feature.binning.bins = bins;
    p.feature.binning.shifts = shifts;
    return p;
  };
  std::vector<hbos::HbosParams> modes = {fixed(10, 1), fixed(1, 1),  fixed(2, 1),  fixed(5, 3),
                                         fixed(16, 1), fixed(17, 1), fixed(300, 1)};
  modes.emplace_back();  // the default: 5 bins x 5 shifts, 25 fine bins
  hbos::HbosParams width;
  width.feature.binning.method = hbos::BinningMethod::FixedWidth;
  width.feature.binning.width = 1.0;
  width.feature.binning.shifts = 1;
  modes.push_back(width);

  auto check = [&](const ColMajor& x, const hbos::HbosParams& params) {
    const Eigen::Index n = x.rows(), d = x.cols();
    const RowMajor rows = x;
    const Strided strided(rows.data(), n, d, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, d));
    Vector reference(n), by_rows(n), by_map(n);
    // A spec the data cannot take (fixed width 1 over a range of 1e38) fails the same way.
    std::string refused;
    try {
      (void)Model::fit_and_score(x, reference, params);
    } catch (const hbos::InvalidArgument& e) {
      refused = e.what();
    }
    if (!refused.empty()) {
      CHECK_THROWS_WITH(Model::fit_and_score(rows, by_rows, params), refused);
      CHECK_THROWS_WITH(Model::fit_and_score(strided, by_map, params), refused);
      return;
    }
    const Model model = Model::fit_and_score(x, reference, params);
    const Model row_model = Model::fit_and_score(rows, by_rows, params);
    const Model map_model = Model::fit_and_score(strided, by_map, params);
    REQUIRE(reference == Model::fit(x, params).score(x));
    REQUIRE(by_rows == reference);
    REQUIRE(by_map == reference);
    REQUIRE(map_model.score(strided) == reference);
    for (Eigen::Index j = 0; j < d; ++j) {
      INFO("feature " << j);
      for (const Model* other : {&row_model, &map_model}) {
        REQUIRE(other->histogram(j).counts() == model.histogram(j).counts());
        REQUIRE(other->histogram(j).edges() == model.histogram(j).edges());
        REQUIRE(other->histogram(j).bin_contributions() == model.histogram(j).bin_contributions());
        REQUIRE(other->histogram(j).cap() == model.histogram(j).cap());
      }
    }
  };

  SECTION("every kind of column next to every other") {
    for (const Eigen::Index d : {1, 2, 3, 5}) {
      for (const Eigen::Index n : {1, 2, 15, 16, 17, 4080, 4081, 8161}) {
        for (Eigen::Index offset = 0; offset < 6; ++offset) {
          const ColMajor x =
              awkward_data<Scalar>(static_cast<std::uint32_t>(n * 7 + d), n, d, offset);
          for (std::size_t m = 0; m < modes.size(); ++m) {
            INFO("d " << d << ", n " << n << ", kinds from " << offset << ", mode " << m);
            check(x, modes[m]);
          }
          // Each feature its own bin count (16, 3, 6, 9, 12): the kernel's constants per lane.
          hbos::HbosParams mixed;
          for (Eigen::Index j = 0; j < d; ++j)
            mixed.features.push_back(fixed(16 - 13 * j % 16, 1).feature);
          INFO("d " << d << ", n " << n << ", kinds from " << offset << ", bins per feature");
          check(x, mixed);
        }
      }
    }
  }
  SECTION("a million rows and three, not a multiple of any block") {
    for (const Eigen::Index d : {1, 2, 3}) {
      const ColMajor x = awkward_data<Scalar>(5, 1000003, d, 0);
      for (const Eigen::Index bins : {10, 16}) {
        INFO("d " << d << ", bins " << bins);
        check(x, fixed(bins, 1));
      }
    }
  }
  SECTION("a non-finite value is named as in the column-major fit, wherever it is") {
    for (const Eigen::Index d : {1, 2, 3}) {
      for (const Eigen::Index at : {0, 15, 4095, 8000}) {
        for (const Scalar bad :
             {std::numeric_limits<Scalar>::quiet_NaN(), -std::numeric_limits<Scalar>::infinity()}) {
          RowMajor rows = awkward_data<Scalar>(9, 8161, d, 0);
          rows(at, d - 1) = bad;
          const Strided strided(rows.data(), rows.rows(), d,
                                Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, d));
          Vector out(rows.rows());
          const std::string where =
              "X(" + std::to_string(at) + ", " + std::to_string(d - 1) + ") is not finite";
          CHECK_THROWS_WITH(Model::fit_and_score(rows, out, fixed(10, 1)), Catch::Contains(where));
          CHECK_THROWS_WITH(Model::fit_and_score(strided, out, fixed(10, 1)),
                            Catch::Contains(where));
        }
      }
    }
  }
}

TEST_CASE("one fitted model scores from many threads", "[model][threads]") {
  const Matrix x = make_data(8, 2000, 4);
  const auto model = hbos::Hbosd::fit(x);
  const Eigen::VectorXd reference = model.score(x);
  std::vector<Eigen::VectorXd> results(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t)
    threads.emplace_back([&, t] {
      for (int repeat = 0; repeat < 5; ++repeat) results[t] = model.score(x);
    });
  for (auto& t : threads) t.join();
  for (const auto& r : results) CHECK(r == reference);
}

TEST_CASE("bad input throws InvalidArgument naming the problem", "[model][errors]") {
  const Matrix x = make_data(3, 50, 2);
  using hbos::InvalidArgument;
  CHECK_THROWS_AS(hbos::Hbosd::fit(Matrix(0, 2)), InvalidArgument);
  CHECK_THROWS_WITH(hbos::Hbosd::fit(Matrix(0, 2)), Catch::Contains("empty"));
  CHECK_THROWS_WITH(hbos::Hbosd::fit(Matrix(5, 0)), Catch::Contains("no features"));

  Matrix bad = x;
  bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(hbos::Hbosd::fit(bad), Catch::Contains("X(7, 1) is not finite"));
  bad(7, 1) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(hbos::Hbosd::fit(bad), Catch::Contains("X(7, 1) is not finite"));

  const auto model = hbos::Hbosd::fit(x);
  CHECK_THROWS_WITH(model.score(Matrix::Zero(3, 3)),
                    Catch::Contains("fitted on 2 features") && Catch::Contains("3 columns"));
  CHECK_THROWS_WITH(model.score(bad), Catch::Contains("not finite"));
  Eigen::VectorXd wrong_size(3);
  CHECK_THROWS_WITH(model.score_into(x, wrong_size), Catch::Contains("3 entries for 50 rows"));
  CHECK_THROWS_WITH(model.histogram(2), Catch::Contains("out of range"));

  hbos::HbosParams params;
  params.feature.binning.bins = 0;
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, params), Catch::Contains("bin count must be >= 1"));
  params = {};
  params.features.resize(3);
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, params),
                    Catch::Contains("3 specs") && Catch::Contains("2 features"));
  params = {};
  params.scoring.empty_bin_count = 0.0;
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, params), Catch::Contains("empty_bin_count"));
  params = {};
  params.scoring.range_tolerance = -1.0;
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, params), Catch::Contains("range_tolerance"));
  CHECK_THROWS_WITH(hbos::Hbosd::fit_row_major(nullptr, 3, 2), Catch::Contains("null"));

  // InvalidArgument is a std::invalid_argument, so generic handlers keep working.
  CHECK_THROWS_AS(hbos::Hbosd::fit(Matrix(0, 2)), std::invalid_argument);
}

TEST_CASE("per-feature specs: a periodic angle next to a one-sided magnitude", "[model]") {
  const double pi = 3.14159265358979323846;
  std::mt19937 rng(4);
  std::gamma_distribution<double> magnitude(2.0, 0.5);
  std::uniform_real_distribution<double> angle(-pi, pi);
  Matrix x(500, 2);
  for (Eigen::Index i = 0; i < 500; ++i) {
    x(i, 0) = magnitude(rng);
    x(i, 1) = angle(rng);
  }
  hbos::HbosParams params;
  params.features = {params.feature, hbos::angle_feature(12)};
  params.features[0].tail = hbos::Tail::Upper;
  const auto model = hbos::Hbosd::fit(x, params);
  CHECK(model.histogram(1).periodic());
  CHECK(model.histogram(0).tail() == hbos::Tail::Upper);
  Matrix probe(2, 2);
  probe << 0.0, 1.0,  // better than typical: the magnitude never penalises it
      50.0, 1.0;      // a gross residual: capped
  const Eigen::MatrixXd c = model.contributions(probe);
  CHECK(c(0, 0) == 0.0);
  CHECK(c(1, 0) == model.histogram(0).cap());
}

TEST_CASE("PyOD's edge-defect example scores the rare value highest", "[model][pyod]") {
  // docs/pyod_compat.md: 200 samples of 0..5 with counts 40, 1, 60, 50, 30, 19 and 5 plain bins
  // (edges 0..5, counts 40, 1, 60, 50, 49). PyOD scores the lone 1 with bin 0 and the commonest
  // value 2 with bin 1, so 2 scores highest and nothing is flagged. Here each value is scored from
  // the bin it was counted in: 1 scores log(60 / 1), 2 scores 0, and only the 1 is flagged.
  const int counts[] = {40, 1, 60, 50, 30, 19};
  Eigen::MatrixXd x(200, 1);
  Eigen::Index row = 0;
  for (int v = 0; v < 6; ++v)
    for (int c = 0; c < counts[v]; ++c) x(row++, 0) = v;
  hbos::HbosParams params;
  params.feature.binning.bins = 5;
  params.feature.binning.shifts = 1;
  const auto model = hbos::Hbosd::fit(x, params);
  CHECK(model.histogram(0).counts() == std::vector<Eigen::Index>{40, 1, 60, 50, 49});
  Eigen::MatrixXd probe(2, 1);
  probe << 1.0, 2.0;
  const Eigen::VectorXd s = model.score(probe);
  CHECK(s(0) == Approx(std::log(60.0)));
  CHECK(s(1) == 0.0);
  const Eigen::VectorXd scores = model.score(x);
  CHECK(scores.maxCoeff() == Approx(std::log(60.0)));
  CHECK(hbos::threshold_scores(scores, hbos::Contamination{0.1}).n_outliers() == 1);
}
