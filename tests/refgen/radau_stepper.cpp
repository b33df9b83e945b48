// radau_stepper.cpp -- one fine step of the specimen by the 2-stage Radau IIA
// collocation method (order 3, L-stable, stiffly accurate; Hairer & Wanner,
// Solving ODEs II, IV.5), applied to the primal cell ODE y' = phi(b - K y) of
// eq. (2) with full Newton on the stage increments Z_i = Y_i - y_n:
//   Z_i - h sum_j a_ij f(t + c_j h, y_n + Z_j) = 0.
// Interleaving (Z1_k, Z2_k) per cell makes the Newton matrix block
// tridiagonal with 2x2 blocks (K is tridiagonal), solved in O(N).
// The linear Maxwell branches q' = (xb - q)/tau use the same tableau.
#include <array>
#include <cmath>

#include "specimen_model.h"

namespace refgen {
namespace {

constexpr double kA[2][2] = {{5.0 / 12.0, -1.0 / 12.0}, {3.0 / 4.0, 1.0 / 4.0}};
constexpr double kC[2] = {1.0 / 3.0, 1.0};

using Block = std::array<double, 4>;  // row-major 2x2
using Vec2 = std::array<double, 2>;

Block mul(const Block &a, const Block &b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3],
          a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3]};
}
Vec2 mul(const Block &a, const Vec2 &v) { return {a[0] * v[0] + a[1] * v[1], a[2] * v[0] + a[3] * v[1]}; }
Block inverse(const Block &a) {
  const double det = a[0] * a[3] - a[1] * a[2];
  return {a[3] / det, -a[1] / det, -a[2] / det, a[0] / det};
}

// Block-tridiagonal solve (block Thomas): L[k] couples row k to k-1, U[k] to
// k+1. Overwrites D and r; the solution is returned in r.
void solve_block_tridiagonal(std::vector<Block> &L, std::vector<Block> &D, std::vector<Block> &U,
                             std::vector<Vec2> &r) {
  const size_t n = D.size();
  for (size_t k = 1; k < n; ++k) {
    const Block m = mul(L[k], inverse(D[k - 1]));
    const Block mu = mul(m, U[k - 1]);
    for (int i = 0; i < 4; ++i) D[k][(size_t)i] -= mu[(size_t)i];
    const Vec2 mr = mul(m, r[k - 1]);
    r[k] = {r[k][0] - mr[0], r[k][1] - mr[1]};
  }
  r[n - 1] = mul(inverse(D[n - 1]), r[n - 1]);
  for (size_t k = n - 1; k-- > 0;) {
    const Vec2 ur = mul(U[k], r[k + 1]);
    r[k] = mul(inverse(D[k]), Vec2{r[k][0] - ur[0], r[k][1] - ur[1]});
  }
}

// Newton matrix block of cells (k, l) from the stage Jacobian entries j1, j2.
Block newton_block(double h, bool same, double j1, double j2) {
  const double I = same ? 1.0 : 0.0;
  return {I - h * kA[0][0] * j1, -h * kA[0][1] * j2, -h * kA[1][0] * j1, I - h * kA[1][1] * j2};
}

// Branch stages: (I + (h/tau) A) Q = q 1 + (h/tau) A xb, a 2x2 solve; the
// step ends at Q2 (stiffly accurate).
double branch_step(double q, double tau, double h, const double xb[2]) {
  const double g = h / tau;
  const Block M = {1.0 + g * kA[0][0], g * kA[0][1], g * kA[1][0], 1.0 + g * kA[1][1]};
  const Vec2 rhs = {q + g * (kA[0][0] * xb[0] + kA[0][1] * xb[1]),
                    q + g * (kA[1][0] * xb[0] + kA[1][1] * xb[1])};
  return mul(inverse(M), rhs)[1];
}

}  // namespace

bool radau_step(const Specimen &s, SpecimenState &st, double t, double h, const Drive d[2]) {
  const size_t N = (size_t)s.N;
  std::vector<double> Z[2], Y[2];
  for (int i = 0; i < 2; ++i) {  // predictor: the last velocities
    Z[i].resize(N);
    Y[i].resize(N);
    for (size_t k = 0; k < N; ++k) Z[i][k] = kC[i] * h * st.v[k];
  }
  CellRates rate[2];
  std::vector<Block> L(N), D(N), U(N);
  std::vector<Vec2> r(N);
  double scale = 0.0;
  for (double y : st.y) scale = std::fmax(scale, std::fabs(y));
  const double tol = 1e-12 * (1.0 + scale);  // [mm]
  bool converged = false;
  for (int it = 0; it < 30 && !converged; ++it) {
    for (int i = 0; i < 2; ++i) {
      for (size_t k = 0; k < N; ++k) Y[i][k] = st.y[k] + Z[i][k];
      // A held end moves as a play operator: stage 2 continues from stage 1.
      const double xb_prev = i == 0 ? st.xb : rate[0].end.xb;
      cell_rates(s, t + kC[i] * h, d[i].x, xb_prev, st.xb_max, Y[i].data(), rate[i]);
    }
    for (size_t k = 0; k < N; ++k) {
      for (int i = 0; i < 2; ++i)  // minus the residual of stage i
        r[k][(size_t)i] = -(Z[i][k] - h * (kA[i][0] * rate[0].v[k] + kA[i][1] * rate[1].v[k]));
      L[k] = newton_block(h, false, rate[0].sub[k], rate[1].sub[k]);
      D[k] = newton_block(h, true, rate[0].diag[k], rate[1].diag[k]);
      U[k] = newton_block(h, false, rate[0].sup[k], rate[1].sup[k]);
    }
    solve_block_tridiagonal(L, D, U, r);
    double step = 0.0;
    for (size_t k = 0; k < N; ++k)
      for (int i = 0; i < 2; ++i) {
        Z[i][k] += r[k][(size_t)i];
        step = std::fmax(step, std::fabs(r[k][(size_t)i]));
      }
    if (!std::isfinite(step)) return false;
    converged = step <= tol;
  }
  if (!converged) return false;
  // Commit: y_{n+1} = Y2, the end position and memories at t + h.
  CellRates end;
  for (size_t k = 0; k < N; ++k) Y[1][k] = st.y[k] + Z[1][k];
  cell_rates(s, t + h, d[1].x, rate[0].end.xb, st.xb_max, Y[1].data(), end);
  const double xb_stage[2] = {rate[0].end.xb, end.end.xb};
  for (size_t j = 0; j < s.branches.size(); ++j)
    st.q[j] = branch_step(st.q[j], s.branches[j].tau, h, xb_stage);
  st.y = Y[1];
  st.v = end.v;
  st.xb = end.end.xb;
  st.contact = end.end.contact;
  st.xb_max = std::fmax(st.xb_max, std::fabs(st.xb));
  return true;
}

}  // namespace refgen
