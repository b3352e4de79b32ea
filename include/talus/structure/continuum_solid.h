#ifndef talus_structure_continuum_solid_h
#define talus_structure_continuum_solid_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_values.h>

#include <string>
#include <vector>

namespace Talus
{
  namespace Structure
  {
    /** Results of one solid cell for output. */
    struct SolidCellOutput
    {
      /** int W(E) dV0 [J]. */
      double strain_energy = 0.;
      /** Cell mean of the von Mises stress of the Cauchy stress [Pa]. */
      double von_mises = 0.;
      /** Cell mean of the mean Cauchy stress tr(sigma)/3 [Pa]. */
      double mean_stress = 0.;
    };


    /** Hyperelastic laws of a ContinuumSolid. */
    enum class SolidLaw
    {
      saint_venant_kirchhoff, ///< S = lambda tr(E) I + 2 mu E
      neo_hookean             ///< P = mu (F - F^-T) + lambda ln J F^-T
    };


    /**
     * A continuum solid in the barrier structure (rigid or elastic
     * obstacles, verification): geometrically nonlinear, total-Lagrangian
     * St. Venant-Kirchhoff elasticity on a Triangulation<dim,dim> with
     * FESystem(FE_Q(degree), dim); dim = 3 in the Structure, dim = 2 (plane
     * strain) in 2D problems (the Structure's PlaneSolidMesh) and element
     * checks. With F = I + Grad u,
     *   E = (F^T F - I)/2,  S = lambda tr(E) I + 2 mu E,  P = F S,
     *   W(E) = lambda/2 tr(E)^2 + mu E:E,
     *   f_i = int P : Grad phi_i dV0,
     *   K_ij = int dE_i : C : dE_j + S : (Grad phi_i^T Grad phi_j) dV0,
     *   dE_i = sym(F^T Grad phi_i),
     * with lambda = E nu/((1+nu)(1-2nu)), mu = E/(2(1+nu)) and Gauss
     * quadrature of degree + 1 points per direction (full integration:
     * linear elements lock in bending, measured in doc/verification.md).
     * Gravity, tractions and the mass are added by the Structure. The
     * St. Venant-Kirchhoff law is the membrane's in three dimensions; it is
     * for moderate strains (it softens and loses stability in strong
     * compression, stretch below 1/sqrt(3) in uniaxial stress). Source:
     * Holzapfel, Nonlinear Solid Mechanics (2000) ch. 6 and 8; Wriggers,
     * Nonlinear Finite Element Methods (2008) ch. 4.
     *
     * With 'material law = neo-Hookean' the compressible neo-Hookean law
     * of the MPM's Materials::NeoHookean replaces it (J = det F, plane
     * strain: F_33 = 1):
     *   W(F) = mu/2 (tr(F^T F) - 3) - mu ln J + lambda/2 (ln J)^2,
     *   P = mu (F - F^-T) + lambda ln J F^-T,
     *   A_iJkL = mu d_ik d_JL + (mu - lambda ln J) F^-1_Li F^-1_Jk
     *            + lambda F^-1_Ji F^-1_Lk,
     *   f_i = int P : Grad phi_i dV0,  K_ij = int Grad phi_i : A :
     *   Grad phi_j dV0,
     * stable in strong compression (W -> infinity as J -> 0), the same as
     * St. Venant-Kirchhoff to first order in the strain. Source: Bonet &
     * Wood, Nonlinear Continuum Mechanics for Finite Element Analysis
     * (2008) sec. 6.4.3.
     */
    template <int dim>
    class ContinuumSolid
    {
    public:
      /** The hyperelastic law of the solid. */
      using Law = SolidLaw;

      double       youngs_modulus = 2.1e11; ///< E [Pa]
      double       poissons_ratio = 0.3;    ///< nu [-], in (-1, 0.5)
      double       density        = 7850.;  ///< rho_0 [kg/m^3]
      unsigned int degree         = 1;      ///< of FE_Q [-]
      Law          law            = Law::saint_venant_kirchhoff; ///< stress law

      /** The law's name as in the parameter file ('St. Venant-Kirchhoff'
       * or 'neo-Hookean'). */
      std::string
      law_name() const;

      /** The material entries of the current subsection (Structure/Solid). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read them; @p subsection (e.g. "Structure/Solid") for messages. */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection);

      /** Lame's first parameter lambda [Pa]. */
      double
      lame_lambda() const;

      /** Shear modulus mu [Pa]. */
      double
      shear_modulus() const;

      /** PK2 stress S(E) [Pa]. */
      dealii::SymmetricTensor<2, dim>
      stress(const dealii::SymmetricTensor<2, dim> &E) const;

      /** Stored energy W(E) per reference volume [J/m^3]
       * (St. Venant-Kirchhoff). */
      double
      energy_density(const dealii::SymmetricTensor<2, dim> &E) const;

      /**
       * First Piola-Kirchhoff stress P(F) [Pa] of the solid's law, its
       * stored energy W(F) per reference volume [J/m^3] in @p energy and,
       * if @p A is not null, the tangent A = dP/dF [Pa]. For dim = 2 the
       * plane-strain values (F_33 = 1). The neo-Hookean law throws for
       * det F <= 0 (the Newton iteration's line search of StaticSolver
       * then shortens the step).
       */
      dealii::Tensor<2, dim>
      piola_stress(const dealii::Tensor<2, dim> &F,
                   double                       &energy,
                   dealii::Tensor<4, dim>       *A = nullptr) const;

      /**
       * Internal forces r = f_int and their derivative K of the cell on
       * which @p fe_values (update_values, gradients, JxW) was reinitialised
       * in the reference configuration, at the displacements @p u of its
       * dofs (FESystem order). spacedim = dim: FESystem(FE_Q, dim).
       * spacedim = 3 > dim = 2: the plane-strain solid of a 2D problem on a
       * flat Triangulation<2,3> in the x-y plane with FESystem(FE_Q, 3)
       * (the Structure's layout); only the in-plane components and
       * derivatives enter, the rows and columns of u_z stay zero. Plane
       * strain (E_33 = 0) per unit thickness; the output adds sigma_33 =
       * lambda tr(E)/J (neo-Hookean: lambda ln J/J) to the von Mises and
       * mean stresses. The neo-Hookean law throws for an inverted
       * quadrature point (J <= 0).
       */
      template <int spacedim>
      void
      compute(const dealii::FEValues<dim, spacedim> &fe_values,
              const std::vector<double>             &u,
              dealii::Vector<double>                &r,
              dealii::FullMatrix<double>            &K,
              SolidCellOutput                       *output = nullptr) const;

    private:
      /** Add the neo-Hookean forces and stiffness of one quadrature point
       * with deformation gradient @p F and shape gradients @p grad_phi. */
      void
      neo_hookean_point(const dealii::Tensor<2, dim>              &F,
                        const std::vector<dealii::Tensor<2, dim>> &grad_phi,
                        const double                               JxW,
                        dealii::Vector<double>                    &r,
                        dealii::FullMatrix<double>                &K) const;
    };


    /**
     * Geometry, supports and surface load of a continuum solid, from
     * subsection Structure/Solid: a Gmsh file of hexahedra or a generated
     * box (GridGenerator::subdivided_hyper_rectangle, colorized: boundary
     * ids 0..5 on the faces x = x_min, x_max, y_min, y_max, z_min, z_max),
     * fixed boundary ids (all components of every DoF on those faces),
     * support boxes (the listed components of every DoF whose support
     * point lies in an axis-aligned box) and a dead traction on one
     * boundary id, scaled by the load factor.
     */
    class SolidGeometry
    {
    public:
      /** A box of supports: DoFs of components @p components in it. */
      struct SupportBox
      {
        dealii::Point<3>  lower, upper;
        std::vector<bool> components = std::vector<bool>(3, false);
      };

      std::string               mesh_file; ///< empty: generated box
      dealii::Point<3>          lower_corner, upper_corner; ///< [m]
      std::vector<unsigned int> subdivisions = {1, 1, 1};
      std::vector<unsigned int> fixed_boundary_ids;
      std::vector<SupportBox>   support_boxes;
      int                       traction_boundary_id = -1;
      dealii::Tensor<1, 3>      traction; ///< [Pa]
      /** Out-of-plane thickness t of the plane-strain solid of the 'plane'
       * models (2D problems) [m]. */
      double thickness = 1.;

      /** The geometry entries of the current subsection (Structure/Solid). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read them; @p subsection for messages. */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection);

      /**
       * Fill @p tria: read the mesh file (errors name 'mesh file' in
       * @p subsection) or generate the box with subdivisions times
       * 2^@p level cells per direction.
       */
      void
      create_triangulation(dealii::Triangulation<3> &tria,
                           const unsigned int        level,
                           const std::string        &subsection) const;

      /**
       * The plane-strain solid of a 2D problem: the rectangle of the x and
       * y coordinates of the corners with the first two 'subdivisions'
       * times 2^@p level cells, colorized (boundary ids 0..3 on x_min,
       * x_max, y_min, y_max). A 'mesh file' is rejected (named in
       * @p subsection).
       */
      void
      create_triangulation(dealii::Triangulation<2> &tria,
                           const unsigned int        level,
                           const std::string        &subsection) const;
    };
  } // namespace Structure
} // namespace Talus

#endif
