// A small Levenberg-Marquardt least-squares minimiser (Eigen, dense, forward/central-difference
// Jacobian) for the few-parameter fits of sweeps/calibration.cpp.
//
// Why not Eigen's unsupported LevenbergMarquardt (the MINPACK port)? It has no bounds, its functor
// interface (inputs()/values()/df(), status enums) hides what a stopping test means, and it lives
// in the unsupported tree whose API is not stable. Our problems have 1-2 parameters and a few
// hundred residuals; 80 readable lines with the stopping rules spelled out are easier to check.
//
// Minimises S(x) = sum_i r_i(x)^2 over unconstrained x (bounds are handled by the caller with a
// transform, e.g. a logistic map onto the allowed interval). Each iteration solves
//   (J^T J + mu diag(J^T J)) dx = -J^T r        (Marquardt's scaling: invariant to units of x)
// accepts the step if S decreases (mu /= 3) and rejects it otherwise (mu *= 4, retry).
// Stops ("converged") when an accepted step changes S by less than f_tol relative, or the step is
// below x_tol (relative to |x| + x_tol), or the gradient |J^T r|_inf is below g_tol; stops
// unconverged after max_iterations Jacobian evaluations or when mu exceeds 1e16 (no descent).
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <string>

namespace lsi::sweeps {

struct LmOptions {
  int max_iterations = 200;
  double f_tol = 1e-12;   // relative decrease of S
  double x_tol = 1e-10;   // step size, relative
  double g_tol = 1e-14;   // gradient (absolute, in units of S per unit x)
  double fd_step = 1e-6;  // finite-difference step, relative to max(1, |x_k|)
  double initial_damping = 1e-3;
};

struct LmResult {
  Eigen::VectorXd x;
  double cost = 0.0;  // S(x) = sum r^2 at the result
  double initial_cost = 0.0;
  int iterations = 0;   // Jacobian evaluations
  int evaluations = 0;  // residual evaluations
  bool converged = false;
  std::string reason;  // which stopping rule fired
};

// Central-difference Jacobian of r at x (m residuals x n parameters).
template <class Residuals>
Eigen::MatrixXd numerical_jacobian(Residuals&& r, const Eigen::VectorXd& x, double rel_step,
                                   int* evaluations = nullptr) {
  const Eigen::VectorXd r0 = r(x);
  Eigen::MatrixXd J(r0.size(), x.size());
  for (int k = 0; k < x.size(); ++k) {
    const double h = rel_step * std::max(1.0, std::fabs(x[k]));
    Eigen::VectorXd xp = x, xm = x;
    xp[k] += h;
    xm[k] -= h;
    J.col(k) = (r(xp) - r(xm)) / (2.0 * h);
  }
  if (evaluations) *evaluations += 1 + 2 * static_cast<int>(x.size());
  return J;
}

template <class Residuals>
LmResult levenberg_marquardt(Residuals&& residuals, Eigen::VectorXd x, const LmOptions& o = {}) {
  LmResult out;
  Eigen::VectorXd r = residuals(x);
  double cost = r.squaredNorm();
  out.initial_cost = cost;
  out.evaluations = 1;
  double mu = o.initial_damping;
  out.reason = "maximum iterations reached";
  for (out.iterations = 0; out.iterations < o.max_iterations;) {
    const Eigen::MatrixXd J = numerical_jacobian(residuals, x, o.fd_step, &out.evaluations);
    ++out.iterations;
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    if (g.lpNorm<Eigen::Infinity>() <= o.g_tol) {
      out.converged = true;
      out.reason = "gradient below g_tol";
      break;
    }
    // Diagonal scaling with a floor, so a parameter the residuals do not see stays put.
    Eigen::VectorXd d = A.diagonal().cwiseMax(1e-12 * std::max(1.0, A.diagonal().maxCoeff()));
    bool accepted = false;
    while (!accepted) {
      Eigen::MatrixXd M = A;
      M.diagonal() += mu * d;
      const Eigen::VectorXd dx = M.ldlt().solve(-g);
      const Eigen::VectorXd x_new = x + dx;
      const Eigen::VectorXd r_new = residuals(x_new);
      ++out.evaluations;
      const double cost_new = r_new.allFinite() ? r_new.squaredNorm() : INFINITY;
      if (dx.allFinite() && cost_new < cost) {
        const double decrease = (cost - cost_new) / std::max(cost, 1e-300);
        const bool small_step = dx.norm() <= o.x_tol * (x.norm() + o.x_tol);
        x = x_new;
        r = r_new;
        cost = cost_new;
        mu = std::max(mu / 3.0, 1e-12);
        accepted = true;
        if (decrease <= o.f_tol || small_step) {
          out.converged = true;
          out.reason = small_step ? "step below x_tol" : "relative decrease below f_tol";
        }
      } else {
        mu *= 4.0;
        if (mu > 1e16) break;  // no descent direction left: a (local) minimum to working precision
        if (dx.allFinite() && dx.norm() <= o.x_tol * (x.norm() + o.x_tol)) break;
      }
    }
    if (!accepted) {
      // Every damped step failed to decrease S: x is a minimum along all directions to the
      // resolution of the steps tried. This is how LM ends at a kink or at an exact zero.
      out.converged = true;
      out.reason = "no decrease possible (minimum to working precision)";
      break;
    }
    if (out.converged) break;
  }
  out.x = x;
  out.cost = cost;
  return out;
}

}  // namespace lsi::sweeps
