// Levenberg-Marquardt bundle adjustment of a camera rig (see rig_bundle_adjustment.hpp).
#include "vision/rig_bundle_adjustment.hpp"

#include <cmath>
#include <map>

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>

#include "core/log.hpp"

namespace finverse::vision {

namespace {

// Parameter layout: per camera its pose (6, not the root's) and intrinsics (fx fy cx cy k1 k2,
// then k3 and p1 p2 when fitted); per seen frame the board's pose (6).
struct Layout {
  std::vector<int> pose, intr, board;  // first index, -1 where absent
  int n_intr = 6;
  int size = 0;
};

struct Unpacked {
  cv::Vec3d r, t;
  cv::Matx33d K;
  cv::Vec<double, 5> dist;
};

class Problem {
 public:
  Problem(const RigState& s, const std::vector<RigObservation>& obs, const BundleOptions& o) : s_(s), obs_(obs), o_(o) {
    const std::size_t nc = s.cameras.size();
    L_.n_intr = o.intrinsics ? 6 + (o.fix_k3 ? 0 : 1) + (o.fit_tangential ? 2 : 0) : 0;
    L_.pose.assign(nc, -1), L_.intr.assign(nc, -1), L_.board.assign(s.board_r.size(), -1);
    for (std::size_t c = 0; c < nc; ++c) {
      if (c != o.root) L_.pose[c] = L_.size, L_.size += 6;
      L_.intr[c] = L_.size, L_.size += L_.n_intr;
    }
    for (const auto& ob : obs)
      if (L_.board[ob.frame] < 0) L_.board[ob.frame] = L_.size, L_.size += 6;
    x_ = Eigen::VectorXd::Zero(L_.size);
    for (std::size_t c = 0; c < nc; ++c) {
      const auto& cam = s.cameras[c];
      if (L_.pose[c] >= 0)
        for (int i = 0; i < 3; ++i) x_[L_.pose[c] + i] = cam.rvec[i], x_[L_.pose[c] + 3 + i] = cam.tvec[i];
      if (!o.intrinsics) continue;
      double* p = x_.data() + L_.intr[c];
      p[0] = cam.K(0, 0), p[1] = cam.K(1, 1), p[2] = cam.K(0, 2), p[3] = cam.K(1, 2), p[4] = cam.dist[0], p[5] = cam.dist[1];
      int k = 6;
      if (!o.fix_k3) p[k++] = cam.dist[4];
      if (o.fit_tangential) p[k++] = cam.dist[2], p[k++] = cam.dist[3];
    }
    for (std::size_t f = 0; f < L_.board.size(); ++f)
      if (L_.board[f] >= 0)
        for (int i = 0; i < 3; ++i) x_[L_.board[f] + i] = s.board_r[f][i], x_[L_.board[f] + 3 + i] = s.board_t[f][i];
  }

  // The parameters observation `ob` depends on, in order: board, camera pose, intrinsics.
  std::vector<int> columns(const RigObservation& ob) const {
    std::vector<int> cols;
    for (int i = 0; i < 6; ++i) cols.push_back(L_.board[ob.frame] + i);
    if (L_.pose[ob.camera] >= 0)
      for (int i = 0; i < 6; ++i) cols.push_back(L_.pose[ob.camera] + i);
    for (int i = 0; i < L_.n_intr; ++i) cols.push_back(L_.intr[ob.camera] + i);
    return cols;
  }

  // In double precision: the finite-difference steps move a corner by ~1e-3 px.
  std::vector<cv::Point2d> project(const RigObservation& ob, const Eigen::VectorXd& x) const {
    const auto& cam = s_.cameras[ob.camera];
    cv::Vec3d rc(0, 0, 0), tc(0, 0, 0);
    if (L_.pose[ob.camera] >= 0)
      for (int i = 0; i < 3; ++i) rc[i] = x[L_.pose[ob.camera] + i], tc[i] = x[L_.pose[ob.camera] + 3 + i];
    cv::Vec3d rb, tb;
    for (int i = 0; i < 3; ++i) rb[i] = x[L_.board[ob.frame] + i], tb[i] = x[L_.board[ob.frame] + 3 + i];
    cv::Vec3d r, t;
    cv::composeRT(rb, tb, rc, tc, r, t);  // board -> root -> camera
    cv::Matx33d K = cam.K;
    cv::Vec<double, 5> d = cam.dist;
    if (o_.intrinsics) {
      const double* p = x.data() + L_.intr[ob.camera];
      K = cv::Matx33d(p[0], 0, p[2], 0, p[1], p[3], 0, 0, 1);
      d[0] = p[4], d[1] = p[5];
      int k = 6;
      if (!o_.fix_k3) d[4] = p[k++];
      if (o_.fit_tangential) d[2] = p[k++], d[3] = p[k++];
    }
    std::vector<cv::Point3d> object(ob.object.begin(), ob.object.end());
    std::vector<cv::Point2d> uv;
    cv::projectPoints(object, r, t, cv::Mat(K), cv::Mat(d), uv);
    return uv;
  }

  double step(int col) const {
    for (std::size_t c = 0; c < L_.intr.size(); ++c)
      if (col >= L_.intr[c] && col < L_.intr[c] + L_.n_intr) return col - L_.intr[c] < 4 ? 1e-3 : 1e-6;
    for (const auto& first : {&L_.pose, &L_.board})
      for (int b : *first)
        if (b >= 0 && col >= b && col < b + 6) return col - b < 3 ? 1e-6 : 1e-7;
    return 1e-7;
  }

  // Cost (Huber) and, when A is given, the normal equations at x.
  double evaluate(const Eigen::VectorXd& x, Eigen::MatrixXd* A, Eigen::VectorXd* g, std::vector<double>* sq, std::vector<int>* count) const {
    double cost = 0;
    if (A) A->setZero(L_.size, L_.size), g->setZero(L_.size);
    for (const auto& ob : obs_) {
      const auto uv = project(ob, x);
      const std::size_t m = uv.size();
      Eigen::VectorXd r(2 * m);
      for (std::size_t i = 0; i < m; ++i) r[2 * i] = uv[i].x - (*ob.image)[i].x, r[2 * i + 1] = uv[i].y - (*ob.image)[i].y;
      Eigen::VectorXd w(2 * m);
      for (std::size_t i = 0; i < m; ++i) {
        const double e = std::hypot(r[2 * i], r[2 * i + 1]);
        const double wi = e <= o_.huber_px ? 1.0 : o_.huber_px / e;
        w[2 * i] = w[2 * i + 1] = wi;
        cost += e <= o_.huber_px ? e * e : o_.huber_px * (2 * e - o_.huber_px);
        if (sq) (*sq)[ob.camera] += e * e, (*count)[ob.camera] += 1;
      }
      if (!A) continue;
      const auto cols = columns(ob);
      Eigen::MatrixXd J(2 * m, static_cast<Eigen::Index>(cols.size()));
      for (std::size_t j = 0; j < cols.size(); ++j) {
        Eigen::VectorXd xp = x;
        const double h = step(cols[j]);
        xp[cols[j]] += h;
        const auto up = project(ob, xp);
        for (std::size_t i = 0; i < m; ++i)
          J(2 * i, j) = (up[i].x - uv[i].x) / h, J(2 * i + 1, j) = (up[i].y - uv[i].y) / h;
      }
      const Eigen::MatrixXd JtW = J.transpose() * w.asDiagonal();
      const Eigen::MatrixXd a = JtW * J;
      const Eigen::VectorXd b = JtW * r;
      for (std::size_t i = 0; i < cols.size(); ++i) {
        (*g)[cols[i]] += b[i];
        for (std::size_t j = 0; j < cols.size(); ++j) (*A)(cols[i], cols[j]) += a(i, j);
      }
    }
    return cost;
  }

  void store(RigState& s) const {
    for (std::size_t c = 0; c < s.cameras.size(); ++c) {
      auto& cam = s.cameras[c];
      if (L_.pose[c] >= 0)
        for (int i = 0; i < 3; ++i) cam.rvec[i] = x_[L_.pose[c] + i], cam.tvec[i] = x_[L_.pose[c] + 3 + i];
      if (!o_.intrinsics) continue;
      const double* p = x_.data() + L_.intr[c];
      cam.K(0, 0) = p[0], cam.K(1, 1) = p[1], cam.K(0, 2) = p[2], cam.K(1, 2) = p[3], cam.dist[0] = p[4], cam.dist[1] = p[5];
      int k = 6;
      if (!o_.fix_k3) cam.dist[4] = p[k++];
      if (o_.fit_tangential) cam.dist[2] = p[k++], cam.dist[3] = p[k++];
    }
    for (std::size_t f = 0; f < L_.board.size(); ++f)
      if (L_.board[f] >= 0)
        for (int i = 0; i < 3; ++i) s.board_r[f][i] = x_[L_.board[f] + i], s.board_t[f][i] = x_[L_.board[f] + 3 + i];
  }

  Eigen::VectorXd x_;
  Layout L_;

 private:
  const RigState& s_;
  const std::vector<RigObservation>& obs_;
  BundleOptions o_;
};

}  // namespace

std::vector<double> bundle_adjust_rig(RigState& state, const std::vector<RigObservation>& all, const BundleOptions& options) {
  // A board whose corners the starting rig misplaces by pixels is a mis-detection (a grid listed
  // the wrong way round), not noise: left out, with a warning.
  std::vector<RigObservation> observations;
  {
    const Problem start(state, all, options);
    for (const auto& ob : all) {
      const auto uv = start.project(ob, start.x_);
      double s2 = 0;
      for (std::size_t i = 0; i < uv.size(); ++i) s2 += std::pow(uv[i].x - (*ob.image)[i].x, 2) + std::pow(uv[i].y - (*ob.image)[i].y, 2);
      const double rms = std::sqrt(s2 / std::max<std::size_t>(1, uv.size()));
      if (rms <= options.max_start_rms_px) observations.push_back(ob);
      else
        log::warn(state.cameras[ob.camera].name + ": frame " + std::to_string(ob.frame) + " left out of the bundle adjustment (" +
                  std::to_string(rms) + " px off the chained rig)");
    }
  }
  Problem P(state, observations, options);
  Eigen::MatrixXd A;
  Eigen::VectorXd g;
  double cost = P.evaluate(P.x_, &A, &g, nullptr, nullptr);
  double lambda = 1e-3;
  for (int it = 0; it < options.iterations; ++it) {
    Eigen::MatrixXd M = A;
    for (Eigen::Index i = 0; i < M.rows(); ++i) M(i, i) += lambda * M(i, i) + 1e-12;
    const Eigen::VectorXd delta = M.ldlt().solve(-g);
    const Eigen::VectorXd cand = P.x_ + delta;
    const double c = P.evaluate(cand, nullptr, nullptr, nullptr, nullptr);
    if (std::isfinite(c) && c < cost) {
      const double drop = (cost - c) / std::max(cost, 1e-300);
      P.x_ = cand, cost = P.evaluate(P.x_, &A, &g, nullptr, nullptr), lambda = std::max(lambda / 10, 1e-9);
      if (drop < 1e-10) break;
    } else {
      lambda *= 10;
      if (lambda > 1e6) break;
    }
  }
  P.store(state);
  std::vector<double> sq(state.cameras.size(), 0.0);
  std::vector<int> count(state.cameras.size(), 0);
  P.evaluate(P.x_, nullptr, nullptr, &sq, &count);
  for (std::size_t c = 0; c < sq.size(); ++c) sq[c] = count[c] ? std::sqrt(sq[c] / count[c]) : 0.0;
  return sq;
}

}  // namespace finverse::vision
