#include "src/solver/serial_vector_ops.hpp"

#include <cmath>

namespace panoptic {
namespace {

sunindextype len(N_Vector v) { return NV_LENGTH_S(v); }
double* data(N_Vector v) { return NV_DATA_S(v); }

// z = a x + b y. N_VLinearSum_Serial's special cases (a or b = +-1: axpy, sum,
// difference, Lin1, Lin2) all equal a x + b y bit for bit (a product by +-1 is exact and
// the sum commutes); only a == b, taken as a (x + y), and a == -b, as a (x - y), round
// differently, and are kept. z may be x or y: each element is read before it is written.
extern "C" void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  const double* yd = data(y);
  double* zd = data(z);
  const bool a_unit = a == 1.0 || a == -1.0, b_unit = b == 1.0 || b == -1.0;
  if (!a_unit && !b_unit && a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (!a_unit && !b_unit && a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = (a * xd[i]) + (b * yd[i]);
  }
}

extern "C" void constant(double c, N_Vector z) {
  const sunindextype n = len(z);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

extern "C" void product(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

extern "C" void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}

// z = c x, with the library's cases: in place x *= c; else a copy for c = 1 and a
// negation for c = -1 (which differ from the products only for NaN: -x flips its sign)
extern "C" void scale(double c, N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  if (z == x) {
    for (sunindextype i = 0; i < n; ++i) zd[i] *= c;
  } else if (c == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i];
  } else if (c == -1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = -xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
  }
}

extern "C" void absolute(N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]);
}

extern "C" void inverse(N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

extern "C" void add_constant(N_Vector x, double b, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

// Reductions in the library's order (one running sum, first element first).
extern "C" double dot_product(N_Vector x, N_Vector y) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

extern "C" double max_norm(N_Vector x) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double max = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (std::fabs(xd[i]) > max) max = std::fabs(xd[i]);
  return max;
}

extern "C" double minimum(N_Vector x) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double min = xd[0];
  for (sunindextype i = 1; i < n; ++i)
    if (xd[i] < min) min = xd[i];
  return min;
}

extern "C" double weighted_l2_norm(N_Vector x, N_Vector w) {
  const sunindextype n = len(x);
  const double *xd = data(x), *wd = data(w);
  double sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  return std::sqrt(sum);
}

extern "C" double l1_norm(N_Vector x) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += std::fabs(xd[i]);
  return sum;
}

extern "C" void compare(double c, N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]) >= c ? 1.0 : 0.0;
}

extern "C" sunbooleantype inverse_test(N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  sunbooleantype no_zero = SUNTRUE;
  for (sunindextype i = 0; i < n; ++i) {
    if (xd[i] == 0.0)
      no_zero = SUNFALSE;
    else
      zd[i] = 1.0 / xd[i];
  }
  return no_zero;
}

// m_i = 1 where x_i breaks constraint c_i (|c| = 2: x > 0; |c| = 1: x >= 0, signed)
extern "C" sunbooleantype constraint_mask(N_Vector c, N_Vector x, N_Vector m) {
  const sunindextype n = len(x);
  const double *cd = data(c), *xd = data(x);
  double* md = data(m);
  bool violated = false;
  for (sunindextype i = 0; i < n; ++i) {
    md[i] = 0.0;
    if (cd[i] == 0.0) continue;
    if ((std::fabs(cd[i]) > 1.5 && xd[i] * cd[i] <= 0.0) ||
        (std::fabs(cd[i]) > 0.5 && xd[i] * cd[i] < 0.0)) {
      md[i] = 1.0;
      violated = true;
    }
  }
  return violated ? SUNFALSE : SUNTRUE;
}

extern "C" double min_quotient(N_Vector num, N_Vector denom) {
  const sunindextype n = len(num);
  const double *nd = data(num), *dd = data(denom);
  bool none_yet = true;
  double min = BIG_REAL;
  for (sunindextype i = 0; i < n; ++i) {
    if (dd[i] == 0.0) continue;
    const double q = nd[i] / dd[i];
    if (none_yet) {
      min = q;
      none_yet = false;
    } else {
      min = min < q ? min : q;  // SUNMIN, NaN included
    }
  }
  return min;
}

}  // namespace

void install_serial_vector_ops(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvdiv = quotient;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = add_constant;
  ops->nvdotprod = dot_product;
  ops->nvmaxnorm = max_norm;
  ops->nvmin = minimum;
  ops->nvwl2norm = weighted_l2_norm;
  ops->nvl1norm = l1_norm;
  ops->nvcompare = compare;
  ops->nvinvtest = inverse_test;
  ops->nvconstrmask = constraint_mask;
  ops->nvminquotient = min_quotient;
}

}  // namespace panoptic
