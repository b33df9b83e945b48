// specimen_model.cpp -- the specimen's constitutive laws: the RT cells of
// eq. (1)-(2) in primal form, the elastic effects, the specimen end position
// (clearance, slack) and the force on the load cell, eq. (11).
#include "specimen_model.h"

#include <algorithm>
#include <cmath>

namespace refgen {

SpecimenState rest_state(const Specimen &s) {
  SpecimenState st;
  st.y.assign((size_t)s.N, 0.0);
  st.v.assign((size_t)s.N, 0.0);
  st.q.assign(s.branches.size(), 0.0);
  return st;
}

SpecimenState relaxed_state(const Specimen &s, double x) {
  SpecimenState st = rest_state(s);
  const double d = std::min(s.half_gap, std::fabs(x));
  st.xb = s.gap == Gap::none ? x : x - std::copysign(d, x);
  st.xb_max = std::fabs(st.xb);
  st.q.assign(s.branches.size(), st.xb);
  // Dashpot forces 0: Kpa and the N springs Kr (the last to ground) carry
  // one series force P, so the nodes step down by P/Kpa, then P/Kr each.
  const double P = st.xb / (1.0 / s.Kpa + s.N / s.Kr);
  for (int k = 0; k < s.N; ++k)
    st.y[(size_t)k] = (k == 0 ? st.xb - P / s.Kpa : st.y[(size_t)k - 1] - P / s.Kr);
  return st;
}

double stiffness_scale(const Specimen &s, double t) { return 1.0 + s.drift_rate * t; }

double static_force(const Specimen &s, double x) {
  return s.K0 * x + x / (1.0 / s.Kpa + s.N / s.Kr);
}

double dashpot_velocity(const Specimen &s, double f, double *dphi_df) {
  const double C = f >= 0.0 ? s.C0 : s.C0 * s.c0_neg_ratio;
  const double r = std::fabs(f) / C, e = 1.0 / s.alpha;
  const double v = std::pow(r, e);  // |phi|
  *dphi_df = r > 0.0 ? e * v / std::fabs(f) : 0.0;
  return f >= 0.0 ? v : -v;
}

double elastic_force(const Specimen &s, double scale, double xb, double y1, double xb_max,
                     double *dF_dxb) {
  double F = scale * (s.K0 * xb + s.Kpa * (xb - y1));  // eq. (11)
  double dF = scale * (s.K0 + s.Kpa);
  F += s.cubic * xb * xb * xb;
  dF += 3.0 * s.cubic * xb * xb;
  if (s.asym != 0.0) {  // a smooth |xb|: tension and compression stiffness differ by 2 asym
    const double u = xb / s.asym_width, th = std::tanh(u);
    F += s.asym * xb * th;
    dF += s.asym * (th + u * (1.0 - th * th));
  }
  F += s.quad * xb * xb + s.quintic * xb * xb * xb * xb * xb;
  dF += 2.0 * s.quad * xb + 5.0 * s.quintic * xb * xb * xb * xb;
  if (s.soft_k != 0.0 && s.soft_tanh) {  // initial stiffness soft_k, saturating at soft_k soft_x
    const double th = std::tanh(xb / s.soft_x);
    F += s.soft_k * s.soft_x * th;
    dF += s.soft_k * (1.0 - th * th);
  } else if (s.soft_k != 0.0) {
    const double r2 = 1.0 + (xb / s.soft_x) * (xb / s.soft_x);
    F += s.soft_k * xb / std::sqrt(r2);
    dF += s.soft_k / (r2 * std::sqrt(r2));
  }
  if (s.mullins != 0.0 && std::fabs(xb) < xb_max) {
    // Below the prior maximum the K0 path has lost up to `mullins` of its
    // stiffness: K0 xb (1 - mu g(r)), r = xb/xb_max, virgin again at xb_max;
    // g = 1 - r^2, or erf(2 (1 - r^2)) (a loss nearly uniform below the max).
    const double r = xb / xb_max, k = s.mullins * scale * s.K0, u = 1.0 - r * r;
    const double g = s.mullins_erf ? std::erf(2.0 * u) : u;
    const double dg_dr = s.mullins_erf ? -8.0 * r * std::exp(-4.0 * u * u) / 1.7724538509055160273  /* sqrt(pi) */
                                       : -2.0 * r;
    F -= k * xb * g;
    dF -= k * (g + r * dg_dr);
  }
  *dF_dxb = dF;
  return F;
}

namespace {

// End position at which the specimen carries no force (it floats free), and
// d xb / d y1. The force is monotone in xb, 0 - Kpa y1 at xb = 0 and of the
// sign of y1 at xb = y1, so the root lies between: safeguarded Newton.
double free_position(const Specimen &s, double scale, double y1, double xb_max, double *dxb_dy1) {
  double lo = std::min(0.0, y1), hi = std::max(0.0, y1);
  double xb = s.Kpa * y1 / (s.K0 + s.Kpa), dF = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double F = elastic_force(s, scale, xb, y1, xb_max, &dF);
    if (F > 0.0) hi = xb; else lo = xb;
    double next = xb - F / dF;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::fabs(next - xb) <= 1e-15 * (1.0 + std::fabs(xb));
    xb = next;
    if (done || hi - lo <= 1e-15 * (1.0 + std::fabs(xb))) break;
  }
  elastic_force(s, scale, xb, y1, xb_max, &dF);
  *dxb_dy1 = scale * s.Kpa / dF;
  return xb;
}

}  // namespace

EndPosition end_position(const Specimen &s, double scale, double x, double y1, double xb_prev,
                         double xb_max) {
  EndPosition e;
  e.xb = x;
  const double d = s.half_gap;
  if (s.gap == Gap::held) {  // play operator: the end stays put until the actuator reaches it
    e.xb = std::min(std::max(xb_prev, x - d), x + d);
    e.contact = e.xb != xb_prev;
  } else if (s.gap == Gap::floating || s.slack) {
    double dfree = 0.0;
    const double xf = free_position(s, scale, y1, xb_max, &dfree);
    const bool free = s.slack ? xf > x : (xf >= x - d && xf <= x + d);
    if (free) {
      e.xb = xf;
      e.dxb_dy1 = dfree;
      e.contact = false;
    } else if (!s.slack) {
      e.xb = xf < x - d ? x - d : x + d;
    }
  }
  return e;
}

void cell_rates(const Specimen &s, double t, double x, double xb_prev, double xb_max,
                const double *y, CellRates &out) {
  const int N = s.N;
  const double sc = stiffness_scale(s, t), kr = sc * s.Kr, kpa = sc * s.Kpa;
  out.end = end_position(s, sc, x, y[0], xb_prev, xb_max);
  out.v.resize((size_t)N);
  out.sub.assign((size_t)N, 0.0);
  out.diag.resize((size_t)N);
  out.sup.assign((size_t)N, 0.0);
  for (int k = 0; k < N; ++k) {
    // (K y)_k of eq. (2): Kpa + Kr on cell 1, 2 Kr on the others (the last
    // spring Kr goes to ground), -Kr to the neighbours.
    const double kk = k == 0 ? kpa + kr : 2.0 * kr;
    double Ky = kk * y[k];
    if (k > 0) Ky -= kr * y[k - 1];
    if (k + 1 < N) Ky -= kr * y[k + 1];
    const double f = (k == 0 ? kpa * out.end.xb : 0.0) - Ky;  // dashpot force
    double dphi = 0.0;
    out.v[(size_t)k] = dashpot_velocity(s, f, &dphi);
    out.diag[(size_t)k] = -dphi * (kk - (k == 0 ? kpa * out.end.dxb_dy1 : 0.0));
    if (k > 0) out.sub[(size_t)k] = dphi * kr;
    if (k + 1 < N) out.sup[(size_t)k] = dphi * kr;
  }
}

double specimen_force(const Specimen &s, const SpecimenState &st, const Drive &d) {
  double dF = 0.0;
  double F = elastic_force(s, stiffness_scale(s, d.t), st.xb, st.y[0], st.xb_max, &dF);
  for (size_t j = 0; j < s.branches.size(); ++j) F += s.branches[j].k * (st.xb - st.q[j]);
  if (st.contact) F += s.viscous * d.v;  // a held end at rest in its gap has xb' = 0
  return F + s.mass * d.a;
}

}  // namespace refgen
