// screen.cpp -- see screen.h.
#include "diagnose/screen.h"

#include <chrono>
#include <cmath>

#include "model/parallel_for.h"

namespace rtb {

namespace {

// Weighted residuals of model m and the weighted sensitivity columns of
// spec's free parameters, stacked over the records.
struct Columns {
  Eigen::VectorXd r;
  Eigen::MatrixXd g;
};
Columns screen_columns(const ExtModel &m, const std::vector<Record> &recs, const MisfitOptions &opt,
                       const ExtFitSpec &spec) {
  std::vector<double> rv;
  std::vector<Eigen::RowVectorXd> rows;
  for (const Record &rec : recs) {
    Eigen::VectorXd F;
    Eigen::MatrixXd J;
    predict_extended(m, rec, opt.sim, spec, F, &J);
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    for (size_t j = 0; j < rec.F.size(); ++j) {
      if (!(w[j] > 0.0)) continue;
      const double q = std::sqrt(w[j]);
      rv.push_back(q * (F[(Eigen::Index)j] - rec.F[j]));
      rows.push_back(q * J.row((Eigen::Index)j));
    }
  }
  Columns c;
  c.r = Eigen::Map<Eigen::VectorXd>(rv.data(), (Eigen::Index)rv.size());
  c.g.resize(c.r.size(), rows.empty() ? 0 : rows[0].size());
  for (size_t k = 0; k < rows.size(); ++k) c.g.row((Eigen::Index)k) = rows[k];
  return c;
}

// Least squares min |r + A th| with the columns of A scaled to unit norm
// (th in scaled units: the unknown is th / cs).
struct ScaledLsq {
  Eigen::VectorXd cs, th, res;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  ScaledLsq(const Eigen::MatrixXd &A, const Eigen::VectorXd &r)
      : cs(A.colwise().norm().transpose().cwiseMax(1e-300)) {
    const Eigen::MatrixXd As = A * cs.cwiseInverse().asDiagonal();
    ldlt.compute(As.transpose() * As);
    th = -ldlt.solve(As.transpose() * r);
    res = r + As * th;
  }
};

// Score test: the linearized least squares with the model's columns and the
// candidate's together; the candidate's amplitude is the first of its
// columns. *model_step receives the accompanying step of the model's
// parameters.
void joint_linear(const Columns &base, const Eigen::MatrixXd &g, CandidateScreen &s,
                  Eigen::VectorXd *model_step = nullptr) {
  const Eigen::Index m = base.r.size(), P = base.g.cols(), q = g.cols();
  Eigen::MatrixXd A(m, P + q);
  A << base.g, g;
  const ScaledLsq ls(A, base.r);
  const double r2 = base.r.squaredNorm();
  s.dJ = r2 > 0 ? 1.0 - ls.res.squaredNorm() / r2 : 0.0;
  s.value = ls.th[P] / ls.cs[P];
  const double s2 = ls.res.squaredNorm() / std::max(1.0, double(m - P - q));
  const Eigen::VectorXd e = Eigen::VectorXd::Unit(P + q, P);
  const double var = s2 * e.dot(ls.ldlt.solve(e)) / (ls.cs[P] * ls.cs[P]);
  s.z = var > 0 ? std::fabs(s.value) / std::sqrt(var) : 0.0;
  if (model_step) *model_step = ls.th.head(P).cwiseQuotient(ls.cs.head(P));
}

// The misfit reduction of the model's own linearized step (no candidate):
// what every candidate's dJ contains. Large where the screen's records are
// not the ones the model was fitted to (the held-out records: 0.60 on
// BM_Diagnose's maxwell case, where the candidates' dJ were 0.60-0.91).
double model_reduction(const Columns &base) {
  const double r2 = base.r.squaredNorm();
  if (!(r2 > 0.0) || base.g.cols() == 0) return 0.0;
  return std::max(0.0, 1.0 - ScaledLsq(base.g, base.r).res.squaredNorm() / r2);
}

// Move the core RT parameters by the linearized step that accompanies the
// candidate's term (the model had bent them to absorb the effect), in log
// coordinates and by at most +-50%.
void apply_rt_step(const Eigen::VectorXd &d, rtb_params &p) {
  const std::vector<ParamId> ids = core_params();
  for (size_t i = 0; i < ids.size() && (Eigen::Index)i < d.size(); ++i) {
    double &v = param_ref(p, ids[i]);
    if (v <= 0.0) continue;
    const double rel = std::max(-0.5, std::min(0.5, d[(Eigen::Index)i] / v));
    v *= std::exp(rel);
  }
  // alpha stays inside the admissible range (a model at the floor
  // RTB_ALPHA_MIN, friction-like, must not be stepped below it).
  p.alpha = std::max(std::min(p.alpha, 0.95), 1.01 * RTB_ALPHA_MIN);
}

struct Job {
  size_t cand;
  int variant;
};

// One pass of a shape scan at model m: the amplitude (the candidate's first
// parameter) linear at each grid value; keeps the best admissible amplitude
// and, in *chosen, its grid value (untouched when there is none).
CandidateScreen scan_pass(const ExtModel &m, const Columns &base, const std::vector<Record> &recs,
                          const MisfitOptions &opt, const DataScales &sc, ParamId amplitude,
                          const ShapePass &pass, double *chosen) {
  CandidateScreen s;
  s.start = m;
  ExtFitSpec one;
  one.free = {amplitude};
  bool any = false;
  for (double g : pass.grid) {
    ExtModel t = m;
    pass.set(t.p, sc, g);
    CandidateScreen c;
    Eigen::VectorXd step;
    joint_linear(base, screen_columns(t, recs, opt, one).g, c, &step);
    if (c.value > 0.0 && (!any || c.dJ > s.dJ)) {
      s = c;
      s.start = t;
      apply_rt_step(step, s.start.p);
      *chosen = g;
      any = true;
    }
  }
  s.plausible = any;
  return s;
}

// The passes in order, each at the shape the earlier ones chose; the
// admissible pass with the largest misfit reduction wins (the first on ties).
CandidateScreen scan_shape(const Candidate &c, const ExtModel &m0, const Columns &base,
                           const std::vector<Record> &recs, const MisfitOptions &opt,
                           const DataScales &sc) {
  CandidateScreen best;
  std::vector<double> chosen;
  for (size_t k = 0; k < c.passes.size(); ++k) {
    ExtModel m = m0;
    for (size_t i = 0; i < k; ++i) c.passes[i].set(m.p, sc, chosen[i]);
    chosen.push_back(c.passes[k].fallback);
    const CandidateScreen s = scan_pass(m, base, recs, opt, sc, c.extra[0], c.passes[k], &chosen[k]);
    if (k == 0 || (s.plausible && (!best.plausible || s.dJ > best.dJ))) best = s;
  }
  return best;
}

// A short joint fit (clearance, slack): not differentiable in the switch.
CandidateScreen short_fit(const Candidate &c, const ExtModel &start, const ExtFitSpec &spec,
                          const Columns &base, const std::vector<Record> &recs,
                          const MisfitOptions &opt, const DataScales &sc) {
  ExtFitSpec one = combined_spec({c}, sc);
  one.free = spec.free;
  for (ParamId id : c.extra) one.free.push_back(id);
  one.fit_delay = spec.fit_delay;
  one.fit_offset = spec.fit_offset;
  // Short, and without the outlier-robust refit (ExtFitSpec): a screen
  // ranks words, it does not size them. Stage 0 has masked the force
  // spikes; what the refit masked here, 6 robust deviations off a
  // baseline that misses an effect, was that effect's own largest
  // residuals (blindgen inertia_s59 at 1 kHz: 78-171 of 50 000 samples on
  // every short fit, the same misfit after 12 iterations as after 6
  // without; the screen 40 -> 27 s on 2 threads, the same verdict).
  one.max_iter = 6;
  one.robust_k = 0.0;
  const ExtFitResult f = fit_extended(recs, start, one, opt);
  CandidateScreen s;
  const double r2 = base.r.squaredNorm();
  s.dJ = r2 > 0 ? std::max(0.0, 1.0 - f.J / (0.5 * r2)) : 0.0;
  s.start = f.model;
  if (c.extra.empty()) {  // a switch: likelihood-ratio significance
    const double m = (double)std::max<long>(1, f.samples);
    s.value = 1.0;
    s.z = s.dJ > 0 ? std::sqrt(std::max(0.0, -m * std::log(1.0 - s.dJ))) : 0.0;
    return s;
  }
  const Eigen::Index gi = (Eigen::Index)spec.free.size();
  s.value = param_get(f.model.p, c.extra[0]);
  s.z = f.stddev_valid && f.stddev[gi] > 0 ? s.value / f.stddev[gi] : 0.0;
  return s;
}

CandidateScreen screen_one(const Candidate &c, int variant, const ExtModel &m,
                           const ExtFitSpec &spec, const Columns &base,
                           const std::vector<Record> &recs, const MisfitOptions &opt,
                           const DataScales &sc) {
  ExtModel m0 = m;
  if (c.configure) c.configure(m0.p, sc);
  if (c.screen == ScreenMethod::shape_scan) return scan_shape(c, m0, base, recs, opt, sc);
  if (c.screen == ScreenMethod::short_fit) {
    if (c.start_at) c.start_at(m0.p, sc, c.starts[(size_t)variant]);
    admit_K0(m0.p);  // K0 < 0 is refused on a slack strip with relax_width
    return short_fit(c, m0, spec, base, recs, opt, sc);
  }

  CandidateScreen s;
  ExtFitSpec one;
  one.free = c.extra;
  one.fit_delay = c.delay;
  one.fit_offset = c.offset;
  Eigen::VectorXd step;
  joint_linear(base, screen_columns(m0, recs, opt, one).g, s, &step);
  s.start = m0;
  apply_rt_step(step, s.start.p);
  if (!c.extra.empty()) {
    const ParamId id = c.extra[0];
    const bool positive = id == P_viscous_c || id == P_mass || id == P_mullins;
    s.plausible = !positive || s.value > 0.0;
    double v = s.value;
    // A wrong-signed screen (the model absorbed part of the effect) still
    // gets a joint fit if it ranks high, from a default positive size.
    if (id == P_mullins && v > 0.0) v = std::min(v, 0.9);
    if (id == P_fric_asym) v = std::max(-0.9, std::min(0.9, v));
    if (id == P_k_asym) v = std::max(-0.9 * k_asym_bound(s.start.p), std::min(0.9 * k_asym_bound(s.start.p), v));
    if (positive && !(v > 0.0)) v = extra_start_value(id, sc);
    param_ref(s.start.p, id) = v;
  }
  if (c.delay) {
    // A lag of the force channel (value > 0), or a lead: the displacement
    // channel lags (joint_fits tries the other definitions).
    s.start.delay = s.value != 0.0 ? std::fabs(s.value) : 2.0 * sc.dt;
    s.start.delay_lead = s.value < 0.0;
  }
  if (c.offset) s.start.offset = m.offset + s.value;
  return s;
}

}  // namespace

std::vector<CandidateScreen> screen_candidates(const std::vector<Candidate> &cands,
                                               const ExtModel &m, const ExtFitSpec &spec,
                                               const std::vector<Record> &recs,
                                               const MisfitOptions &opt, const DataScales &sc,
                                               int threads) {
  // Jobs (candidate, variant), the long clearance and slack fits first.
  std::vector<Job> jobs;
  for (size_t i = 0; i < cands.size(); ++i) {
    const Candidate &c = cands[i];
    const bool slow = c.screen == ScreenMethod::short_fit;
    const int variants = c.start_at ? (int)c.starts.size() : 1;
    for (int v = 0; v < variants; ++v) {
      if (slow) jobs.insert(jobs.begin(), {i, v});
      else jobs.push_back({i, v});
    }
  }
  const Columns base = screen_columns(m, recs, opt, spec);
  std::vector<CandidateScreen> per_job(jobs.size());
  parallel_for(jobs.size(), threads, [&](size_t k) {
    const auto t1 = std::chrono::steady_clock::now();
    try {
      per_job[k] = screen_one(cands[jobs[k].cand], jobs[k].variant, m, spec, base, recs, opt, sc);
    } catch (const std::exception &) {
      per_job[k] = CandidateScreen();  // a failed screen ranks last
      per_job[k].start = m;
    }
    per_job[k].seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  });
  const double dJ_model = model_reduction(base);
  for (CandidateScreen &s : per_job) s.dJ_model = dJ_model;
  // A candidate's screen is its best variant (largest misfit reduction).
  std::vector<CandidateScreen> out(cands.size());
  std::vector<bool> have(cands.size(), false);
  for (size_t k = 0; k < jobs.size(); ++k) {
    CandidateScreen &s = out[jobs[k].cand];
    const double spent = s.seconds + per_job[k].seconds;
    if (!have[jobs[k].cand] || per_job[k].dJ > s.dJ) s = per_job[k];
    s.seconds = spent;
    have[jobs[k].cand] = true;
  }
  return out;
}

}  // namespace rtb
