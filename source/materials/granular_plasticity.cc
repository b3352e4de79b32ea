#include <talus/base/input.h>
#include <talus/materials/exceptions.h>
#include <talus/materials/granular_plasticity.h>
#include <talus/materials/hencky_elastic.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

namespace Talus
{
  namespace Materials
  {
    namespace
    {
      constexpr double degree = M_PI / 180.;

      GranularStrength::Value
      soften(const double peak,
             const double residual,
             const double eta,
             const double eps_p)
      {
        if (peak == residual)
          return {peak, 0.};
        const double e = std::exp(-eps_p / eta);
        return {residual + (peak - residual) * e, -(peak - residual) / eta * e};
      }

      /** A copy of @p s with the table of sin_cos() and tan() filled. */
      GranularStrength
      with_trigonometry_table(const GranularStrength &s)
      {
        GranularStrength copy = s;
        copy.tabulate_trigonometry();
        return copy;
      }
    } // namespace



    bool
    GranularStrength::softening() const
    {
      return residual_friction_angle != friction_angle ||
             residual_cohesion != cohesion ||
             residual_dilatancy_angle != dilatancy_angle;
    }



    GranularStrength::Value
    GranularStrength::phi(const double eps_p) const
    {
      return soften(friction_angle,
                    residual_friction_angle,
                    softening_strain,
                    eps_p);
    }



    bool
    GranularStrength::rate_dependent() const
    {
      return friction_coefficient_increment > 0.;
    }



    GranularStrength::RateValue
    GranularStrength::phi(const double eps_p,
                          const double plastic_strain_increment,
                          const double pressure,
                          const double time_step,
                          const bool   compute_angle) const
    {
      const Value static_phi = phi(eps_p);
      if (!rate_dependent() || !(time_step > 0.))
        {
          const SinCos t = sin_cos(static_phi.value);
          return {static_phi.value, t.sin, t.cos, static_phi.derivative, 0.};
        }
      // I/(I0 + I) = X/(X + Y) with X = gamma_dot d sqrt(rho_s) and
      // Y = I0 sqrt(P): finite for P -> 0
      const double dX_deps =
        std::sqrt(3.) * grain_diameter * std::sqrt(grain_density) / time_step;
      const double X     = std::max(0., plastic_strain_increment) * dX_deps;
      const double sqrtP = std::sqrt(std::max(0., pressure));
      const double Y     = reference_inertial_number * sqrtP;
      const double tan_s = tan(static_phi.value);
      double       ratio = 0., dratio_deps = 0., dratio_dP = 0.;
      if (X + Y > 0.)
        {
          ratio = X / (X + Y);
          if (plastic_strain_increment > 0.)
            dratio_deps = Y / ((X + Y) * (X + Y)) * dX_deps;
          if (pressure > 0.)
            dratio_dP = -X / ((X + Y) * (X + Y)) * reference_inertial_number /
                        (2. * sqrtP);
        }
      const double mu    = tan_s + friction_coefficient_increment * ratio;
      const double dphi  = 1. / (1. + mu * mu); // d phi/d mu
      const double dmu_s = (1. + tan_s * tan_s) * static_phi.derivative;
      // sin and cos from tan(phi) = mu, phi in (0, pi/2)
      const double cos_phi = std::sqrt(dphi);
      return {compute_angle ? std::atan(mu) :
                              std::numeric_limits<double>::quiet_NaN(),
              mu * cos_phi,
              cos_phi,
              dphi * (dmu_s + friction_coefficient_increment * dratio_deps),
              dphi * friction_coefficient_increment * dratio_dP};
    }



    GranularStrength::Value
    GranularStrength::c(const double eps_p) const
    {
      return soften(cohesion, residual_cohesion, softening_strain, eps_p);
    }



    GranularStrength::Value
    GranularStrength::apex_pressure(const double eps_p) const
    {
      const Value  f   = phi(eps_p);
      const Value  k   = c(eps_p);
      const SinCos t   = sin_cos(f.value);
      const double cot = t.cos / t.sin;
      if (k.value * cot >= tension_cutoff)
        return {tension_cutoff, 0.};
      return {k.value * cot,
              k.derivative * cot - k.value * f.derivative / (t.sin * t.sin)};
    }



    GranularStrength::SinCos
    GranularStrength::sin_cos(const double angle) const
    {
      for (const auto &row : trigonometry_table)
        if (row[0] == angle)
          return {row[1], row[2]};
      return {std::sin(angle), std::cos(angle)};
    }



    double
    GranularStrength::tan(const double angle) const
    {
      for (const auto &row : trigonometry_table)
        if (row[0] == angle)
          return row[3];
      return std::tan(angle);
    }



    void
    GranularStrength::tabulate_trigonometry()
    {
      const std::array<double, 4> angles = {{friction_angle,
                                             residual_friction_angle,
                                             dilatancy_angle,
                                             residual_dilatancy_angle}};
      for (unsigned int i = 0; i < angles.size(); ++i)
        trigonometry_table[i] = {{angles[i],
                                  std::sin(angles[i]),
                                  std::cos(angles[i]),
                                  std::tan(angles[i])}};
    }



    GranularStrength::Value
    GranularStrength::psi(const double eps_p) const
    {
      return soften(dilatancy_angle,
                    residual_dilatancy_angle,
                    softening_strain,
                    eps_p);
    }



    std::string
    GranularStrength::to_string() const
    {
      std::ostringstream s;
      s << "phi = " << friction_angle / degree << " deg, c = " << cohesion
        << " Pa, psi = " << dilatancy_angle / degree << " deg, ";
      if (softening())
        s << "softening to phi_r = " << residual_friction_angle / degree
          << " deg, c_r = " << residual_cohesion
          << " Pa, psi_r = " << residual_dilatancy_angle / degree
          << " deg with softening plastic strain " << softening_strain;
      else
        s << "no softening";
      s << ", tension cut-off = " << tension_cutoff << " Pa";
      if (recoverable_separation)
        s << ", recoverable separated volume";
      if (rate_dependent())
        s << ", rate-dependent friction mu(I): tan(phi_2) - tan(phi) = "
          << friction_coefficient_increment << " (phi_2 = "
          << std::atan(std::tan(friction_angle) +
                       friction_coefficient_increment) /
               degree
          << " deg), I0 = " << reference_inertial_number
          << ", grain diameter = " << grain_diameter
          << " m, grain density = " << grain_density << " kg/m^3";
      return s.str();
    }



    GranularPlasticity::GranularPlasticity(const IsotropicElasticity &elastic,
                                           const GranularStrength    &strength)
      : elastic(elastic)
      , strength_parameters(with_trigonometry_table(strength))
    {
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          D[a][b] = elastic.lambda + (a == b ? 2. * elastic.mu : 0.);
      C = dealii::invert(D);
    }



    unsigned int
    GranularPlasticity::n_history_variables() const
    {
      return 10;
    }



    void
    GranularPlasticity::initialize_history(
      const dealii::ArrayView<double> &history) const
    {
      AssertDimension(history.size(), n_history_variables());
      std::fill(history.begin(), history.end(), 0.);
      history[0] = history[1] = history[2] = 1.;
    }



    bool
    GranularPlasticity::initialize_history_for_stress(
      const dealii::SymmetricTensor<2, 3> &stress,
      const dealii::ArrayView<double>     &history) const
    {
      initialize_history(history);
      // Hencky: eps^e = (tau - lambda/(3 lambda + 2 mu) tr(tau) I) / (2 mu).
      const double lambda = elastic.lambda;
      const double mu     = elastic.mu;
      const auto   eps =
        (stress - lambda / (3. * lambda + 2. * mu) * dealii::trace(stress) *
                    dealii::unit_symmetric_tensor<3>()) /
        (2. * mu);
      const auto                    eigen = dealii::eigenvectors(eps);
      dealii::SymmetricTensor<2, 3> G;
      for (const auto &e : eigen)
        G += std::exp(2. * e.first) *
             dealii::symmetrize(dealii::outer_product(e.second, e.second));
      history[0] = G[0][0];
      history[1] = G[1][1];
      history[2] = G[2][2];
      history[3] = G[0][1];
      history[4] = G[1][2];
      history[5] = G[0][2];

      // Admissible if F = I from this state returns elastically.
      std::vector<double> trial(history.size());
      const auto I = dealii::Tensor<2, 3>(dealii::unit_symmetric_tensor<3>());
      dealii::Tensor<2, 3> P;
      compute_stress(I,
                     I,
                     dealii::ArrayView<const double>(history.data(),
                                                     history.size()),
                     dealii::ArrayView<double>(trial.data(), trial.size()),
                     0.,
                     P,
                     nullptr);
      return trial[return_type_index] == 0.;
    }



    std::vector<std::string>
    GranularPlasticity::history_names() const
    {
      return {"Cp_inv_xx",
              "Cp_inv_yy",
              "Cp_inv_zz",
              "Cp_inv_xy",
              "Cp_inv_yz",
              "Cp_inv_xz",
              "plastic_strain",
              "plastic_dissipation",
              "return_type",
              "open_volumetric_strain"};
    }



    unsigned int
    GranularPlasticity::return_branch(
      const dealii::ArrayView<const double> &history) const
    {
      AssertDimension(history.size(), n_history_variables());
      return static_cast<unsigned int>(history[return_type_index] + 0.5);
    }



    double
    GranularPlasticity::p_wave_modulus() const
    {
      return elastic.p_wave_modulus();
    }



    const IsotropicElasticity &
    GranularPlasticity::elasticity() const
    {
      return elastic;
    }



    const GranularStrength &
    GranularPlasticity::strength() const
    {
      return strength_parameters;
    }



    namespace
    {
      dealii::Tensor<2, 3>
      history_to_G(const dealii::ArrayView<const double> &h)
      {
        dealii::Tensor<2, 3> G;
        G[0][0] = h[0];
        G[1][1] = h[1];
        G[2][2] = h[2];
        G[0][1] = G[1][0] = h[3];
        G[1][2] = G[2][1] = h[4];
        G[0][2] = G[2][0] = h[5];
        return G;
      }


    } // namespace



    void
    GranularPlasticity::compute_stress(
      const dealii::Tensor<2, 3> & /*F_old*/,
      const dealii::Tensor<2, 3>            &F,
      const dealii::ArrayView<const double> &history_old,
      const dealii::ArrayView<double>       &history_new,
      const double                           time_step,
      dealii::Tensor<2, 3>                  &P,
      dealii::Tensor<4, 3>                  *A) const
    {
      AssertDimension(history_old.size(), n_history_variables());
      AssertDimension(history_new.size(), n_history_variables());

      const auto s =
        LogarithmicStrain::elastic_state(name(), F, history_to_G(history_old));

      // sort the principal directions: order[k] = index of the k-th largest
      std::array<unsigned int, 3> order = {{0, 1, 2}};
      std::sort(order.begin(),
                order.end(),
                [&](const unsigned int a, const unsigned int b) {
                  return s.eps[a] > s.eps[b];
                });
      dealii::Tensor<1, 3> eps_sorted;
      for (unsigned int k = 0; k < 3; ++k)
        eps_sorted[k] = s.eps[order[k]];

      const double plastic_strain_old = history_old[plastic_strain_index];
      const PrincipalReturn r =
        principal_return(eps_sorted, plastic_strain_old, time_step);

      std::array<double, 3> tau;
      dealii::Tensor<2, 3>  dtau_deps;
      for (unsigned int k = 0; k < 3; ++k)
        {
          tau[order[k]] = r.tau[k];
          for (unsigned int l = 0; l < 3; ++l)
            dtau_deps[order[k]][order[l]] = r.dtau_deps[k][l];
        }
      LogarithmicStrain::principal_kirchhoff_to_piola(
        F, s.b_e, s.spectral, tau, dtau_deps, P, A, tangent_dimension());

      // history
      if (r.return_type == 0)
        {
          for (unsigned int i = 0; i < 6; ++i)
            history_new[i] = history_old[i];
          history_new[dissipation_index] = history_old[dissipation_index];
          history_new[open_strain_index] = 0.;
        }
      else
        {
          dealii::Tensor<1, 3> eps_new = C * r.tau;
          // Recoverable separation: the volumetric strain beyond a
          // hydrostatic apex stays elastic (b^e) and stress-free.
          double open = 0.;
          if (strength_parameters.recoverable_separation &&
              r.return_type >= 3 &&
              std::abs(r.tau[0] - r.tau[2]) <=
                1e-12 * (std::abs(r.tau[0]) + elastic.mu))
            {
              open = std::max(0.,
                              eps_sorted[0] + eps_sorted[1] + eps_sorted[2] -
                                (eps_new[0] + eps_new[1] + eps_new[2]));
              for (unsigned int k = 0; k < 3; ++k)
                eps_new[k] += open / 3.;
            }
          history_new[open_strain_index]   = open;
          double               dissipation = 0.;
          dealii::Tensor<2, 3> b_e_new;
          for (unsigned int k = 0; k < 3; ++k)
            {
              dissipation += r.tau[k] * (eps_sorted[k] - eps_new[k]);
              const dealii::Tensor<1, 3> &n = s.spectral.eigenvectors[order[k]];
              b_e_new +=
                std::exp(2. * eps_new[k]) * dealii::outer_product(n, n);
            }
          const dealii::Tensor<2, 3> F_inv = dealii::invert(F);
          const dealii::Tensor<2, 3> G_new =
            F_inv * b_e_new * dealii::transpose(F_inv);
          history_new[0] = G_new[0][0];
          history_new[1] = G_new[1][1];
          history_new[2] = G_new[2][2];
          history_new[3] = 0.5 * (G_new[0][1] + G_new[1][0]);
          history_new[4] = 0.5 * (G_new[1][2] + G_new[2][1]);
          history_new[5] = 0.5 * (G_new[0][2] + G_new[2][0]);
          history_new[dissipation_index] =
            history_old[dissipation_index] + dissipation;
        }
      history_new[plastic_strain_index] = r.plastic_strain;
      history_new[return_type_index]    = r.return_type;
    }



    double
    GranularPlasticity::energy_density(
      const dealii::Tensor<2, 3>            &F,
      const dealii::ArrayView<const double> &history) const
    {
      const auto s =
        LogarithmicStrain::elastic_state(name(), F, history_to_G(history));
      // the open (separated) volumetric strain stores no energy
      const double open = history[open_strain_index] / 3.;
      double       tr   = 0.;
      double       sum2 = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          tr += s.eps[k] - open;
          sum2 += (s.eps[k] - open) * (s.eps[k] - open);
        }
      return 0.5 * elastic.lambda * tr * tr + elastic.mu * sum2;
    }



    void
    GranularPlasticity::fail(const std::string          &what,
                             const dealii::Tensor<1, 3> &eps_trial,
                             const double                plastic_strain_old,
                             const std::string          &reason) const
    {
      std::ostringstream         msg;
      const dealii::Tensor<1, 3> tau = D * eps_trial;
      msg << "The " << name() << " return mapping (" << what
          << ") failed: " << reason << ". Trial principal Kirchhoff stresses "
          << tau[0] << ", " << tau[1] << ", " << tau[2]
          << " Pa, accumulated plastic strain " << plastic_strain_old << ".";
      throw ExcReturnMappingFailed(msg.str());
    }



    PrincipalReturn
    GranularPlasticity::prescribed_stress_return(
      const dealii::Tensor<1, 3>                        &eps_trial,
      const double                                       plastic_strain_old,
      const std::function<void(const double,
                               const dealii::Tensor<1, 3> &,
                               dealii::Tensor<1, 3> &,
                               dealii::Tensor<1, 3> &,
                               dealii::Tensor<2, 3> &)> &stress,
      const unsigned int                                 return_type,
      const std::string                                 &what) const
    {
      const double         k     = std::sqrt(2. / 3.);
      double               eps_p = plastic_strain_old;
      dealii::Tensor<1, 3> T, dT_dp, m_hat;
      dealii::Tensor<2, 3> dT_deps;
      double               dr_dp     = 1.;
      bool                 converged = false;
      for (unsigned int it = 0; it < 50; ++it)
        {
          stress(eps_p, eps_trial, T, dT_dp, dT_deps);
          const dealii::Tensor<1, 3> m    = eps_trial - C * T;
          const double               norm = m.norm();
          m_hat          = (norm > 0. ? m / norm : dealii::Tensor<1, 3>());
          const double r = eps_p - plastic_strain_old - k * norm;
          dr_dp          = 1. + k * (m_hat * (C * dT_dp));
          if (!std::isfinite(r) || !std::isfinite(dr_dp) || dr_dp <= 0.)
            fail(what,
                 eps_trial,
                 plastic_strain_old,
                 "non-finite or non-positive derivative in the local Newton "
                 "iteration");
          if (std::abs(r) <= 1e-14 * (1. + eps_p))
            {
              converged = true;
              break;
            }
          eps_p -= r / dr_dp;
        }
      if (!converged)
        fail(what,
             eps_trial,
             plastic_strain_old,
             "the local Newton iteration did not converge in 50 iterations");

      PrincipalReturn result;
      result.tau            = T;
      result.plastic_strain = eps_p;
      result.return_type    = return_type;
      // d eps_p/d eps = k m_hat^T (I - C dT/deps) / dr_dp
      dealii::Tensor<2, 3> I;
      for (unsigned int a = 0; a < 3; ++a)
        I[a][a] = 1.;
      const dealii::Tensor<1, 3> dp_deps =
        k / dr_dp * (m_hat * dealii::Tensor<2, 3>(I - C * dT_deps));
      result.dtau_deps = dT_deps + dealii::outer_product(dT_dp, dp_deps);
      return result;
    }



    void
    declare_granular_strength(dealii::ParameterHandler &prm,
                              const std::string        &tension_cutoff_meaning)
    {
      prm.declare_entry(
        "friction angle",
        "30",
        dealii::Patterns::Double(),
        "Peak angle of internal friction phi [deg]; 0 < phi < 90.");
      prm.declare_entry("cohesion",
                        "0",
                        dealii::Patterns::Double(),
                        "Peak cohesion c [Pa]; >= 0 (0: cohesionless).");
      prm.declare_entry(
        "dilatancy angle",
        "0",
        dealii::Patterns::Double(),
        "Peak dilatancy angle psi [deg] of the plastic potential (flow "
        "rule); 0 <= psi <= phi. psi = phi: associative flow; psi = 0: "
        "isochoric plastic flow (no plastic volume change). psi < phi (and "
        "softening) make the consistent tangent non-symmetric: use "
        "Solver/linear solver = GMRES or direct, not CG.");
      prm.declare_entry("tension cut-off",
                        "1e30",
                        dealii::Patterns::Double(),
                        "Tension cut-off t [Pa]; >= 0. " +
                          tension_cutoff_meaning +
                          " It only has an effect if t < c cot(phi) (the "
                          "tensile strength of the cone or pyramid apex); "
                          "the default 1e30 disables it. Not softened.");
      prm.declare_entry(
        "separated volume",
        "plastic",
        dealii::Patterns::Selection("plastic|recoverable"),
        "What happens to the volume a point gains beyond the apex of the "
        "yield surface (stress-free separation of the grains, e.g. at a "
        "free surface or a spreading front of a cohesionless material). "
        "'plastic': it is stored as plastic dilation, so the point resists "
        "compression from its dilated volume on and does not recompact. "
        "'recoverable': it stays an isotropic, stress-free opening that "
        "closes without stress when the point is compressed back to the "
        "apex volume (the disconnected state of Dunatunga & Kamrin, JFM "
        "779 (2015) 483); the history value open_volumetric_strain holds "
        "it [-].");
      prm.declare_entry(
        "residual friction angle",
        "peak",
        dealii::Patterns::Anything(),
        "Residual friction angle phi_r [deg] reached after large plastic "
        "strains; 0 < phi_r <= phi, or 'peak' (= friction angle: no "
        "softening of phi). Softening law: X = X_r + (X_p - X_r) "
        "exp(-eps_p/eta) for X = phi, c, psi, with eps_p the accumulated "
        "equivalent plastic strain and eta the softening plastic strain.");
      prm.declare_entry(
        "residual cohesion",
        "peak",
        dealii::Patterns::Anything(),
        "Residual cohesion c_r [Pa]; 0 <= c_r <= c, or 'peak' (= cohesion: "
        "no softening of c).");
      prm.declare_entry(
        "residual dilatancy angle",
        "peak",
        dealii::Patterns::Anything(),
        "Residual dilatancy angle psi_r [deg]; 0 <= psi_r <= psi and "
        "psi_r <= phi_r, or 'peak' (= dilatancy angle: no softening of psi).");
      prm.declare_entry(
        "softening plastic strain",
        "0.1",
        dealii::Patterns::Double(),
        "Softening plastic strain eta [-] of the exponential softening law "
        "(the accumulated equivalent plastic strain over which the "
        "difference between peak and residual values decays by the factor "
        "e); > 0. Only used if a residual value differs from its peak "
        "value.");
      prm.declare_entry(
        "limiting friction angle",
        "none",
        dealii::Patterns::Anything(),
        "Rate-dependent friction (mu(I) rheology, Jop, Forterre & Pouliquen, "
        "Nature 441 (2006) 727): the friction angle phi_2 [deg] reached at "
        "large inertial numbers I, phi < phi_2 < 90, or 'none' "
        "(rate-independent, the default). tan(phi) = tan(phi_s) + "
        "(tan(phi_2) - tan(phi_peak)) I/(I_0 + I), with phi_s the static "
        "(softened) friction angle, I = gamma_p d/sqrt(P/rho_s), gamma_p = "
        "sqrt(3) (equivalent plastic strain rate) the plastic shear rate and "
        "P the trial pressure. Jop et al. (glass beads): phi = 20.9, phi_2 = "
        "32.76 deg, I_0 = 0.279. Used in the plane and edge returns of "
        "Mohr-Coulomb and the cone return of Drucker-Prager (the cone "
        "coefficients of the cone fit at phi(I)); the apex and the cap keep "
        "the static friction.");
      prm.declare_entry("reference inertial number",
                        "0.279",
                        dealii::Patterns::Double(),
                        "Reference inertial number I_0 [-] of the "
                        "rate-dependent friction; > 0. Default: Jop et al. "
                        "2006. Only used with a limiting friction angle.");
      prm.declare_entry("grain diameter",
                        "0",
                        dealii::Patterns::Double(),
                        "Grain diameter d [m] in the inertial number; > 0 "
                        "when a limiting friction angle is given.");
      prm.declare_entry("grain density",
                        "0",
                        dealii::Patterns::Double(),
                        "Density of the grains rho_s [kg/m^3] in the "
                        "inertial number; 0: the material density "
                        "(Material/density, the bulk density), otherwise "
                        "> 0. Only used with a limiting friction angle.");
    }



    namespace
    {
      /**
       * A number, or the word @p keyword (e.g. "peak") that stands for
       * @p keyword_value.
       */
      double
      read_number_or(const dealii::ParameterHandler &prm,
                     const std::string              &subsection_path,
                     const std::string              &entry,
                     const std::string              &keyword,
                     const double                    keyword_value)
      {
        const std::string text    = prm.get(entry);
        std::string       trimmed = text;
        trimmed.erase(0, trimmed.find_first_not_of(" \t"));
        trimmed.erase(trimmed.find_last_not_of(" \t") + 1);
        if (trimmed == keyword)
          return keyword_value;
        try
          {
            std::size_t  used  = 0;
            const double value = std::stod(trimmed, &used);
            if (used == trimmed.size() && std::isfinite(value))
              return value;
          }
        catch (const std::exception &)
          {}
        InputFile::reject(subsection_path,
                          entry,
                          text,
                          "it must be a number or '" + keyword + "'");
      }


      /** A residual value: "peak" or a number. */
      double
      read_residual(const dealii::ParameterHandler &prm,
                    const std::string              &subsection_path,
                    const std::string              &entry,
                    const double                    peak)
      {
        return read_number_or(prm, subsection_path, entry, "peak", peak);
      }


      std::string
      number(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }
    } // namespace



    GranularStrength
    read_granular_strength(const dealii::ParameterHandler &prm,
                           const std::string              &subsection_path)
    {
      const std::string &sub = subsection_path;
      GranularStrength   s;

      const double phi = prm.get_double("friction angle");
      if (!(phi > 0. && phi < 90.))
        InputFile::reject(sub,
                          "friction angle",
                          prm.get("friction angle"),
                          "it must lie strictly between 0 and 90 degrees");
      const double c = prm.get_double("cohesion");
      if (!(c >= 0.) || !std::isfinite(c))
        InputFile::reject(sub,
                          "cohesion",
                          prm.get("cohesion"),
                          "it must be >= 0 Pa");
      const double psi = prm.get_double("dilatancy angle");
      if (!(psi >= 0. && psi <= phi))
        InputFile::reject(sub,
                          "dilatancy angle",
                          prm.get("dilatancy angle"),
                          "it must lie between 0 and the friction angle (" +
                            number(phi) + " degrees)");
      const double t = prm.get_double("tension cut-off");
      if (!(t >= 0.))
        InputFile::reject(sub,
                          "tension cut-off",
                          prm.get("tension cut-off"),
                          "it must be >= 0 Pa");

      const double phi_r =
        read_residual(prm, sub, "residual friction angle", phi);
      if (!(phi_r > 0. && phi_r <= phi))
        InputFile::reject(sub,
                          "residual friction angle",
                          prm.get("residual friction angle"),
                          "it must be > 0 and not above the (peak) friction "
                          "angle " +
                            number(phi) + " degrees");
      const double c_r = read_residual(prm, sub, "residual cohesion", c);
      if (!(c_r >= 0. && c_r <= c))
        InputFile::reject(sub,
                          "residual cohesion",
                          prm.get("residual cohesion"),
                          "it must be >= 0 and not above the (peak) cohesion " +
                            number(c) + " Pa");
      const double psi_r =
        read_residual(prm, sub, "residual dilatancy angle", psi);
      if (!(psi_r >= 0. && psi_r <= psi && psi_r <= phi_r))
        InputFile::reject(sub,
                          "residual dilatancy angle",
                          prm.get("residual dilatancy angle"),
                          "it must be >= 0 and not above the (peak) dilatancy "
                          "angle " +
                            number(psi) +
                            " degrees nor the residual friction angle " +
                            number(phi_r) + " degrees");

      s.friction_angle           = phi * degree;
      s.cohesion                 = c;
      s.dilatancy_angle          = psi * degree;
      s.tension_cutoff           = t;
      s.recoverable_separation   = prm.get("separated volume") == "recoverable";
      s.residual_friction_angle  = phi_r * degree;
      s.residual_cohesion        = c_r;
      s.residual_dilatancy_angle = psi_r * degree;
      s.softening_strain         = prm.get_double("softening plastic strain");

      const double phi_2 =
        read_number_or(prm,
                       sub,
                       "limiting friction angle",
                       "none",
                       std::numeric_limits<double>::quiet_NaN());
      if (!std::isnan(phi_2))
        {
          if (!(phi_2 > phi && phi_2 < 90.))
            InputFile::reject(sub,
                              "limiting friction angle",
                              prm.get("limiting friction angle"),
                              "it must be 'none' or lie strictly between the "
                              "friction angle " +
                                number(phi) + " degrees and 90 degrees");
          s.friction_coefficient_increment =
            std::tan(phi_2 * degree) - std::tan(phi * degree);
          s.reference_inertial_number =
            prm.get_double("reference inertial number");
          if (!(s.reference_inertial_number > 0.) ||
              !std::isfinite(s.reference_inertial_number))
            InputFile::reject(sub,
                              "reference inertial number",
                              prm.get("reference inertial number"),
                              "it must be > 0");
          s.grain_diameter = prm.get_double("grain diameter");
          if (!(s.grain_diameter > 0.) || !std::isfinite(s.grain_diameter))
            InputFile::reject(sub,
                              "grain diameter",
                              prm.get("grain diameter"),
                              "it must be > 0 m when a limiting friction "
                              "angle is given");
          s.grain_density = prm.get_double("grain density");
          if (!(s.grain_density >= 0.) || !std::isfinite(s.grain_density))
            InputFile::reject(sub,
                              "grain density",
                              prm.get("grain density"),
                              "it must be > 0 kg/m^3, or 0 for the material "
                              "density");
        }
      if (s.softening() && !(s.softening_strain > 0.))
        InputFile::reject(sub,
                          "softening plastic strain",
                          prm.get("softening plastic strain"),
                          "it must be > 0 when a residual value differs "
                          "from its peak value (softening)");
      return s;
    }
  } // namespace Materials
} // namespace Talus
