#ifndef talus_structure_line_elements_h
#define talus_structure_line_elements_h

#include <talus/structure/axial_law.h>

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <string>

namespace Talus
{
  /**
   * The barrier structure: membranes, trusses, cables, sliding cables and
   * brakes in one geometrically nonlinear, total-Lagrangian finite element
   * model (doc/architecture.md, doc/theory.md "Barrier structures").
   */
  namespace Structure
  {
    /**
     * History of one two-node element, committed at the end of a converged
     * load or time step.
     */
    struct LineState
    {
      /** Plastic strain in the truss's strain measure (Truss) or plastic
       * elongation, the brake stroke (Brake) [-] or [m]. */
      double plastic = 0.;
      /** Accumulated plastic strain alpha (Truss) [-]; dissipated energy
       * (Brake) [J]. */
      double accumulated = 0.;
    };


    /**
     * What a two-node element returns for the current positions: the axial
     * force, the nodal internal forces f = N [-e; e] (dofs ordered node 0
     * x,y,z then node 1 x,y,z), the tangent dF/dx (6x6) and the trial
     * history.
     */
    struct LineResponse
    {
      LineResponse();

      double force  = 0.; ///< axial force N [N]
      double energy = 0.; ///< stored elastic energy [J]
      /** Strain in the element's measure: Green-Lagrange (l^2-L^2)/(2L^2)
       * or engineering (l - l0)/l0 [-]. */
      double                     strain = 0.;
      bool                       slack  = false;
      dealii::Vector<double>     f;
      dealii::FullMatrix<double> K;
      LineState                  state;
    };


    /**
     * Interface of a two-node line element (one cell of a
     * Triangulation<1,3>). X0, X1: reference positions, x0, x1: current
     * positions.
     */
    class LineElement
    {
    public:
      virtual ~LineElement() = default;

      /** Name for messages and output ("truss", "cable", "brake"). */
      virtual std::string
      name() const = 0;

      /** Mass per reference length rho A [kg/m]. */
      virtual double
      mass_per_length() const = 0;

      virtual void
      compute(const dealii::Tensor<1, 3> &X0,
              const dealii::Tensor<1, 3> &X1,
              const dealii::Tensor<1, 3> &x0,
              const dealii::Tensor<1, 3> &x1,
              const LineState            &old_state,
              LineResponse               &response) const = 0;

      /**
       * Energy dissipated by the element up to the history @p state [J]:
       * 0 for elastic elements (the default).
       */
      virtual double
      dissipated_energy(const dealii::Tensor<1, 3> &X0,
                        const dealii::Tensor<1, 3> &X1,
                        const LineState            &state) const;

      /**
       * Stiffness added to the tangent (never to the forces) of a slack
       * element, as a fraction of the axial stiffness EA/L, so that a net
       * whose cables go slack does not make the Newton matrix singular
       * [-]. The converged state is not affected: the residual contains no
       * such force. A cable taut at zero force (l = l0 exactly, N = 0) has
       * the axial tangent dN/dl of the tension side and this stiffness
       * across (the geometric stiffness N/l is zero there), so that a
       * straight stress-free cable does not make the matrix singular.
       */
      double slack_stiffness_ratio = 1e-8;

    protected:
      /**
       * f and K of an axial force N with tangent dN/dl at current length l
       * along e: K = dN/dl e e^T + N/l (I - e e^T), blocks [[K,-K],[-K,K]].
       */
      static void
      assemble_axial(const dealii::Tensor<1, 3> &e,
                     const double                l,
                     const double                N,
                     const double                dN_dl,
                     LineResponse               &response);

      /** f = 0, K = k_reg (I) blocks, for a slack element. */
      static void
      assemble_slack(const double k_reg, LineResponse &response);

      /** Adds k_reg (I - e e^T) blocks to K, for an element taut at zero
       * force (see slack_stiffness_ratio). */
      static void
      add_transverse(const double                k_reg,
                     const dealii::Tensor<1, 3> &e,
                     LineResponse               &response);
    };


    /**
     * Total-Lagrangian truss (bar) with PK2 pre-stress and 1D elasto-plasticity
     * with linear isotropic hardening in Green-Lagrange strain / PK2 stress:
     *   eps = (l^2 - L^2)/(2 L^2),  S = E (eps - eps_p) + sigma_0,
     *   |S| <= sigma_y + H alpha,  N = A S l / L,  f = N [-e; e],
     *   K = (E_t A l^2/L^3) e e^T + (A S / L) I   (E_t = E or E H/(E+H)).
     * With strain_measure = engineering: eps = (l - l0)/l0 on the
     * unstretched length l0 = L/(1 + sigma_0/E), S = E (eps - eps_p) (S =
     * sigma_0 at l = L), N = A S, K = (E_t A/l0) e e^T + (N/l) (I - e e^T).
     * Works in tension and compression (no buckling). Source: Crisfield
     * (1991) vol. 1 ch. 3; NOTES-structures-coupling.md section 2.1; return
     * mapping of Simo & Hughes (1998) ch. 1.
     */
    class Truss : public LineElement
    {
    public:
      double youngs_modulus = 0.; ///< E [Pa]
      double area           = 0.; ///< A [m^2]
      double prestress      = 0.; ///< sigma_0, PK2 [Pa]
      double density        = 0.; ///< rho [kg/m^3]
      double yield_stress   = 0.; ///< sigma_y [Pa]; 0: elastic
      double hardening      = 0.; ///< H [Pa]
      /** Axial law (AxialLaw); yield_stress and hardening apply to S of
       * that measure. */
      StrainMeasure strain_measure = StrainMeasure::green_lagrange;

      std::string
      name() const override;

      double
      mass_per_length() const override;

      void
      compute(const dealii::Tensor<1, 3> &X0,
              const dealii::Tensor<1, 3> &X1,
              const dealii::Tensor<1, 3> &x0,
              const dealii::Tensor<1, 3> &x1,
              const LineState            &old_state,
              LineResponse               &response) const override;
      /** Plastic work A L (sigma_y alpha + H alpha^2 / 2) [J] (the stress
       * stays on the yield surface while alpha grows). */
      double
      dissipated_energy(const dealii::Tensor<1, 3> &X0,
                        const dealii::Tensor<1, 3> &X1,
                        const LineState            &state) const override;
    };


    /**
     * Tension-only elastic cable with the axial law N(lambda) of AxialLaw,
     * lambda = l/L:
     *   Green-Lagrange (default): the truss law of Truss without
     *     plasticity, N = A (E (l^2 - L^2)/(2 L^2) + sigma_0) l/L,
     *   engineering: N = EA (l - l0)/l0, l0 = L/(1 + sigma_0/E) the
     *     unstretched length, dN/dl = EA/l0, W = EA (l - l0)^2/(2 l0);
     * f = N [-e; e], K = dN/dl e e^T + (N/l) (I - e e^T) (assemble_axial).
     * N < 0 gives a slack cable with no force and no stiffness (Kratos
     * CableElement3D2N; NOTES-structures-coupling.md section 2.1); at N =
     * 0 exactly the taut tangent is used, so that a stress-free cable
     * starts taut for Newton, with the regularising stiffness across (see
     * slack_stiffness_ratio). A straight cable in tension has the lateral
     * stiffness N/l.
     */
    class Cable : public LineElement
    {
    public:
      double youngs_modulus = 0.; ///< E [Pa]
      double area           = 0.; ///< A [m^2]
      double prestress      = 0.; ///< sigma_0, PK2 [Pa]
      double density        = 0.; ///< rho [kg/m^3]
      /** Axial law (AxialLaw). */
      StrainMeasure strain_measure = StrainMeasure::green_lagrange;

      std::string
      name() const override;

      double
      mass_per_length() const override;

      void
      compute(const dealii::Tensor<1, 3> &X0,
              const dealii::Tensor<1, 3> &X1,
              const dealii::Tensor<1, 3> &x0,
              const dealii::Tensor<1, 3> &x1,
              const LineState            &old_state,
              LineResponse               &response) const override;

      /** The axial law of this cable. */
      AxialLaw
      law() const;
    };


    /**
     * Brake (energy dissipating element): an elasto-plastic, tension-only
     * spring in the elongation d = l - L,
     *   N = k_e (d - s) >= 0,  N <= F_a + H s,  0 <= s <= s_max,
     * with stroke s (plastic elongation), activation force F_a, hardening H
     * and stroke limit s_max, after which the brake is blocked and behaves
     * elastically with k_e. Dissipated energy D = F_a s + H s^2 / 2 (summed
     * increment by increment). Slack (d < s): N = 0 (at d = s the elastic
     * tangent is used, so that a stress-free brake starts taut). The law
     * is linear in the elongation (an engineering law on the length L
     * of the element); it has no strain measure to choose. Return mapping
     * as in NOTES-structures-coupling.md section 2.4.
     */
    class Brake : public LineElement
    {
    public:
      double stiffness        = 0.; ///< k_e [N/m]
      double activation_force = 0.; ///< F_a [N]
      double hardening        = 0.; ///< H [N/m]
      double stroke_limit     = 0.; ///< s_max [m]; 0: unlimited
      double mass             = 0.; ///< rho A [kg/m]

      std::string
      name() const override;

      double
      mass_per_length() const override;

      void
      compute(const dealii::Tensor<1, 3> &X0,
              const dealii::Tensor<1, 3> &X1,
              const dealii::Tensor<1, 3> &x0,
              const dealii::Tensor<1, 3> &x1,
              const LineState            &old_state,
              LineResponse               &response) const override;
      /** The work F_a s + H s^2 / 2 of the stroke s [J]. */
      double
      dissipated_energy(const dealii::Tensor<1, 3> &X0,
                        const dealii::Tensor<1, 3> &X1,
                        const LineState            &state) const override;
    };
  } // namespace Structure
} // namespace Talus

#endif
