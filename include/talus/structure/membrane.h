#ifndef talus_structure_membrane_h
#define talus_structure_membrane_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <string>

namespace Talus
{
  namespace Structure
  {
    /**
     * Plane-stress St. Venant-Kirchhoff material of a membrane, isotropic
     * or orthotropic, with in-plane PK2 pre-stress and an optional
     * wrinkling (tension-field) law. Strains and stresses are in Voigt form
     * in the local orthonormal material axes {t1, t2} of the reference
     * surface: E = [E11, E22, 2 E12], S = [S11, S22, S12].
     *   S = C E + S_0,
     *   C = [[E1/D, nu12 E2/D, 0], [nu12 E2/D, E2/D, 0], [0, 0, G12]],
     *   D = 1 - nu12^2 E2/E1 (isotropic: E1 = E2 = E, G12 = E/(2(1+nu))).
     * Wrinkling (Kratos wrinkling_linear_2d_law; Raible et al. 2005): taut if
     * the smaller principal value of S is > 0; otherwise, with n the
     * direction of the minor principal stress and a = [n1^2, n2^2, 2 n1 n2],
     *   S_w = S - (a.S)/(a.C a) C a   (zero stress across the wrinkles),
     * wrinkled if S_w keeps a tension (its larger principal value > 0),
     * slack (S = 0, C = slack_stiffness_ratio C) if not. Since a.S_w = 0,
     * S_w vanishes where it loses its tension, so the stress is continuous
     * across all three states, also with a pre-stress S_0 (without S_0 and
     * isotropic, slack is the strain criterion eps_max <= 0 of Raible et
     * al.; with S_0 it is eps_max(E + C^-1 S_0) <= 0). The wrinkled tangent
     * is the consistent derivative dS_w/dE, the rotation of n with E
     * included (doc/theory.md, "Membranes").
     */
    class MembraneMaterial
    {
    public:
      enum class State
      {
        taut,
        wrinkled,
        slack
      };

      double               thickness        = 0.; ///< t [m]
      double               youngs_modulus_1 = 0.; ///< E1 [Pa] (along t1)
      double               youngs_modulus_2 = 0.; ///< E2 [Pa]
      double               poissons_ratio   = 0.; ///< nu12 [-]
      double               shear_modulus    = 0.; ///< G12 [Pa]
      dealii::Tensor<1, 3> prestress; ///< S_0 = [S11, S22, S12] [Pa]
      bool                 wrinkling = false;
      /** Regularising stiffness of a slack point as a fraction of C [-]. */
      double slack_stiffness_ratio = 1e-8;

      /** Set an isotropic material. */
      void
      set_isotropic(const double E, const double nu);

      /** The elastic plane-stress matrix C [Pa]. */
      dealii::Tensor<2, 3>
      elasticity() const;

      /** PK2 stress S and tangent dS/dE at Voigt strain @p E. */
      State
      stress(const dealii::Tensor<1, 3> &E,
             dealii::Tensor<1, 3>       &S,
             dealii::Tensor<2, 3>       &C_tangent) const;

    private:
      /** S_w(E) and, if @p tangent is given, its derivative dS_w/dE
       * (the rotation of the wrinkle direction included). */
      dealii::Tensor<1, 3>
      wrinkled_stress(const dealii::Tensor<1, 3> &E,
                      dealii::Tensor<2, 3>       *tangent = nullptr) const;
    };


    /** Results of one membrane cell for output. */
    struct MembraneCellOutput
    {
      double area             = 0.; ///< reference area A0 [m^2]
      double mean_stress      = 0.; ///< mean (sigma_1 + sigma_2)/2, Cauchy [Pa]
      double max_principal    = 0.; ///< largest principal Cauchy stress [Pa]
      double min_principal    = 0.; ///< smallest principal Cauchy stress [Pa]
      unsigned int n_wrinkled = 0, n_slack = 0; ///< quadrature points
      /** t int (E.C E/2 + S_0.E) dA0 (the SVK energy; with wrinkling the
       * energy of the unmodified law) [J]. */
      double strain_energy = 0.;
    };


    /**
     * Geometrically nonlinear, total-Lagrangian membrane on a
     * Triangulation<2,3> with FESystem(FE_Q(1),3): at a quadrature point
     * with orthonormal reference axes t_a and g_a = F t_a,
     *   E_ab = (g_a.g_b - delta_ab)/2,  f_I = t int S_ab N_I,a g_b dA0,
     *   K_IJ = t int B_I^T C B_J dA0 + t int S_ab N_I,a N_J,b dA0 I3,
     * plus an optional follower pressure p on the current surface,
     *   f_ext,I = p int N_I (g_1 x g_2) dA0,
     * with its (non-symmetric) load stiffness. Gravity is added by the
     * Structure. Source: NOTES-structures-coupling.md section 2.3; Holzapfel
     * (2000); Wriggers, Nonlinear FEM (2008) ch. 9.
     */
    class Membrane
    {
    public:
      MembraneMaterial material;
      double           density  = 0.; ///< rho [kg/m^3]
      double           pressure = 0.; ///< follower pressure p [Pa]
      /** Unit vector whose projection on the surface is material axis 1
       * (orthotropic nets); the first cell edge direction if it is normal
       * to the surface. */
      dealii::Tensor<1, 3> fibre_direction;

      Membrane();

      /**
       * Residual r = f_int - load_factor f_pressure and its derivative K for
       * the cell on which @p fe_values (update_values, gradients, jacobians,
       * JxW) was reinitialised in the reference configuration, with the
       * displacements @p u of its dofs (FESystem order).
       */
      void
      compute(const dealii::FEValues<2, 3> &fe_values,
              const std::vector<double>    &u,
              const double                  load_factor,
              dealii::Vector<double>       &r,
              dealii::FullMatrix<double>   &K,
              MembraneCellOutput           *output = nullptr) const;
    };
  } // namespace Structure
} // namespace Talus

#endif
