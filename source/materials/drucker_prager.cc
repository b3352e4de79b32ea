#include <talus/materials/drucker_prager.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace Talus
{
  namespace Materials
  {
    DruckerPrager::DruckerPrager(const IsotropicElasticity &elastic,
                                 const GranularStrength    &strength,
                                 const ConeFit              fit)
      : GranularPlasticity(elastic, strength)
      , fit(fit)
    {}



    std::string
    DruckerPrager::name() const
    {
      return "Drucker-Prager";
    }



    GranularStrength::Value
    DruckerPrager::eta(const double angle) const
    {
      const double s = std::sin(angle), c = std::cos(angle);
      const double k = 6. / std::sqrt(3.);
      switch (fit)
        {
          case ConeFit::plane_strain:
            {
              const double t = std::tan(angle);
              const double q = 9. + 12. * t * t;
              return {3. * t / std::sqrt(q), 27. / std::pow(q, 1.5) / (c * c)};
            }
          case ConeFit::triaxial_compression:
            return {k * s / (3. - s), k * 3. / ((3. - s) * (3. - s)) * c};
          case ConeFit::triaxial_extension:
          default:
            return {k * s / (3. + s), k * 3. / ((3. + s) * (3. + s)) * c};
        }
    }



    GranularStrength::Value
    DruckerPrager::xi(const double phi) const
    {
      const double s = std::sin(phi), c = std::cos(phi);
      const double k = 6. / std::sqrt(3.);
      switch (fit)
        {
          case ConeFit::plane_strain:
            {
              const double t = std::tan(phi);
              const double q = 9. + 12. * t * t;
              return {3. / std::sqrt(q), -36. * t / std::pow(q, 1.5) / (c * c)};
            }
          case ConeFit::triaxial_compression:
            return {k * c / (3. - s),
                    k * (1. - 3. * s) / ((3. - s) * (3. - s))};
          case ConeFit::triaxial_extension:
          default:
            return {k * c / (3. + s),
                    k * (-1. - 3. * s) / ((3. + s) * (3. + s))};
        }
    }



    std::string
    DruckerPrager::description() const
    {
      std::ostringstream s;
      s << "Drucker-Prager (finite strain, Hencky elasticity E = "
        << elastic.youngs_modulus << " Pa, nu = " << elastic.poissons_ratio
        << "): cone fit "
        << (fit == ConeFit::plane_strain ?
              "plane strain" :
              (fit == ConeFit::triaxial_compression ?
                 "triaxial compression (outer cone)" :
                 "triaxial extension (inner cone)"))
        << ", eta = " << eta(strength_parameters.friction_angle).value
        << ", xi = " << xi(strength_parameters.friction_angle).value
        << " (sqrt(J2)/(-p) = " << eta(strength_parameters.friction_angle).value
        << " for c = 0), " << strength_parameters.to_string()
        << " (mean stress p <= t)";
      return s.str();
    }



    double
    DruckerPrager::yield_function(const dealii::Tensor<1, 3> &tau,
                                  const double                eps_p) const
    {
      const double p  = (tau[0] + tau[1] + tau[2]) / 3.;
      double       J2 = 0.;
      for (unsigned int a = 0; a < 3; ++a)
        J2 += 0.5 * (tau[a] - p) * (tau[a] - p);
      const double phi = strength_parameters.phi(eps_p).value;
      return std::sqrt(J2) + eta(phi).value * p -
             xi(phi).value * strength_parameters.c(eps_p).value;
    }



    PrincipalReturn
    DruckerPrager::principal_return(const dealii::Tensor<1, 3> &eps_trial,
                                    const double plastic_strain_old,
                                    const double time_step) const
    {
      const GranularStrength    &s         = strength_parameters;
      const double               t         = s.tension_cutoff;
      const double               K         = elastic.bulk_modulus();
      const double               mu        = elastic.mu;
      const double               k         = std::sqrt(2. / 3.);
      const dealii::Tensor<1, 3> tau_trial = D * eps_trial;
      const double stress_scale            = std::max({std::abs(tau_trial[0]),
                                                       std::abs(tau_trial[1]),
                                                       std::abs(tau_trial[2])}) +
                                  s.cohesion + 1e-12 * mu;

      dealii::Tensor<1, 3> one, N;
      dealii::Tensor<2, 3> I_dev;
      for (unsigned int a = 0; a < 3; ++a)
        {
          one[a] = 1.;
          for (unsigned int b = 0; b < 3; ++b)
            I_dev[a][b] = (a == b ? 1. : 0.) - 1. / 3.;
        }
      const double eps_v = eps_trial[0] + eps_trial[1] + eps_trial[2];
      const dealii::Tensor<1, 3> e_d       = eps_trial - eps_v / 3. * one;
      const double               e_norm    = e_d.norm();
      const double               p_trial   = K * eps_v;
      const double               sJ2_trial = std::sqrt(2.) * mu * e_norm;
      // the deviatoric direction, if there is one
      const bool has_deviator = e_norm > 1e-14 * (std::abs(eps_v) + 1e-300);
      if (has_deviator)
        N = e_d / e_norm;

      const double f_trial = yield_function(tau_trial, plastic_strain_old);
      const bool   cone_violated   = f_trial > 1e-14 * stress_scale;
      const bool   cutoff_violated = p_trial > t;
      if (!cone_violated && !cutoff_violated)
        return {tau_trial, D, plastic_strain_old, 0};

      const double tol_stress = 1e-10 * stress_scale;

      // 1. cone: unknowns dgamma and eps_p (with a rate-dependent friction
      // the increment deps = eps_p - eps_p,n, which the rate needs to more
      // digits than eps_p holds)
      const bool rate_dependent = s.rate_dependent() && time_step > 0.;
      if (cone_violated && has_deviator)
        {
          double dgamma = 0., eps_p = plastic_strain_old, deps = 0.;
          double R1 = 0., R2 = 0., J11 = 0., J12 = 0., J21 = 0., J22 = 0.;
          double eta_bar = 0., deta_bar = 0.;
          // d R1/d P_trial of the rate-dependent friction (P = -p_trial)
          double     dR1_dP   = 0.;
          const auto evaluate = [&]() {
            const auto phi   = s.phi(eps_p, deps, -p_trial, time_step);
            const auto c     = s.c(eps_p);
            const auto psi   = s.psi(eps_p);
            const auto e     = eta(phi.value);
            const auto x     = xi(phi.value);
            const auto eb    = eta(psi.value);
            eta_bar          = eb.value;
            deta_bar         = eb.derivative * psi.derivative;
            const double de  = e.derivative * phi.d_plastic_strain;
            const double dxc = x.derivative * phi.d_plastic_strain * c.value +
                               x.value * c.derivative;
            const double kdp  = k * std::sqrt(0.5 + eta_bar * eta_bar / 3.);
            const double dkdp = k * (eta_bar * deta_bar / 3.) /
                                std::sqrt(0.5 + eta_bar * eta_bar / 3.);
            const double p = p_trial - K * eta_bar * dgamma;
            R1 = sJ2_trial - mu * dgamma + e.value * p - x.value * c.value;
            R2 = (rate_dependent ? deps : eps_p - plastic_strain_old) -
                 kdp * dgamma;
            dR1_dP =
              (e.derivative * p - x.derivative * c.value) * phi.d_pressure;
            J11 = -mu - e.value * K * eta_bar;
            J12 = de * p - e.value * K * deta_bar * dgamma - dxc;
            J21 = -kdp;
            J22 = 1. - dkdp * dgamma;
            const double r =
              std::max(std::abs(R1) / stress_scale,
                       std::abs(R2) / (rate_dependent ? std::abs(deps) + 1e-12 :
                                                        1. + eps_p));
            if (!std::isfinite(r))
              fail("cone",
                   eps_trial,
                   plastic_strain_old,
                   "non-finite values in the local Newton iteration");
            return r;
          };
          bool converged = false;
          for (unsigned int it = 0; it < 50 && !converged; ++it)
            {
              if (evaluate() <= 1e-13)
                {
                  converged = true;
                  break;
                }
              const double det    = J11 * J22 - J12 * J21;
              double       d_dg   = (J22 * R1 - J12 * R2) / det;
              double       d_deps = (-J21 * R1 + J11 * R2) / det;
              if (rate_dependent)
                {
                  // no overshoot to a negative multiplier or increment (the
                  // friction saturates in the rate; see MohrCoulomb)
                  double alpha = 1.;
                  if (dgamma > 0. && d_dg > 0.9 * dgamma)
                    alpha = std::min(alpha, 0.9 * dgamma / d_dg);
                  if (deps > 0. && d_deps > 0.9 * deps)
                    alpha = std::min(alpha, 0.9 * deps / d_deps);
                  d_dg *= alpha;
                  d_deps *= alpha;
                  dgamma -= d_dg;
                  deps -= d_deps;
                  eps_p = plastic_strain_old + deps;
                }
              else
                {
                  dgamma -= d_dg;
                  eps_p -= d_deps;
                }
            }
          if (!converged && !(evaluate() <= 1e-10))
            fail("cone",
                 eps_trial,
                 plastic_strain_old,
                 "the local Newton iteration did not converge in 50 "
                 "iterations");

          const double sJ2 = sJ2_trial - mu * dgamma;
          const double p   = p_trial - K * eta_bar * dgamma;
          if (sJ2 >= -tol_stress && p <= t + tol_stress)
            {
              PrincipalReturn r;
              r.tau = p * one + std::sqrt(2.) * std::max(sJ2, 0.) * N;
              r.plastic_strain = eps_p;
              r.return_type    = 1;
              // [d dgamma; d eps_p] = -J^{-1} [g; 0], g = dR1/deps (with
              // dP/deps = -K one for the rate-dependent friction)
              const dealii::Tensor<1, 3> g =
                std::sqrt(2.) * mu * N +
                eta(s.phi(eps_p, deps, -p_trial, time_step).value).value * K *
                  one -
                dR1_dP * K * one;
              const double               det     = J11 * J22 - J12 * J21;
              const dealii::Tensor<1, 3> ddgamma = -J22 / det * g;
              const dealii::Tensor<1, 3> deps_p  = J21 / det * g;
              const dealii::Tensor<1, 3> dp = K * one - K * eta_bar * ddgamma -
                                              K * dgamma * deta_bar * deps_p;
              r.dtau_deps =
                dealii::outer_product(one, dp) +
                mu * (2. * I_dev -
                      std::sqrt(2.) * dealii::outer_product(N, ddgamma) -
                      std::sqrt(2.) * dgamma / e_norm *
                        (I_dev - dealii::outer_product(N, N)));
              return r;
            }
        }

      if (cutoff_violated)
        {
          // 2. cap: p = t, deviator kept
          const auto cap = [&](const double,
                               const dealii::Tensor<1, 3> &,
                               dealii::Tensor<1, 3> &T,
                               dealii::Tensor<1, 3> &dT_dp,
                               dealii::Tensor<2, 3> &dT_deps) {
            T       = t * one + 2. * mu * e_d;
            dT_dp   = dealii::Tensor<1, 3>();
            dT_deps = 2. * mu * I_dev;
          };
          const PrincipalReturn r = prescribed_stress_return(
            eps_trial, plastic_strain_old, cap, 4, "tension cut-off");
          if (yield_function(r.tau, r.plastic_strain) <= tol_stress)
            return r;

          // 3. corner of cap and cone: p = t, sqrt(J2) = xi c - eta t
          const double apex_stress = s.c(plastic_strain_old).value /
                                     std::tan(s.phi(plastic_strain_old).value);
          if (has_deviator && t < apex_stress)
            {
              const auto corner = [&](const double eps_p,
                                      const dealii::Tensor<1, 3> &,
                                      dealii::Tensor<1, 3> &T,
                                      dealii::Tensor<1, 3> &dT_dp,
                                      dealii::Tensor<2, 3> &dT_deps) {
                const auto   phi = s.phi(eps_p);
                const auto   c   = s.c(eps_p);
                const auto   e   = eta(phi.value);
                const auto   x   = xi(phi.value);
                const double R   = x.value * c.value - e.value * t;
                const double dR  = x.derivative * phi.derivative * c.value +
                                  x.value * c.derivative -
                                  e.derivative * phi.derivative * t;
                T       = t * one + std::sqrt(2.) * R * N;
                dT_dp   = std::sqrt(2.) * dR * N;
                dT_deps = std::sqrt(2.) * R / e_norm *
                          (I_dev - dealii::outer_product(N, N));
              };
              const PrincipalReturn r =
                prescribed_stress_return(eps_trial,
                                         plastic_strain_old,
                                         corner,
                                         4,
                                         "tension cut-off corner");
              const double phi = s.phi(r.plastic_strain).value;
              if (xi(phi).value * s.c(r.plastic_strain).value -
                    eta(phi).value * t >=
                  0.)
                return r;
            }
        }

      // 4. apex: p = min(c cot(phi), t), s = 0
      const auto apex = [&](const double eps_p,
                            const dealii::Tensor<1, 3> &,
                            dealii::Tensor<1, 3> &T,
                            dealii::Tensor<1, 3> &dT_dp,
                            dealii::Tensor<2, 3> &dT_deps) {
        const auto   apex_p  = s.apex_pressure(eps_p);
        const double p_apex  = apex_p.value;
        const double dp_apex = apex_p.derivative;
        T                    = p_apex * one;
        dT_dp                = dp_apex * one;
        dT_deps              = dealii::Tensor<2, 3>();
      };
      const double apex_stress = s.c(plastic_strain_old).value /
                                 std::tan(s.phi(plastic_strain_old).value);
      return prescribed_stress_return(
        eps_trial, plastic_strain_old, apex, apex_stress <= t ? 3 : 4, "apex");
    }
  } // namespace Materials
} // namespace Talus
