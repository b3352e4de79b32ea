#ifndef talus_structure_sliding_cable_h
#define talus_structure_sliding_cable_h

#include <talus/structure/axial_law.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace Talus
{
  namespace Structure
  {
    /**
     * A cable running through nodes 0..n without friction (shackles,
     * rings, pulleys): one uniform tension along the whole cable.
     * With segment lengths L_i (reference) and l_i (current), L = sum L_i,
     * l = sum l_i, e_i = (x_{i+1} - x_i)/l_i:
     *   eps = (l^2 - L^2)/(2 L^2),  S = E eps + sigma_0,  N = A S l / L,
     *   f = N g,  g_0 = -e_0,  g_k = e_{k-1} - e_k,  g_n = e_{n-1},
     *   K = (E A l^2/L^3 + A S/L) g g^T
     *       + N sum_i (I - e_i e_i^T)/l_i [[1,-1],[-1,1]] on segment i.
     * With strain_measure = engineering the law of the whole cable is
     * N = EA (l - l0)/l0, l0 = L/(1 + sigma_0/E), and E A l^2/L^3 + A S/L
     * above becomes dN/dl = EA/l0 (AxialLaw; per segment with friction).
     * Tension only: N < 0 gives no force (slack). Source: Kratos
     * SlidingCableElement3D (K. B. Sautter); NOTES-structures-coupling.md
     * section 2.2. The interior nodes are the shackles; they slide freely
     * along the cable.
     */
    class SlidingCable
    {
    public:
      double youngs_modulus        = 0.;   ///< E [Pa]
      double area                  = 0.;   ///< A [m^2]
      double prestress             = 0.;   ///< sigma_0, PK2 [Pa]
      double density               = 0.;   ///< rho [kg/m^3]
      double slack_stiffness_ratio = 1e-8; ///< as LineElement [-]
      /** Axial law (AxialLaw). */
      StrainMeasure strain_measure = StrainMeasure::green_lagrange;
      /**
       * Capstan (Euler-Eytelwein) friction coefficient mu at the interior
       * nodes [-]; 0: frictionless. With mu > 0 the cable is assumed to
       * slide towards its last node (pulled there) at every node: the
       * segment tensions are N_i = N_0 prod_{k<=i} exp(mu theta_k), theta_k
       * the deviation angle at node k, and N_0 follows from the length of
       * cable material, sum_i l_i / lambda(N_i) = L, with lambda(N) the
       * stretch of the axial law (AxialLaw::stretch(), per segment). The
       * tangent is the analytic derivative of this map (add_tension_tangent()).
       * With stick_slip, the law with stick below (history dependent).
       */
      double friction_coefficient = 0.;

      /**
       * Stick-slip law of the capstan friction (with friction_coefficient
       * > 0): the history is the material (unstretched) length L_i of each
       * segment. An interior node k between segments k-1 and k sticks (no
       * material passes it) while the capstan inequality holds,
       *   exp(-mu theta_k) <= N_k / N_{k-1} <= exp(mu theta_k),
       * and slips at the limit otherwise, material moving towards the
       * higher tension, N_i = N(lambda_i) of the axial law (AxialLaw),
       * lambda_i = l_i / L_i (tension only). Return map: active
       * set over the nodes; a run of segments joined by slipping nodes
       * shares its material, N_i = N_a prod exp(+-mu theta), N_a from
       * sum l_i / lambda(N_i) = sum L_i^old (bisection); a slipping node
       * whose material moved against its slip direction sticks again.
       * Tangent: the exact derivative of the return for the final active
       * set (add_tension_tangent()), from the same committed history.
       * false: the cable slides towards its last node at every node (no
       * history).
       */
      bool stick_slip = false;

      /** Segment tensions of the last compute() with friction [N]. */
      mutable std::vector<double> segment_forces;

      /**
       * Nodal forces f (3 per node, node by node) and tangent K for the
       * reference positions @p X and current positions @p x of the nodes in
       * cable order. Returns the tension N [N].
       */
      double
      compute(const std::vector<dealii::Tensor<1, 3>> &X,
              const std::vector<dealii::Tensor<1, 3>> &x,
              dealii::Vector<double>                  &f,
              dealii::FullMatrix<double>              &K,
              double                                  *energy = nullptr) const;

      /** The axial law of this cable. */
      AxialLaw
      law() const;

      /**
       * As compute() with the stick-slip law (stick_slip, friction > 0):
       * @p old_lengths are the committed material lengths L_i of the
       * segments [m], @p new_lengths receives those of this state.
       */
      double
      compute(const std::vector<dealii::Tensor<1, 3>> &X,
              const std::vector<dealii::Tensor<1, 3>> &x,
              const std::vector<double>               &old_lengths,
              dealii::Vector<double>                  &f,
              dealii::FullMatrix<double>              &K,
              std::vector<double>                     &new_lengths) const;

    private:
      /** Internal forces with friction (see friction_coefficient); returns
       * N_0 and fills segment_forces. */
      double
      friction_forces(const std::vector<dealii::Tensor<1, 3>> &X,
                      const std::vector<dealii::Tensor<1, 3>> &x,
                      dealii::Vector<double>                  &f) const;

      /** Internal forces of the stick-slip law (see stick_slip); returns
       * N_0, fills segment_forces and @p new_lengths. */
      double
      stick_slip_forces(const std::vector<dealii::Tensor<1, 3>> &x,
                        const std::vector<double>               &old_lengths,
                        dealii::Vector<double>                  &f,
                        std::vector<double>                     &new_lengths,
                        std::vector<int> *slip = nullptr) const;

      /**
       * Adds the consistent tangent of the segment tensions @p N with
       * material lengths @p L to @p K (doc/theory.md, "Capstan friction:
       * consistent tangent"). @p slip[k] (k >= 1) is the slip direction
       * +-1 of interior node k, or 0 where it sticks: runs of segments
       * joined by slipping nodes share their material,
       *   N_i = N_a c_i,  c_i = prod_{a<k<=i} exp(s_k mu theta_k),
       *   sum_i l_i / lambda(N_i) = sum_i L_i (fixed),
       * and a stuck segment has N_i = N(l_i / L_i) with L_i fixed. The
       * derivative of the constraint gives dN_a, the chain rule dN_i.
       */
      void
      add_tension_tangent(const std::vector<dealii::Tensor<1, 3>> &x,
                          const std::vector<double>               &L,
                          const std::vector<double>               &N,
                          const std::vector<int>                  &slip,
                          dealii::FullMatrix<double>              &K) const;
    };
  } // namespace Structure
} // namespace Talus

#endif
