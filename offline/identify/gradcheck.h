// gradcheck.h -- adjoint gradient against central finite differences of the
// same discrete misfit, and the dot-product test of eq. (15)-(16).
#ifndef RTB_OFFLINE_GRADCHECK_H
#define RTB_OFFLINE_GRADCHECK_H

#include <vector>

#include "adjoint/misfit_gradient.h"

namespace rtb {

struct GradcheckRow {
  ParamId id;
  double adjoint, fd, rel;  // rel = |adjoint - fd| / max(|fd|, floor)
};
struct GradcheckResult {
  double J = 0.0;
  std::vector<GradcheckRow> rows;
  double max_rel_diff = 0.0;
  double dot_product_rel_mismatch = 0.0;
};

// Checks every parameter in `ids` (default: the nonzero ones). The stepper
// runs at a tight Newton tolerance so that the finite differences resolve
// the discrete map; FD are Richardson-extrapolated central differences.
GradcheckResult gradcheck(const rtb_params &p, const std::vector<Record> &recs,
                          MisfitOptions opt, std::vector<ParamId> ids = {});

}  // namespace rtb

#endif
