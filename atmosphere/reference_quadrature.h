#pragma once
// Gauss–Kronrod quadrature for the CPU reference (docs/reference.md, "Quadrature").
//
// The 15-point Kronrod rule K15 and its embedded 7-point Gauss rule G7 on [-1, 1] (Kronrod 1965;
// the digits are QUADPACK's qk15). K15 integrates polynomials of degree 22 exactly, G7 of degree 13;
// |K15 - G7| bounds the error of G7 and, very pessimistically, of K15, which is what the adaptive
// integrators accept a panel on.
//
// The cumulative ("spectral integration") matrix gives the integral from the left end of a panel to
// each of its 15 nodes from the same 15 function values: with l_k the Lagrange basis polynomial of
// node k (degree 14),
//   ∫_{-1}^{x_i} f(x) dx  ≈  Σ_k S[i][k] f(x_k),   S[i][k] = ∫_{-1}^{x_i} l_k(x) dx,
// exact for polynomials of degree 14. The reference needs the optical depth from the start of a
// panel to every node of that panel (transmittance along the view ray at each in-scattering point);
// this costs no extra evaluations of the medium.
#include <array>

namespace firmament::reference {

inline constexpr int kKronrodPoints = 15;

struct GaussKronrod15 {
  // Nodes in increasing order on [-1, 1], K15 weights, and G7 weights (zero at the 8 Kronrod-only
  // nodes).
  std::array<double, kKronrodPoints> nodes;
  std::array<double, kKronrodPoints> kronrodWeights;
  std::array<double, kKronrodPoints> gaussWeights;
  // cumulative[i][k] = ∫_{-1}^{nodes[i]} l_k(x) dx (see above).
  std::array<std::array<double, kKronrodPoints>, kKronrodPoints> cumulative;
};

// The rule, built once (thread-safe static initialisation).
const GaussKronrod15& gaussKronrod15();

}  // namespace firmament::reference
