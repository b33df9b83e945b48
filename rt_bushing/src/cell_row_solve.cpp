/* cell_row_solve.cpp -- the Gauss-Seidel pass of cell_row_solve.h. */
#include "cell_row_solve.h"

#include "no_heap.h"

extern "C" int rtb_cell_gauss_seidel(const rtb_law *L, int n, rtb_real hK0, rtb_real hKr,
                                     const rtb_real *r, const rtb_real *v0, rtb_real *f,
                                     rtb_real *v, rtb_real *D) {
  int total = 0;
  for (int k = 0; k < n; ++k) {
    const rtb_real a = k == 0 ? hK0 : 2.0 * hKr;
    const rtb_real b = r[k] + hKr * ((k > 0 ? v[k - 1] : 0.0) + (k + 1 < n ? v0[k + 1] : 0.0));
    int evals;
    v[k] = rtb_cell_row_solve(L, a, b, RTB_ROW_SOLVE_EVALS, &f[k], &D[k], &evals);
    total += evals;
  }
  return total;
}
