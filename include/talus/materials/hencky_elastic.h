#ifndef talus_materials_hencky_elastic_h
#define talus_materials_hencky_elastic_h

#include <talus/materials/constitutive_model.h>
#include <talus/materials/linear_elastic.h>

#include <deal.II/base/tensor.h>

#include <array>
#include <string>

namespace Talus
{
  namespace Materials
  {
    /**
     * Tools for isotropic models written in principal logarithmic strains:
     * Hencky elasticity (HenckyElastic) and the multiplicative
     * elastoplastic models whose return mapping works on the principal
     * values of the elastic logarithmic strain
     * @f$\boldsymbol\varepsilon^e = \frac12\ln\mathbf b^e@f$ (Mohr-Coulomb,
     * Drucker-Prager), see E.A. de Souza Neto, D. Peric, D.R.J. Owen,
     * Computational Methods for Plasticity, Wiley 2008, ch. 14 and
     * appendix A.
     */
    namespace LogarithmicStrain
    {
      /**
       * Eigenvalues @f$b_a@f$ and orthonormal eigenvectors
       * @f$\mathbf n_a@f$ of a symmetric 3x3 tensor,
       * @f$\mathbf b = \sum_a b_a\,\mathbf n_a\otimes\mathbf n_a@f$.
       * Repeated eigenvalues are allowed (the eigenvectors are then an
       * arbitrary orthonormal basis of the eigenspace). No ordering.
       */
      struct SpectralDecomposition
      {
        std::array<double, 3>               eigenvalues;
        std::array<dealii::Tensor<1, 3>, 3> eigenvectors;
      };

      /**
       * Spectral decomposition of the symmetric tensor @p b (only its
       * upper triangle is read) by the cyclic Jacobi method: robust for
       * repeated and nearly repeated eigenvalues, accurate to round-off.
       */
      SpectralDecomposition
      spectral_decomposition(const dealii::Tensor<2, 3> &b);

      /**
       * The elastic left Cauchy-Green tensor b_e = F G F^T (exactly
       * symmetric), its spectral decomposition and the principal elastic
       * logarithmic strains eps_a = 1/2 ln b_a.
       */
      struct ElasticState
      {
        dealii::Tensor<2, 3>  b_e;
        SpectralDecomposition spectral;
        std::array<double, 3> eps;
      };

      /**
       * ElasticState for the deformation gradient @p F and the inverse
       * plastic right Cauchy-Green tensor @p G (identity for pure
       * elasticity). Throws ExcInvertedMaterialPoint (naming @p model) if
       * det F <= 0 or b_e is numerically not positive definite.
       */
      ElasticState
      elastic_state(const std::string          &model,
                    const dealii::Tensor<2, 3> &F,
                    const dealii::Tensor<2, 3> &G);


      /**
       * Given an isotropic Kirchhoff stress
       * @f$\boldsymbol\tau = \sum_a \tau_a\,\mathbf n_a\otimes\mathbf n_a@f$
       * that is a function of the (trial) elastic left Cauchy-Green tensor
       * @f$\mathbf b^e = \mathbf F\mathbf G\mathbf F^T = \sum_a b_a\,
       * \mathbf n_a\otimes\mathbf n_a@f$ (with @f$\mathbf G =
       * \mathbf C_p^{-1}@f$ fixed during the step; for pure elasticity
       * @f$\mathbf G = \mathbf I@f$ and @f$\mathbf b^e = \mathbf F\mathbf
       * F^T@f$), compute the first Piola-Kirchhoff stress
       * @f$\mathbf P = \boldsymbol\tau\mathbf F^{-T}@f$ and, if @p A is
       * not nullptr, its exact derivative @f$\mathbb A = \partial\mathbf
       * P/\partial\mathbf F@f$:
       * @f[
       *   \mathbb A_{iJkL} = 2\,\mathbb D_{ipkn} H_{nL} F^{-1}_{Jp}
       *                      - P_{iL} F^{-1}_{Jk},\qquad
       *   \mathbf H = \mathbf b^e\mathbf F^{-T},
       * @f]
       * with @f$\mathbb D = \partial\boldsymbol\tau/\partial\mathbf b^e@f$
       * from the formula for derivatives of isotropic tensor functions
       * (de Souza Neto et al. 2008, appendix A.5):
       * @f[
       *   \mathbb D = \sum_{a,c}\frac{\partial\tau_a}{\partial b_c}
       *               \mathbf E_{aa}\otimes\mathbf E_{cc}
       *   + \sum_{a\ne c}\theta_{ac}\,\mathbf E_{ac}\otimes
       *     \operatorname{sym}\mathbf E_{ac},\qquad
       *   \mathbf E_{ac} = \mathbf n_a\otimes\mathbf n_c,\qquad
       *   \theta_{ac} = \frac{\tau_a - \tau_c}{b_a - b_c},
       * @f]
       * where @f$\partial\tau_a/\partial b_c =
       * \frac{1}{2b_c}\partial\tau_a/\partial\varepsilon_c@f$ and, for
       * (nearly) equal eigenvalues @f$|b_a - b_c| \le 10^{-8}\max(b_a,
       * b_c)@f$, @f$\theta_{ac}@f$ is replaced by its limit
       * @f$\frac{\partial\tau_a}{\partial b_a} -
       * \frac{\partial\tau_a}{\partial b_c}@f$ (averaged over a and c).
       *
       * @param F  deformation gradient, det F > 0 (not checked here)
       * @param b_e  (trial) elastic left Cauchy-Green tensor, symmetric
       * @param spectral  spectral decomposition of @p b_e
       * @param tau  principal Kirchhoff stresses [Pa], tau[a] belongs to
       *   eigenvector a of @p spectral
       * @param dtau_deps  dtau_deps[a][c] = @f$\partial\tau_a/\partial
       *   \varepsilon_c@f$ [Pa] with @f$\varepsilon_c = \frac12\ln b_c@f$
       *   (the elastic or consistent elastoplastic principal moduli)
       * @param P  first Piola-Kirchhoff stress [Pa] (output)
       * @param A  if not nullptr: dP/dF [Pa] (output)
       * @param tangent_dimension  only the entries A_iJkL with all indices
       *   below it are computed, the others are set to zero (2 for plane
       *   strain, where the in-plane block is all the solver uses)
       */
      void
      principal_kirchhoff_to_piola(const dealii::Tensor<2, 3>  &F,
                                   const dealii::Tensor<2, 3>  &b_e,
                                   const SpectralDecomposition &spectral,
                                   const std::array<double, 3> &tau,
                                   const dealii::Tensor<2, 3>  &dtau_deps,
                                   dealii::Tensor<2, 3>        &P,
                                   dealii::Tensor<4, 3>        *A,
                                   const unsigned int tangent_dimension = 3);
    } // namespace LogarithmicStrain


    /**
     * Hencky hyperelasticity: isotropic linear elasticity between the
     * Kirchhoff stress and the logarithmic (Hencky) strain,
     * @f[
     *   \boldsymbol\varepsilon = \tfrac12\ln\mathbf b,\quad
     *   \mathbf b = \mathbf F\mathbf F^T,\qquad
     *   \boldsymbol\tau = \lambda\operatorname{tr}(\boldsymbol\varepsilon)
     *     \mathbf I + 2\mu\boldsymbol\varepsilon,\qquad
     *   \mathbf P = \boldsymbol\tau\mathbf F^{-T},
     * @f]
     * with the stored energy per unit reference volume
     * @f$\psi = \frac\lambda2(\operatorname{tr}\boldsymbol\varepsilon)^2 +
     * \mu\,\boldsymbol\varepsilon:\boldsymbol\varepsilon@f$ (so that
     * @f$\mathbf P = \partial\psi/\partial\mathbf F@f$). The tangent
     * @f$\mathbb A = \partial\mathbf P/\partial\mathbf F@f$ is exact
     * (LogarithmicStrain::principal_kirchhoff_to_piola()), including the
     * cases of repeated principal stretches (F = I, plane strain with equal
     * in-plane stretches).
     *
     * The model is objective, agrees with LinearElastic to first order in
     * the strain, and is the elastic part of the elastoplastic models with
     * return mapping in principal logarithmic strains (Mohr-Coulomb).
     *
     * Throws ExcInvertedMaterialPoint if @f$\det\mathbf F \le 0@f$.
     *
     * References: E.A. de Souza Neto, D. Peric, D.R.J. Owen, Computational
     * Methods for Plasticity: Theory and Applications, Wiley 2008, section
     * 14.2; J.C. Simo, Algorithms for static and dynamic multiplicative
     * plasticity that preserve the classical return mapping schemes of the
     * infinitesimal theory, CMAME 99 (1992) 61-112.
     */
    class HenckyElastic : public ConstitutiveModel
    {
    public:
      /**
       * @param youngs_modulus  Young's modulus E [Pa]; > 0
       * @param poissons_ratio  Poisson's ratio nu [-]; -1 < nu < 0.5
       */
      HenckyElastic(const double youngs_modulus, const double poissons_ratio);

      /** Returns "Hencky". */
      std::string
      name() const override;

      /** P(F_new) and its exact tangent; F_old and the history are unused. */
      void
      compute_stress(const dealii::Tensor<2, 3>            &F_old,
                     const dealii::Tensor<2, 3>            &F_new,
                     const dealii::ArrayView<const double> &history_old,
                     const dealii::ArrayView<double>       &history_new,
                     const double                           time_step,
                     dealii::Tensor<2, 3>                  &P,
                     dealii::Tensor<4, 3>                  *A) const override;

      /** psi(F) [J/m^3]. */
      double
      energy_density(
        const dealii::Tensor<2, 3>            &F,
        const dealii::ArrayView<const double> &history) const override;

      /** lambda + 2 mu [Pa]. */
      double
      p_wave_modulus() const override;

      /** The elastic constants. */
      const IsotropicElasticity &
      elasticity() const;

      /**
       * Principal Kirchhoff stresses for principal logarithmic strains
       * @p eps: @f$\tau_a = \lambda\sum_c\varepsilon_c + 2\mu\varepsilon_a@f$.
       */
      std::array<double, 3>
      principal_stress(const std::array<double, 3> &eps) const;

      /**
       * Principal elastic moduli @f$\partial\tau_a/\partial\varepsilon_c =
       * \lambda + 2\mu\delta_{ac}@f$ [Pa].
       */
      dealii::Tensor<2, 3>
      principal_moduli() const;

    private:
      const IsotropicElasticity elastic;
    };
  } // namespace Materials
} // namespace Talus

#endif
