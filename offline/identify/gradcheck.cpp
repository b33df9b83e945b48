// gradcheck.cpp -- see gradcheck.h.
#include "identify/gradcheck.h"

#include <cmath>

namespace rtb {

GradcheckResult gradcheck(const rtb_params &p, const std::vector<Record> &recs,
                          MisfitOptions opt, std::vector<ParamId> ids) {
  opt.sim.tol = 1e-15;  // resolve the discrete map to rounding level
  if (ids.empty())
    for (int i = 0; i < P_COUNT; ++i)
      if (param_get(p, ParamId(i)) != 0.0) ids.push_back(ParamId(i));
  GradcheckResult out;
  const MisfitValue m = misfit(p, recs, opt, true);
  out.J = m.J;
  double gmax = 0.0;
  for (ParamId id : ids) gmax = std::fmax(gmax, std::fabs(m.grad[id] * param_get(p, id)));
  for (ParamId id : ids) {
    const double v = param_get(p, id);
    auto J_at = [&](double h) {
      rtb_params q = p;
      param_ref(q, id) = v + h;
      return misfit(q, recs, opt, false).J;
    };
    // Relative step 1e-4: large enough that J's rounding (~1e-16 J) is
    // negligible, small enough that Richardson's O(h^4) error is too.
    const double h = 1e-4 * (v != 0.0 ? std::fabs(v) : 1.0);
    const double d1 = (J_at(h) - J_at(-h)) / (2.0 * h);
    const double d2 = (J_at(0.5 * h) - J_at(-0.5 * h)) / h;
    const double fd = (4.0 * d2 - d1) / 3.0;
    // Compare in the scaled variable p_i dJ/dp_i: a component far below the
    // others' scale is judged against 1e-8 of the largest.
    const double floor = 1e-8 * gmax / std::fabs(v != 0.0 ? v : 1.0);
    const double rel = std::fabs(m.grad[id] - fd) / std::fmax(std::fabs(fd), floor);
    out.rows.push_back({id, m.grad[id], fd, rel});
    out.max_rel_diff = std::fmax(out.max_rel_diff, rel);
  }
  double worst = 0.0;
  for (const Record &rec : recs)
    worst = std::fmax(worst, dot_product_test(p, rec, opt.sim, 12345u));
  out.dot_product_rel_mismatch = worst;
  return out;
}

}  // namespace rtb
