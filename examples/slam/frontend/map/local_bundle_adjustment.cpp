#include "frontend/map/local_bundle_adjustment.hpp"

#include <hbos/error.hpp>
#include <hbos/screening/pose_refinement.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::slam {

namespace {

using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix63 = Eigen::Matrix<double, 6, 3>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// ORB-SLAM2's outlier gates: the 95 % quantiles of chi2 with 2 and 3 degrees of freedom.
constexpr double kChi2Mono = 5.991;
constexpr double kChi2Depth = 7.815;

// [m] A predicted depth at or below this counts as behind the camera: the projection's Jacobian
// grows as 1/z^2 and a point at the optical centre has no pixel at all.
constexpr double kMinDepth = 1e-6;

// A point's 3x3 block whose smallest eigenvalue is below this share of its largest is singular.
// One observation without depth leaves the ray's direction with exactly no information (about
// 1e-16 of the rest after rounding); two views 3 mm apart of a point 4 m away still give ~1e-7.
constexpr double kMinPointConditioning = 1e-10;

// Marquardt's damping: the diagonal scaled by (1 + lambda), so rotations [rad], translations and
// points [m] are damped each in its own units. The start is near Gauss-Newton, as a local map
// starts from poses the tracker already refined.
constexpr double kInitialLambda = 1e-5;
constexpr double kMinLambda = 1e-12;
constexpr double kMaxLambda = 1e12;
// Failed steps tried per iteration, each with ten times the damping, before giving up: the cost
// is then at a minimum to within rounding.
constexpr int kMaxTries = 10;
// A diagonal entry with no information (a free keyframe no active observation reaches) is damped
// as if it had this much, so the reduced system stays invertible and that keyframe's step is 0.
constexpr double kDiagonalFloor = 1e-9;
constexpr double kRelativeDecrease = 1e-6;  // stop below this relative fall of the cost

std::size_t at(int index) { return static_cast<std::size_t>(index); }

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

double huber_cost(double chi2, double width) {
  if (width <= 0.0) return chi2;
  const double norm = std::sqrt(chi2);
  return norm <= width ? chi2 : 2.0 * width * norm - width * width;
}

// IRLS weight of the Huber loss: its derivative with respect to chi2.
double huber_weight(double chi2, double width) {
  if (width <= 0.0) return 1.0;
  const double norm = std::sqrt(chi2);
  return norm <= width ? 1.0 : width / norm;
}

void validate(const std::vector<BundleKeyframe>& keyframes, const std::vector<BundlePoint>& points,
              const std::vector<BundleObservation>& observations,
              const hbos::PinholeCamerad& camera, const BundleAdjustmentConfig& config) {
  using hbos::detail::require;
  hbos::detail::validate(camera);
  require(config.iterations >= 1, "BundleAdjustmentConfig iterations must be >= 1, got ",
          config.iterations);
  require(std::isfinite(config.huber_mono) && config.huber_mono >= 0.0,
          "BundleAdjustmentConfig huber_mono must be finite and >= 0, got ", config.huber_mono);
  require(std::isfinite(config.huber_depth) && config.huber_depth >= 0.0,
          "BundleAdjustmentConfig huber_depth must be finite and >= 0, got ", config.huber_depth);
  require(std::isfinite(config.disparity_sigma_px) && config.disparity_sigma_px >= 0.0,
          "BundleAdjustmentConfig disparity_sigma_px must be finite and >= 0 (0: the keypoint's "
          "sigma), got ",
          config.disparity_sigma_px);
  require(!config.use_depth || (std::isfinite(config.baseline_fx) && config.baseline_fx > 0.0),
          "BundleAdjustmentConfig baseline_fx must be finite and > 0 with use_depth, got ",
          config.baseline_fx);
  bool any_fixed = false;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const Eigen::Isometry3d& T = keyframes[i].T_camera_world;
    require(T.matrix().allFinite(), "keyframes[", i, "].T_camera_world must be finite");
    const double off =
        (T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    // Looser than rounding, tighter than any rotation a tracker could mean.
    require(off <= 1e-6, "keyframes[", i,
            "].T_camera_world rotation must be orthonormal, R^T R - I reaches ", off);
    any_fixed = any_fixed || keyframes[i].fixed;
  }
  for (std::size_t j = 0; j < points.size(); ++j) {
    require(points[j].position_world.allFinite(), "points[", j, "].position_world must be finite");
  }
  const auto n_keyframes = static_cast<long long>(keyframes.size());
  const auto n_points = static_cast<long long>(points.size());
  for (std::size_t o = 0; o < observations.size(); ++o) {
    const BundleObservation& ob = observations[o];
    require(ob.keyframe >= 0 && ob.keyframe < n_keyframes, "observations[", o,
            "].keyframe must index the ", n_keyframes, " keyframes, got ", ob.keyframe);
    require(ob.point >= 0 && ob.point < n_points, "observations[", o, "].point must index the ",
            n_points, " points, got ", ob.point);
    require(ob.pixel.allFinite(), "observations[", o, "].pixel must be finite, got (", ob.pixel.x(),
            ", ", ob.pixel.y(), ")");
    require(std::isfinite(ob.sigma) && ob.sigma > 0.0, "observations[", o,
            "].sigma must be finite and > 0, got ", ob.sigma);
    require(std::isfinite(ob.depth_m) && ob.depth_m >= 0.0, "observations[", o,
            "].depth_m must be finite and >= 0 (0 = none), got ", ob.depth_m);
  }
  require(observations.empty() || any_fixed, "no keyframe is fixed among ", keyframes.size(),
          ": the map's position and orientation would be free (fix at least one)");
}

struct PassSummary {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  bool converged = false;
};

// The state and every buffer the adjustment needs, sized once: an iteration allocates nothing.
class BundleSolver {
 public:
  BundleSolver(const std::vector<BundleKeyframe>& keyframes, const std::vector<BundlePoint>& points,
               const std::vector<BundleObservation>& observations,
               const hbos::PinholeCamerad& camera, const BundleAdjustmentConfig& config)
      : camera_(camera), config_(config) {
    const std::size_t n_obs = observations.size();
    free_.assign(keyframes.size(), -1);
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      poses_.push_back(keyframes[i].T_camera_world);
      if (!keyframes[i].fixed) free_[i] = n_free_++;
    }
    trial_poses_ = poses_;
    for (const BundlePoint& p : points) positions_.push_back(p.position_world);
    trial_positions_ = positions_;

    keyframe_.resize(n_obs);
    point_.resize(n_obs);
    measured_.resize(n_obs);
    inv_sigma_.resize(n_obs);
    inv_sigma_depth_.resize(n_obs);
    has_depth_.resize(n_obs);
    active_.assign(n_obs, 0);
    W_.resize(n_obs);
    WV_.resize(n_obs);
    std::vector<std::size_t> count(points.size() + 1, 0);
    for (std::size_t o = 0; o < n_obs; ++o) {
      const BundleObservation& ob = observations[o];
      keyframe_[o] = at(ob.keyframe);
      point_[o] = at(ob.point);
      has_depth_[o] = config.use_depth && ob.depth_m > 0.0 ? 1 : 0;
      const double disparity = has_depth_[o] != 0 ? config.baseline_fx / ob.depth_m : 0.0;
      measured_[o] = Eigen::Vector3d(ob.pixel.x(), ob.pixel.y(), disparity);
      inv_sigma_[o] = 1.0 / ob.sigma;
      inv_sigma_depth_[o] =
          config.disparity_sigma_px > 0.0 ? 1.0 / config.disparity_sigma_px : inv_sigma_[o];
      ++count[point_[o] + 1];
    }
    // Observations grouped by point: the Schur complement pairs up those of one point.
    for (std::size_t j = 0; j < points.size(); ++j) count[j + 1] += count[j];
    point_begin_ = count;
    point_obs_.resize(n_obs);
    for (std::size_t o = 0; o < n_obs; ++o) point_obs_[count[point_[o]]++] = o;

    U_.resize(static_cast<std::size_t>(n_free_));
    gc_.resize(static_cast<std::size_t>(n_free_));
    V_.resize(points.size());
    gp_.resize(points.size());
    V_inv_.resize(points.size());
    solvable_.assign(points.size(), 0);
    const Eigen::Index n = 6 * n_free_;
    S_.resize(n, n);
    rhs_.resize(n);
    dc_.resize(n);
  }

  // Levenberg-Marquardt on the observations with use[o] set, from the current state.
  PassSummary optimise(const std::vector<std::uint8_t>& use) {
    PassSummary summary;
    double cost = 0.0;
    std::size_t in_front = 0;
    evaluate(poses_, positions_, use, cost, in_front);
    summary.initial_cost = cost;
    double lambda = kInitialLambda;
    for (int it = 0; it < config_.iterations; ++it) {
      if (cost <= 0.0) {  // an exact fit: nothing left to lower
        summary.converged = true;
        break;
      }
      linearise(use);
      ++summary.iterations;
      bool accepted = false;
      double trial_cost = 0.0;
      for (int attempt = 0; attempt < kMaxTries && !accepted; ++attempt) {
        std::size_t trial_in_front = 0;
        if (solve(lambda)) {
          evaluate(trial_poses_, trial_positions_, use, trial_cost, trial_in_front);
          // A step that pushes points behind a camera would lower the cost by losing terms.
          accepted = trial_cost < cost && trial_in_front >= in_front;
          if (accepted) in_front = trial_in_front;
        }
        lambda =
            accepted ? std::max(lambda / 10.0, kMinLambda) : std::min(lambda * 10.0, kMaxLambda);
      }
      if (!accepted) {
        summary.converged = true;
        break;
      }
      const double decrease = (cost - trial_cost) / cost;
      commit();
      cost = trial_cost;
      if (decrease < kRelativeDecrease) {
        summary.converged = true;
        break;
      }
    }
    summary.final_cost = cost;
    return summary;
  }

  // 1 where the observation is behind its camera or above its chi2 gate at the current state.
  void mark_outliers(std::vector<std::uint8_t>& outlier) const {
    Eigen::Vector3d p_c;
    Eigen::Vector3d e;
    for (std::size_t o = 0; o < outlier.size(); ++o) {
      if (!whitened_residual(poses_[keyframe_[o]], positions_[point_[o]], o, p_c, e)) {
        outlier[o] = 1;
        continue;
      }
      const double gate = has_depth_[o] != 0 ? kChi2Depth : kChi2Mono;
      outlier[o] = e.squaredNorm() > gate ? 1 : 0;
    }
  }

  void write_back(std::vector<BundleKeyframe>& keyframes, std::vector<BundlePoint>& points) const {
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      if (free_[i] >= 0) keyframes[i].T_camera_world = poses_[i];
    }
    for (std::size_t j = 0; j < points.size(); ++j) points[j].position_world = positions_[j];
  }

 private:
  double huber_width(std::size_t o) const {
    return has_depth_[o] != 0 ? config_.huber_depth : config_.huber_mono;
  }

  // e = (measured - predicted) / sigma, third row 0 without depth. False when behind the camera.
  bool whitened_residual(const Eigen::Isometry3d& T, const Eigen::Vector3d& X, std::size_t o,
                         Eigen::Vector3d& p_c, Eigen::Vector3d& e) const {
    p_c = T * X;
    if (!(p_c.z() > kMinDepth)) return false;  // also catches a NaN
    const double inv_z = 1.0 / p_c.z();
    const double u = camera_.fx * p_c.x() * inv_z + camera_.cx;
    const double v = camera_.fy * p_c.y() * inv_z + camera_.cy;
    const Eigen::Vector3d& m = measured_[o];
    e.x() = (m.x() - u) * inv_sigma_[o];
    e.y() = (m.y() - v) * inv_sigma_[o];
    e.z() = has_depth_[o] != 0 ? (m.z() - config_.baseline_fx * inv_z) * inv_sigma_depth_[o] : 0.0;
    return true;
  }

  void evaluate(const std::vector<Eigen::Isometry3d>& poses,
                const std::vector<Eigen::Vector3d>& positions, const std::vector<std::uint8_t>& use,
                double& cost, std::size_t& in_front) const {
    cost = 0.0;
    in_front = 0;
    Eigen::Vector3d p_c;
    Eigen::Vector3d e;
    for (std::size_t o = 0; o < use.size(); ++o) {
      if (use[o] == 0) continue;
      if (!whitened_residual(poses[keyframe_[o]], positions[point_[o]], o, p_c, e)) continue;
      ++in_front;
      cost += huber_cost(e.squaredNorm(), huber_width(o));
    }
  }

  // The Huber-weighted normal equations at the current state, block by block: U (pose-pose),
  // V (point-point), W (pose-point, one per observation) and the gradients gc, gp.
  void linearise(const std::vector<std::uint8_t>& use) {
    for (Matrix6& U : U_) U.setZero();
    for (Vector6& g : gc_) g.setZero();
    for (Eigen::Matrix3d& V : V_) V.setZero();
    for (Eigen::Vector3d& g : gp_) g.setZero();
    const double fx = camera_.fx;
    const double fy = camera_.fy;
    const double bf = config_.baseline_fx;
    Eigen::Vector3d p_c;
    Eigen::Vector3d e;
    for (std::size_t o = 0; o < use.size(); ++o) {
      active_[o] = 0;
      if (use[o] == 0) continue;
      const Eigen::Isometry3d& T = poses_[keyframe_[o]];
      if (!whitened_residual(T, positions_[point_[o]], o, p_c, e)) continue;
      active_[o] = 1;
      const double w = huber_weight(e.squaredNorm(), huber_width(o));
      const double inv_z = 1.0 / p_c.z();
      const double inv_z2 = inv_z * inv_z;
      // d(prediction)/d(p_c), whitened; the disparity bf/z varies along z alone.
      Eigen::Matrix3d J_proj;
      J_proj << fx * inv_z, 0.0, -fx * p_c.x() * inv_z2,  //
          0.0, fy * inv_z, -fy * p_c.y() * inv_z2,        //
          0.0, 0.0, -bf * inv_z2;
      if (has_depth_[o] == 0) J_proj.row(2).setZero();
      J_proj.topRows<2>() *= inv_sigma_[o];
      J_proj.row(2) *= inv_sigma_depth_[o];
      const Eigen::Matrix3d J_point = J_proj * T.linear();  // d p_c / d X = R
      const std::size_t j = point_[o];
      V_[j].noalias() += w * J_point.transpose() * J_point;
      gp_[j].noalias() += w * J_point.transpose() * e;
      const int f = free_[keyframe_[o]];
      if (f < 0) continue;
      // Left perturbation: p_c <- exp(delta) p_c, so d p_c / d(rotation, translation) = [-[p_c]x,
      // I].
      Matrix36 J_pose;
      J_pose.leftCols<3>().noalias() = -J_proj * skew(p_c);
      J_pose.rightCols<3>() = J_proj;
      U_[at(f)].noalias() += w * J_pose.transpose() * J_pose;
      gc_[at(f)].noalias() += w * J_pose.transpose() * e;
      W_[o].noalias() = w * J_pose.transpose() * J_point;
    }
    for (std::size_t j = 0; j < V_.size(); ++j) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
      eigen.computeDirect(V_[j], Eigen::EigenvaluesOnly);
      const Eigen::Vector3d& ev = eigen.eigenvalues();  // ascending
      solvable_[j] = ev(2) > 0.0 && ev(0) > kMinPointConditioning * ev(2) ? 1 : 0;
    }
  }

  // One damped step into trial_poses_ / trial_positions_. False when the solve failed.
  bool solve(double lambda) {
    S_.setZero();
    for (std::size_t f = 0; f < U_.size(); ++f) {
      const auto r = 6 * static_cast<Eigen::Index>(f);
      Matrix6 U = U_[f];
      U.diagonal() += lambda * U.diagonal().cwiseMax(kDiagonalFloor);
      S_.block<6, 6>(r, r) = U;
      rhs_.segment<6>(r) = gc_[f];
    }
    // Reduced camera system: S = U - sum_j W_j V_j^-1 W_j^T, rhs = gc - sum_j W_j V_j^-1 gp_j.
    for (std::size_t j = 0; j < V_.size(); ++j) {
      if (solvable_[j] == 0) continue;
      Eigen::Matrix3d V = V_[j];
      V.diagonal() += lambda * V.diagonal().cwiseMax(kDiagonalFloor);
      V_inv_[j] = V.inverse();
      for (std::size_t a = point_begin_[j]; a < point_begin_[j + 1]; ++a) {
        const std::size_t oa = point_obs_[a];
        const int fa = free_[keyframe_[oa]];
        if (active_[oa] == 0 || fa < 0) continue;
        const Eigen::Index ra = 6 * static_cast<Eigen::Index>(fa);
        WV_[oa].noalias() = W_[oa] * V_inv_[j];
        rhs_.segment<6>(ra).noalias() -= WV_[oa] * gp_[j];
        for (std::size_t b = a; b < point_begin_[j + 1]; ++b) {
          const std::size_t ob = point_obs_[b];
          const int fb = free_[keyframe_[ob]];
          if (active_[ob] == 0 || fb < 0) continue;
          const Eigen::Index rb = 6 * static_cast<Eigen::Index>(fb);
          const Matrix6 block = WV_[oa] * W_[ob].transpose();
          S_.block<6, 6>(ra, rb) -= block;
          if (b != a) S_.block<6, 6>(rb, ra) -= block.transpose();
        }
      }
    }
    if (n_free_ > 0) {
      ldlt_.compute(S_);
      if (ldlt_.info() != Eigen::Success) return false;
      dc_ = ldlt_.solve(rhs_);
      if (!dc_.allFinite()) return false;
    }
    for (std::size_t i = 0; i < poses_.size(); ++i) {
      const int f = free_[i];
      if (f < 0) continue;
      const Vector6 delta = dc_.segment<6>(6 * static_cast<Eigen::Index>(f));
      Eigen::Isometry3d update = Eigen::Isometry3d::Identity();
      update.linear() = hbos::detail::so3_exp<double>(delta.head<3>());
      update.translation() = delta.tail<3>();  // first order in the translation
      trial_poses_[i] = update * poses_[i];
    }
    // Back-substitution: dp_j = V_j^-1 (gp_j - sum W^T dc).
    for (std::size_t j = 0; j < V_.size(); ++j) {
      if (solvable_[j] == 0) {
        trial_positions_[j] = positions_[j];
        continue;
      }
      Eigen::Vector3d g = gp_[j];
      for (std::size_t a = point_begin_[j]; a < point_begin_[j + 1]; ++a) {
        const std::size_t o = point_obs_[a];
        const int f = free_[keyframe_[o]];
        if (active_[o] == 0 || f < 0) continue;
        g.noalias() -= W_[o].transpose() * dc_.segment<6>(6 * static_cast<Eigen::Index>(f));
      }
      const Eigen::Vector3d step = V_inv_[j] * g;
      if (!step.allFinite()) return false;
      trial_positions_[j] = positions_[j] + step;
    }
    return true;
  }

  void commit() {
    for (std::size_t i = 0; i < poses_.size(); ++i) {
      if (free_[i] >= 0) poses_[i] = trial_poses_[i];
    }
    positions_ = trial_positions_;  // same size: copies, no allocation
  }

  hbos::PinholeCamerad camera_;
  BundleAdjustmentConfig config_;

  int n_free_ = 0;
  std::vector<int> free_;  // per keyframe: its block in the reduced system, -1 = fixed
  std::vector<Eigen::Isometry3d> poses_, trial_poses_;
  std::vector<Eigen::Vector3d> positions_, trial_positions_;

  // Per observation.
  std::vector<std::size_t> keyframe_, point_;
  std::vector<Eigen::Vector3d> measured_;  // (u, v, bf / depth)
  std::vector<double> inv_sigma_, inv_sigma_depth_;
  std::vector<std::uint8_t> has_depth_;
  std::vector<std::uint8_t> active_;  // used and in front in the last linearisation
  std::vector<Matrix63> W_, WV_;

  // Per point: its observations point_obs_[point_begin_[j] .. point_begin_[j + 1]).
  std::vector<std::size_t> point_begin_, point_obs_;
  std::vector<Eigen::Matrix3d> V_, V_inv_;
  std::vector<Eigen::Vector3d> gp_;
  std::vector<std::uint8_t> solvable_;

  // Per free keyframe, and the reduced system over them.
  std::vector<Matrix6> U_;
  std::vector<Vector6> gc_;
  Eigen::MatrixXd S_;
  Eigen::VectorXd rhs_, dc_;
  // Sized by its first compute(), reused after. Not built with LDLT(n): that constructor leaves
  // its status unset, and moving it into place reads it (UBSan reports an invalid enum value).
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

}  // namespace

BundleAdjustmentResult adjust_bundle(std::vector<BundleKeyframe>& keyframes,
                                     std::vector<BundlePoint>& points,
                                     const std::vector<BundleObservation>& observations,
                                     const hbos::PinholeCamerad& camera,
                                     const BundleAdjustmentConfig& config) {
  validate(keyframes, points, observations, camera, config);
  BundleSolver solver(keyframes, points, observations, camera, config);
  BundleAdjustmentResult result;
  result.outlier.assign(observations.size(), 0);
  std::vector<std::uint8_t> use(observations.size(), 1);
  PassSummary pass = solver.optimise(use);
  result.initial_cost = pass.initial_cost;
  result.iterations = pass.iterations;
  if (config.reject_outliers) {
    solver.mark_outliers(result.outlier);
    for (std::size_t o = 0; o < use.size(); ++o) use[o] = result.outlier[o] != 0 ? 0 : 1;
    pass = solver.optimise(use);
    result.iterations += pass.iterations;
  }
  solver.mark_outliers(result.outlier);
  result.final_cost = pass.final_cost;
  result.converged = pass.converged;
  solver.write_back(keyframes, points);
  return result;
}

}  // namespace hbos::slam
