#include "atmosphere/reference_quadrature.h"

namespace firmament::reference {
namespace {

// QUADPACK qk15: abscissae of K15 on [0, 1) (the rule is symmetric) and their weights. Odd indices
// (1, 3, 5, 7 counted from the outside) are the G7 nodes.
constexpr double kHalfNodes[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                  0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                  0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                  0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr double kHalfKronrodWeights[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                           0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                           0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                           0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kHalfGaussWeights[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                         0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

GaussKronrod15 buildRule() {
  GaussKronrod15 rule{};
  // Nodes in increasing order: -x_0, -x_1, ..., -x_6, 0, x_6, ..., x_0.
  for (int j = 0; j < 8; ++j) {
    const int left = j;        // -kHalfNodes[j]
    const int right = 14 - j;  // +kHalfNodes[j]
    rule.nodes[left] = -kHalfNodes[j];
    rule.nodes[right] = kHalfNodes[j];
    rule.kronrodWeights[left] = rule.kronrodWeights[right] = kHalfKronrodWeights[j];
    const double gauss = (j % 2 == 1) ? kHalfGaussWeights[j / 2] : 0.0;
    rule.gaussWeights[left] = rule.gaussWeights[right] = gauss;
  }
  // S[i][k] = ∫_{-1}^{x_i} l_k(x) dx. l_k has degree 14, so K15 mapped onto [-1, x_i] integrates it
  // exactly (up to rounding): ∫_{-1}^{x_i} g = (x_i + 1)/2 Σ_m w_m g(-1 + (x_i + 1)(y_m + 1)/2).
  auto lagrange = [&](int k, double x) {
    double value = 1.0;
    for (int m = 0; m < kKronrodPoints; ++m)
      if (m != k) value *= (x - rule.nodes[m]) / (rule.nodes[k] - rule.nodes[m]);
    return value;
  };
  for (int i = 0; i < kKronrodPoints; ++i) {
    const double halfLength = 0.5 * (rule.nodes[i] + 1.0);
    for (int k = 0; k < kKronrodPoints; ++k) {
      double sum = 0.0;
      for (int m = 0; m < kKronrodPoints; ++m) {
        const double y = -1.0 + halfLength * (rule.nodes[m] + 1.0);
        sum += rule.kronrodWeights[m] * lagrange(k, y);
      }
      rule.cumulative[i][k] = halfLength * sum;
    }
  }
  return rule;
}

}  // namespace

const GaussKronrod15& gaussKronrod15() {
  static const GaussKronrod15 rule = buildRule();
  return rule;
}

}  // namespace firmament::reference
