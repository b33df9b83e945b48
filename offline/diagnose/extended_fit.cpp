// extended_fit.cpp -- see extended_fit.h.
#include "diagnose/extended_fit.h"

#include <algorithm>
#include <cmath>

#include "identify/optimizer.h"
#include "model/parallel_for.h"

namespace rtb {

namespace {

// The force channel as a first-order low-pass of time constant tau, exact
// for a force held between samples: y_j = a_j y_j-1 + (1 - a_j) F_j,
// a_j = exp(-h_j / tau), from y_0 = F_0 (the record starts at rest). The
// sensitivities pass through the same filter (it is linear in F); the
// delay column is dy/dtau: s_j = a_j s_j-1 + a_j h_j / tau^2 (y_j-1 - F_j).
void lowpass_channel(const ExtModel &m, const Record &rec, const ExtFitSpec &spec,
                     const Eigen::VectorXd &Fm, const Eigen::MatrixXd &Jm, Eigen::VectorXd &F,
                     Eigen::MatrixXd *jac) {
  const Eigen::Index n = Fm.size(), P = (Eigen::Index)spec.free.size();
  const double tau = m.delay;
  double y = Fm[0], s = 0.0;
  Eigen::RowVectorXd yJ;
  if (jac) yJ = Jm.row(0);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (j > 0) {
      const double h = rec.t[(size_t)j] - rec.t[(size_t)j - 1], q = h / tau, a = std::exp(-q);
      // da/dtau = a q / tau, written so that a tau the fit drives towards 0
      // gives 0 (its limit), not 0 * inf.
      s = a * s + (a > 0.0 ? a * q / tau : 0.0) * (y - Fm[j]);
      y = a * y + (1.0 - a) * Fm[j];
      if (jac) yJ = a * yJ + (1.0 - a) * Jm.row(j);
    }
    F[j] = y + m.offset;
    if (jac) {
      jac->row(j).head(P) = yJ;
      Eigen::Index c = P;
      if (spec.fit_delay) (*jac)(j, c++) = s;
      if (spec.fit_offset) (*jac)(j, c) = 1.0;
    }
  }
}

}  // namespace

void predict_extended(const ExtModel &m, const Record &rec, const SimOptions &sim,
                      const ExtFitSpec &spec, Eigen::VectorXd &F, Eigen::MatrixXd *jac,
                      SensitivityCache *cache) {
  Eigen::VectorXd Fm;
  Eigen::MatrixXd Jm;
  record_sensitivities(m.p, rec, sim, spec.free, Fm, jac ? &Jm : nullptr, cache);
  const Eigen::Index n = Fm.size(), P = (Eigen::Index)spec.free.size();
  const Eigen::Index cols = P + spec.fit_delay + spec.fit_offset;
  F.resize(n);
  if (jac) jac->setZero(n, cols);
  if (m.delay_lowpass && !m.delay_lead && m.delay > 0.0 && n > 0) {
    lowpass_channel(m, rec, spec, Fm, Jm, F, jac);
    return;
  }
  // Linear interpolation of the model output at t_j - shift (a lag) or
  // t_j + delay (a lead: shift = -delay).
  const double shift = m.delay_lead ? -m.delay : m.delay;
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double u = rec.t[(size_t)j] - shift;
    double val, slope = 0.0;
    if (m.delay == 0.0) {
      val = Fm[j];
      if (jac) jac->row(j).head(P) = Jm.row(j);
      // Slope for d/d(delay) at 0: the backward-difference of the model force.
      if (j > 0) slope = (Fm[j] - Fm[j - 1]) / (rec.t[(size_t)j] - rec.t[(size_t)j - 1]);
    } else if (u <= rec.t[0]) {
      val = Fm[0];
      if (jac) jac->row(j).head(P) = Jm.row(0);
    } else if (u >= rec.t[(size_t)n - 1]) {
      val = Fm[n - 1];
      if (jac) jac->row(j).head(P) = Jm.row(n - 1);
    } else {
      while (k + 1 < n && rec.t[(size_t)k + 1] <= u) ++k;
      while (k > 0 && rec.t[(size_t)k] > u) --k;
      const double h = rec.t[(size_t)k + 1] - rec.t[(size_t)k], a = (u - rec.t[(size_t)k]) / h;
      val = (1 - a) * Fm[k] + a * Fm[k + 1];
      slope = (Fm[k + 1] - Fm[k]) / h;
      if (jac) jac->row(j).head(P) = (1 - a) * Jm.row(k) + a * Jm.row(k + 1);
    }
    F[j] = val + m.offset;
    if (jac) {
      Eigen::Index c = P;
      if (spec.fit_delay) (*jac)(j, c++) = m.delay_lead ? slope : -slope;
      if (spec.fit_offset) (*jac)(j, c) = 1.0;
    }
  }
}

double extended_error(const ExtModel &m, const std::vector<Record> &recs,
                      const MisfitOptions &opt, double *Jout, double *J0out, double trim) {
  double J = 0.0, J0 = 0.0;
  ExtFitSpec none;
  none.free.clear();
  std::vector<Eigen::VectorXd> Fs(recs.size());
  parallel_for(recs.size(), opt.threads,
               [&](size_t k) { predict_extended(m, recs[k], opt.sim, none, Fs[k], nullptr); });
  for (const Record &rec : recs) {  // summed in record order: the same bits on any thread count
    const Eigen::VectorXd &F = Fs[(size_t)(&rec - &recs[0])];
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    std::vector<double> terms;
    for (size_t j = 0; j < rec.F.size(); ++j) {
      const double r = F[(Eigen::Index)j] - rec.F[j];
      terms.push_back(0.5 * w[j] * r * r);
      J0 += 0.5 * w[j] * rec.F[j] * rec.F[j];
    }
    // Trimmed: drop the largest `trim` fraction of the terms (isolated
    // outliers such as one-sample spikes at ideal input corners).
    const size_t drop = (size_t)(trim * (double)terms.size());
    if (drop > 0) {
      std::nth_element(terms.begin(), terms.end() - (long)drop, terms.end());
      terms.resize(terms.size() - drop);
    }
    for (double t : terms) J += t;
  }
  if (Jout) *Jout = J;
  if (J0out) *J0out = J0;
  return J0 > 0.0 ? std::sqrt(J / J0) : INFINITY;
}

ExtFitResult fit_extended(const std::vector<Record> &recs, const ExtModel &start_in,
                          const ExtFitSpec &spec, const MisfitOptions &opt) {
  ParamTransform tf(spec.free, start_in.p, stiffness_cap_for(recs));
  // A start assembled from another fit (a chain from the STS inversion, a
  // core from another basin) may hold a kink past the static tangent of its
  // new chain (|k_asym| <= K0 + chain, rtb_params_check): the map's clamps
  // take it back inside.
  ExtModel start = start_in;
  if (rtb_params_validate(&start.p) != RTB_OK) start.p = tf.to_params(tf.to_theta(start.p), start.p);
  for (ParamId id : spec.free)
    if (spec.scale[id] > 0.0 && (param_get(start.p, id) == 0.0 || is_ramp(id)))
      tf.scale[id] = std::fmax(std::fabs(param_get(start.p, id)), spec.scale[id]);
  const Eigen::Index P = (Eigen::Index)spec.free.size();
  const Eigen::Index nt = P + spec.fit_delay + spec.fit_offset;
  double J0 = 0.0;
  extended_error(start, recs, opt, nullptr, &J0);
  const double s = 1.0 / std::sqrt(J0);
  SensitivityCache cache;  // accepted trial points reuse their forward run
  cache.prepare(recs);
  std::vector<std::vector<double>> weights;  // quadrature weights, 0 where masked
  for (const Record &rec : recs) weights.push_back(quadrature_weights(rec, opt.fit_from));

  auto unpack = [&](const Eigen::VectorXd &th) {
    ExtModel m = start;
    m.p = tf.to_params(th.head(P), start.p);
    Eigen::Index c = P;
    if (spec.fit_delay) m.delay = spec.delay_scale * std::exp(th[c++]);  // > 0: the force lags
    if (spec.fit_offset) m.offset = th[c] * spec.offset_scale;
    return m;
  };
  Objective obj;
  obj.residuals = [&](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *jac) {
    const ExtModel m = unpack(th);
    std::vector<double> rv;
    std::vector<Eigen::RowVectorXd> rows;
    try {
      if (rtb_params_validate(&m.p) != RTB_OK) throw std::runtime_error("invalid");
      // d(natural)/d(theta): the parameter block (with the k_asym clamp's
      // coupling to K0) and the diagonal of the delay/offset coordinates.
      Eigen::MatrixXd dn = Eigen::MatrixXd::Zero(nt, nt);
      dn.topLeftCorner(P, P) = tf.jacobian(th.head(P), start.p);
      Eigen::Index c = P;
      if (spec.fit_delay) { dn(c, c) = m.delay; ++c; }
      if (spec.fit_offset) dn(c, c) = spec.offset_scale;
      // The records simulated in parallel (serially inside a parallel
      // candidate loop), stacked in record order.
      std::vector<Eigen::VectorXd> Fs(recs.size());
      std::vector<Eigen::MatrixXd> Js(recs.size());
      parallel_for(recs.size(), opt.threads, [&](size_t k) {
        predict_extended(m, recs[k], opt.sim, spec, Fs[k], jac ? &Js[k] : nullptr, &cache);
      });
      for (const Record &rec : recs) {
        const Eigen::VectorXd &F = Fs[(size_t)(&rec - &recs[0])];
        const Eigen::MatrixXd &J = Js[(size_t)(&rec - &recs[0])];
        const std::vector<double> &w = weights[(size_t)(&rec - &recs[0])];
        for (size_t j = 0; j < rec.F.size(); ++j) {
          if (!(w[j] > 0.0)) continue;
          const double q = s * std::sqrt(w[j]);
          rv.push_back(q * (F[(Eigen::Index)j] - rec.F[j]));
          if (jac) rows.push_back(q * J.row((Eigen::Index)j) * dn);
        }
      }
    } catch (const std::runtime_error &) {
      r = Eigen::VectorXd::Constant(1, INFINITY);
      if (jac) jac->setZero(1, nt);
      return;
    }
    r = Eigen::Map<Eigen::VectorXd>(rv.data(), (Eigen::Index)rv.size());
    if (jac) {
      jac->resize(r.size(), nt);
      for (size_t k = 0; k < rows.size(); ++k) jac->row((Eigen::Index)k) = rows[k];
    }
  };
  Eigen::VectorXd th0(nt);
  th0.head(P) = tf.to_theta(start.p);
  Eigen::Index c = P;
  if (spec.fit_delay) th0[c++] = std::log(std::fmax(start.delay, 1e-3 * spec.delay_scale) / spec.delay_scale);
  if (spec.fit_offset) th0[c] = start.offset / spec.offset_scale;
  OptOptions oo;
  oo.max_iter = spec.max_iter;
  oo.ftol = 1e-10;
  oo.chi2_tol = spec.chi2_tol;
  // The transform's box on the model parameters; delay and offset are free.
  oo.lower = Eigen::VectorXd::Constant(nt, -INFINITY);
  oo.upper = Eigen::VectorXd::Constant(nt, INFINITY);
  oo.lower.head(P) = tf.lower();
  oo.upper.head(P) = tf.upper();
  OptResult o = minimize_trust_region(obj, th0, oo);
  restart_sloppy(obj, [&](const Eigen::VectorXd &t, const OptOptions &op) {
    return minimize_trust_region(obj, t, op);
  }, oo, spec.restarts, o);
  int iterations = o.iterations;
  long masked = 0;
  if (spec.robust_k > 0.0) {
    // Robust scale of the unweighted residuals at the first fit.
    const ExtModel m = unpack(o.theta);
    std::vector<std::vector<double>> res(recs.size());
    std::vector<double> all;
    ExtFitSpec none = spec;
    none.free.clear();
    none.fit_delay = none.fit_offset = false;
    for (size_t k = 0; k < recs.size(); ++k) {
      Eigen::VectorXd F;
      predict_extended(m, recs[k], opt.sim, none, F, nullptr, nullptr);
      for (size_t j = 0; j < recs[k].F.size(); ++j) {
        res[k].push_back(F[(Eigen::Index)j] - recs[k].F[j]);
        if (weights[k][j] > 0.0) all.push_back(std::fabs(res[k].back()));
      }
    }
    if (!all.empty()) {
      std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
      const double sigma = 1.4826 * all[all.size() / 2];
      long count = 0;
      for (size_t k = 0; k < recs.size(); ++k)
        for (size_t j = 0; j < res[k].size(); ++j)
          count += weights[k][j] > 0.0 && std::fabs(res[k][j]) > spec.robust_k * sigma;
      if (count > 0 && count <= spec.robust_max_fraction * (double)all.size()) {
        for (size_t k = 0; k < recs.size(); ++k)
          for (size_t j = 0; j < res[k].size(); ++j)
            if (std::fabs(res[k][j]) > spec.robust_k * sigma) weights[k][j] = 0.0;
        masked = count;
        oo.max_iter = spec.robust_max_iter;
        o = minimize_trust_region(obj, o.theta, oo);
        iterations += o.iterations;
      }
    }
  }

  ExtFitResult out;
  out.model = unpack(o.theta);
  out.masked = masked;
  out.iterations = iterations;
  out.converged = o.converged;
  out.error = extended_error(out.model, recs, opt, &out.J, &out.J0);
  for (ParamId id : spec.free) out.names.push_back(param_name(id));
  if (spec.fit_delay) out.names.push_back("delay");
  if (spec.fit_offset) out.names.push_back("offset");
  out.value.resize(nt);
  for (Eigen::Index i = 0; i < P; ++i) out.value[i] = param_get(out.model.p, spec.free[(size_t)i]);
  c = P;
  if (spec.fit_delay) out.value[c++] = out.model.delay;
  if (spec.fit_offset) out.value[c] = out.model.offset;

  // Standard deviations from the Gauss-Newton information in natural units
  // (white-noise sandwich as in identify.cpp). Dividing by each coordinate's
  // own slope undoes the Jacobian exactly except at the k_asym clamp, where
  // k_asym's column is 0 (it sits on its bound: infinite deviation) and K0's
  // moves along the bound.
  Eigen::VectorXd r;
  Eigen::MatrixXd Jt;
  obj.residuals(o.theta, r, &Jt);
  out.samples = r.size();
  Eigen::VectorXd scale(nt);
  scale.head(P) = tf.dp_dtheta(o.theta.head(P));
  c = P;
  if (spec.fit_delay) scale[c++] = out.model.delay;
  if (spec.fit_offset) scale[c] = spec.offset_scale;
  std::vector<double> w;
  std::vector<int> group;
  for (size_t k = 0; k < recs.size(); ++k)
    for (double v : weights[k])
      if (v > 0.0) {
        w.push_back(v);
        group.push_back((int)k);
      }
  if (r.size() > nt && (Eigen::Index)w.size() == r.size()) {
    const Eigen::MatrixXd Jp = Jt * scale.cwiseInverse().asDiagonal() / s;  // natural units
    const Eigen::VectorXd rp = r / s;
    const Eigen::Map<Eigen::VectorXd> wv(w.data(), r.size());
    out.stddev_valid = sandwich_covariance(rp, Jp, wv, group, out.stddev, nullptr);
  }
  return out;
}

std::vector<Record> artefact_corrected(const std::vector<Record> &recs, const ExtModel &m) {
  std::vector<Record> out = recs;
  for (size_t r = 0; r < recs.size(); ++r) {
    const std::vector<double> &t = recs[r].t, &F = recs[r].F;
    const size_t n = t.size();
    size_t k = 0;
    const double shift = m.delay_lead ? -m.delay : m.delay;
    for (size_t j = 0; j < n; ++j) {
      const double u = t[j] + shift;
      while (k + 1 < n && t[k + 1] <= u) ++k;
      const double w = k + 1 < n ? (u - t[k]) / (t[k + 1] - t[k]) : 0.0;
      const double Fu = u <= t[0] ? F[0] : (k + 1 < n ? F[k] + w * (F[k + 1] - F[k]) : F[n - 1]);
      out[r].F[j] = Fu - m.offset;
    }
  }
  return out;
}

double elastic_tangent_at_rest(const rtb_params &p) {
  return p.sat_force > 0.0 && p.sat_disp > 0.0 ? p.sat_force / p.sat_disp : 0.0;
}

std::vector<Record> chain_records(const std::vector<Record> &recs, const ExtModel &m) {
  std::vector<Record> out = artefact_corrected(recs, m);
  const rtb_params &p = m.p;
  const double k1 = elastic_tangent_at_rest(p);
  if (p.k2 == 0.0 && p.k3 == 0.0 && p.k_asym == 0.0 && k1 == 0.0) return out;
  for (Record &r : out)
    for (size_t j = 0; j < r.x.size(); ++j) {
      const double x = r.x[j];
      const double sat = k1 > 0.0 ? p.sat_force * std::tanh(x / p.sat_disp) - k1 * x : 0.0;
      r.F[j] -= p.k2 * x * x + p.k3 * x * x * x + p.k_asym * std::fabs(x) + sat;
    }
  return out;
}

}  // namespace rtb
