#include "robocore/collision/small_lp.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

using Mat4 = std::array<LpVector, kLpUnknowns>;

// Rows are unit normals with a 1 appended (or of similar size), so an
// absolute pivot threshold tells dependent rows from steep ones.
constexpr long double kSingularPivot = 1e-17L;
constexpr long double kRelativeZero = 1e-15L;  // "zero" for directions and multipliers
constexpr int kMaxPivots = 200;  // far above the ~10 a 4-unknown LP needs; a guard against round-off loops

long double Dot(const LpVector& a, const LpVector& b) {
  long double s = 0;
  for (int i = 0; i < kLpUnknowns; ++i) s += a[i] * b[i];
  return s;
}

long double MaxAbs(const LpVector& v) {
  long double m = 0;
  for (long double x : v) m = std::max(m, std::fabs(x));
  return m;
}

// Gauss-Jordan with partial pivoting; false if singular.
bool Invert(Mat4 m, Mat4& inv) {
  for (int r = 0; r < kLpUnknowns; ++r)
    for (int c = 0; c < kLpUnknowns; ++c) inv[r][c] = r == c ? 1 : 0;
  for (int c = 0; c < kLpUnknowns; ++c) {
    int pivot = c;
    for (int r = c + 1; r < kLpUnknowns; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (std::fabs(m[pivot][c]) < kSingularPivot) return false;
    std::swap(m[c], m[pivot]);
    std::swap(inv[c], inv[pivot]);
    const long double d = m[c][c];
    for (int k = 0; k < kLpUnknowns; ++k) m[c][k] /= d, inv[c][k] /= d;
    for (int r = 0; r < kLpUnknowns; ++r) {
      if (r == c || m[r][c] == 0) continue;
      const long double f = m[r][c];
      for (int k = 0; k < kLpUnknowns; ++k) m[r][k] -= f * m[c][k], inv[r][k] -= f * inv[c][k];
    }
  }
  return true;
}

// The first row not yet active that z + t p runs into (smallest t, then
// smallest index: Bland's entering rule); -1 if none.
int RatioTest(const std::vector<LpRow>& rows, const std::vector<bool>& active, const LpVector& z, const LpVector& p,
              long double& step) {
  const long double p_zero = kRelativeZero * MaxAbs(p);
  int entering = -1;
  for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
    if (active[k]) continue;
    const long double rate = Dot(rows[k].normal, p);
    if (rate <= p_zero) continue;
    const long double t = std::max(0.0L, rows[k].rhs - Dot(rows[k].normal, z)) / rate;
    if (entering < 0 || t < step) entering = k, step = t;
  }
  return entering;
}

void Advance(LpVector& z, const LpVector& p, long double t) {
  for (int i = 0; i < kLpUnknowns; ++i) z[i] += t * p[i];
}

// Component of v orthogonal to the orthonormal vectors q.
LpVector Orthogonal(LpVector v, const std::vector<LpVector>& q) {
  for (const LpVector& u : q) {
    const long double f = Dot(u, v);
    for (int i = 0; i < kLpUnknowns; ++i) v[i] -= f * u[i];
  }
  return v;
}

}  // namespace

LpSolution MaximizeBySimplex(const std::vector<LpRow>& rows, const LpVector& c, const LpVector& start,
                             long double feasibility_tolerance) {
  LpSolution out;
  LpVector z = start;
  std::vector<bool> active(rows.size(), false);
  std::vector<int> basis;
  // Phase 0: from the feasible start to a vertex, never lowering c . z. Each
  // step moves in the null space of the active rows (uphill if possible) to
  // the first row it meets, which then joins them.
  std::vector<LpVector> q;  // orthonormal basis of the active rows
  while (static_cast<int>(basis.size()) < kLpUnknowns) {
    LpVector p = Orthogonal(c, q);
    bool level = false;
    if (MaxAbs(p) < kRelativeZero * std::max(1.0L, MaxAbs(c))) {  // c is in the active rows' span
      level = true;
      long double best = -1;
      for (int e = 0; e < kLpUnknowns; ++e) {
        LpVector unit{};
        unit[e] = 1;
        const LpVector candidate = Orthogonal(unit, q);
        if (MaxAbs(candidate) > best) best = MaxAbs(candidate), p = candidate;
      }
    }
    long double t = 0;
    int k = RatioTest(rows, active, z, p, t);
    if (k < 0 && level) {  // objective-neutral: the other way must meet a row (no lines)
      for (long double& x : p) x = -x;
      k = RatioTest(rows, active, z, p, t);
    }
    if (k < 0) return out;  // unbounded or lines in the feasible set
    Advance(z, p, t);
    active[k] = true;
    basis.push_back(k);
    LpVector u = Orthogonal(rows[k].normal, q);
    const long double norm = std::sqrt(Dot(u, u));
    if (norm < kSingularPivot) return out;
    for (long double& x : u) x /= norm;
    q.push_back(u);
  }
  // Phase 1: vertex to vertex. Multipliers mu solve A_B^T mu = c; a
  // negative one names a row to leave (lowest index: Bland), and the move
  // keeps the other three active.
  for (out.pivots = 0; out.pivots <= kMaxPivots; ++out.pivots) {
    Mat4 a, inv;
    for (int i = 0; i < kLpUnknowns; ++i) a[i] = rows[basis[i]].normal;
    if (!Invert(a, inv)) return out;
    LpVector mu{};
    for (int i = 0; i < kLpUnknowns; ++i)
      for (int j = 0; j < kLpUnknowns; ++j) mu[i] += inv[j][i] * c[j];
    const long double mu_zero = kRelativeZero * std::max(1.0L, MaxAbs(mu));
    int leaving = -1;
    for (int i = 0; i < kLpUnknowns; ++i)
      if (mu[i] < -mu_zero && (leaving < 0 || basis[i] < basis[leaving])) leaving = i;
    if (leaving < 0) {
      // Optimal. Recompute the vertex from its rows rather than keep the
      // sum of all steps' round-off.
      for (int i = 0; i < kLpUnknowns; ++i) {
        z[i] = 0;
        for (int j = 0; j < kLpUnknowns; ++j) z[i] += inv[i][j] * rows[basis[j]].rhs;
      }
      for (const LpRow& row : rows)
        if (Dot(row.normal, z) > row.rhs + feasibility_tolerance) return out;
      out.solved = true;
      out.z = z;
      out.value = Dot(c, z);
      return out;
    }
    LpVector p;
    for (int j = 0; j < kLpUnknowns; ++j) p[j] = -inv[j][leaving];
    long double t = 0;
    const int k = RatioTest(rows, active, z, p, t);
    if (k < 0) return out;
    Advance(z, p, t);
    active[basis[leaving]] = false;
    active[k] = true;
    basis[leaving] = k;
  }
  return out;
}

LpSolution MaximizeByVertexEnumeration(const std::vector<LpRow>& rows, const LpVector& c,
                                       long double feasibility_tolerance) {
  LpSolution out;
  out.enumerated = true;
  const int n = static_cast<int>(rows.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int d = b + 1; d < n; ++d)
        for (int e = d + 1; e < n; ++e) {
          const int chosen[kLpUnknowns] = {a, b, d, e};
          Mat4 m, inv;
          for (int i = 0; i < kLpUnknowns; ++i) m[i] = rows[chosen[i]].normal;
          if (!Invert(m, inv)) continue;
          LpVector z{};
          for (int i = 0; i < kLpUnknowns; ++i)
            for (int j = 0; j < kLpUnknowns; ++j) z[i] += inv[i][j] * rows[chosen[j]].rhs;
          const long double value = Dot(c, z);
          if (out.solved && value <= out.value) continue;
          bool feasible = true;
          for (const LpRow& row : rows)
            if (Dot(row.normal, z) > row.rhs + feasibility_tolerance) {
              feasible = false;
              break;
            }
          if (!feasible) continue;
          out.solved = true;
          out.z = z;
          out.value = value;
        }
  return out;
}

LpSolution SolveSmallLp(const std::vector<LpRow>& rows, const LpVector& c, const LpVector& start,
                        long double feasibility_tolerance) {
  LpSolution s = MaximizeBySimplex(rows, c, start, feasibility_tolerance);
  if (s.solved) return s;
  return MaximizeByVertexEnumeration(rows, c, feasibility_tolerance);
}

}  // namespace rc
