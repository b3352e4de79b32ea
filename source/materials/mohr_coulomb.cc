#include <talus/materials/mohr_coulomb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace Talus
{
  namespace Materials
  {
    namespace
    {
      /** A plane a . tau = r with flow direction n, their derivatives
       * with respect to the accumulated plastic strain (da, dn, dr) and
       * with respect to the trial pressure (da_dP, dr_dP: rate-dependent
       * friction). */
      struct PlaneData
      {
        dealii::Tensor<1, 3> a, da, n, dn, da_dP;
        double               r, dr, dr_dP = 0.;
      };


      /** What the rate-dependent friction of a step depends on besides
       * the accumulated plastic strain. */
      struct RateState
      {
        double plastic_strain_increment;
        double pressure;
        double time_step;
      };


      /** Friction, cohesion and dilatancy of one state of the return. */
      struct PlaneStrength
      {
        GranularStrength::RateValue phi;
        GranularStrength::Value     c;
        GranularStrength::Value     psi;
        GranularStrength::SinCos    psi_trig;
      };


      /**
       * The strength at the plastic strain @p eps_p and the @p rate state,
       * computed once for all planes of a return (the friction angle's
       * arctangent is not needed: only its sine and cosine).
       */
      PlaneStrength
      plane_strength(const GranularStrength &s,
                     const double            eps_p,
                     const RateState        &rate)
      {
        PlaneStrength p{s.phi(eps_p,
                              rate.plastic_strain_increment,
                              rate.pressure,
                              rate.time_step,
                              false),
                        s.c(eps_p),
                        s.psi(eps_p),
                        {0., 1.}};
        p.psi_trig = s.sin_cos(p.psi.value);
        return p;
      }


      PlaneData
      plane_data(const MohrCoulomb::Plane plane,
                 const GranularStrength  &s,
                 const PlaneStrength     &strength)
      {
        PlaneData d;
        if (plane == MohrCoulomb::Plane::cutoff_1 ||
            plane == MohrCoulomb::Plane::cutoff_2 ||
            plane == MohrCoulomb::Plane::cutoff_3)
          {
            const unsigned int i =
              (plane == MohrCoulomb::Plane::cutoff_1 ?
                 0 :
                 (plane == MohrCoulomb::Plane::cutoff_2 ? 1 : 2));
            d.a[i] = d.n[i] = 1.;
            d.r             = s.tension_cutoff;
            d.dr            = 0.;
            return d;
          }
        // (tau_i - tau_j) + (tau_i + tau_j) sin(phi) = 2 c cos(phi)
        unsigned int i = 0, j = 2;
        if (plane == MohrCoulomb::Plane::right_edge)
          j = 1;
        else if (plane == MohrCoulomb::Plane::left_edge)
          i = 1;
        const auto  &phi  = strength.phi;
        const auto  &c    = strength.c;
        const auto  &psi  = strength.psi;
        const double sphi = phi.sin, cphi = phi.cos;
        const double spsi = strength.psi_trig.sin, cpsi = strength.psi_trig.cos;
        d.a[i]  = 1. + sphi;
        d.a[j]  = -(1. - sphi);
        d.da[i] = d.da[j] = cphi * phi.d_plastic_strain;
        d.da_dP[i] = d.da_dP[j] = cphi * phi.d_pressure;
        d.n[i]                  = 1. + spsi;
        d.n[j]                  = -(1. - spsi);
        d.dn[i] = d.dn[j] = cpsi * psi.derivative;
        d.r               = 2. * c.value * cphi;
        d.dr =
          2. * c.derivative * cphi - 2. * c.value * sphi * phi.d_plastic_strain;
        d.dr_dP = -2. * c.value * sphi * phi.d_pressure;
        return d;
      }


      std::string
      plane_names(const dealii::ArrayView<const MohrCoulomb::Plane> &planes)
      {
        static const char *names[] = {"main plane",
                                      "right edge",
                                      "left edge",
                                      "tension cut-off 1",
                                      "tension cut-off 2",
                                      "tension cut-off 3"};
        std::string        result;
        for (const auto p : planes)
          result += (result.empty() ? "" : " + ") +
                    std::string(names[static_cast<int>(p)]);
        return result;
      }
    } // namespace



    MohrCoulomb::MohrCoulomb(const IsotropicElasticity &elastic,
                             const GranularStrength    &strength)
      : GranularPlasticity(elastic, strength)
    {}



    std::string
    MohrCoulomb::name() const
    {
      return "Mohr-Coulomb";
    }



    std::string
    MohrCoulomb::description() const
    {
      std::ostringstream s;
      s << "Mohr-Coulomb (finite strain, Hencky elasticity E = "
        << elastic.youngs_modulus << " Pa, nu = " << elastic.poissons_ratio
        << "): " << strength_parameters.to_string()
        << " (Rankine: max principal stress <= t)";
      return s.str();
    }



    double
    MohrCoulomb::yield_function(const dealii::Tensor<1, 3> &tau,
                                const double                eps_p) const
    {
      const double t1 = std::max({tau[0], tau[1], tau[2]});
      const double t3 = std::min({tau[0], tau[1], tau[2]});
      const auto   phi =
        strength_parameters.sin_cos(strength_parameters.phi(eps_p).value);
      const double c = strength_parameters.c(eps_p).value;
      return (t1 - t3) + (t1 + t3) * phi.sin - 2. * c * phi.cos;
    }



    namespace
    {
      /**
       * The local Jacobian of return_to_planes(), a bordered matrix
       * [[A, b], [c^T, d]]: A (m x m, m <= 3 active planes) couples the
       * plastic multipliers, b, c and d the accumulated plastic strain. It
       * is solved by block elimination with deal.II's 3x3 inverse of A
       * (padded with the identity) and the scalar Schur complement
       * S = d - c . A^{-1} b, so the return mapping needs no heap
       * memory (it runs at every material point in every assembly).
       */
      struct BorderedJacobian
      {
        dealii::Tensor<2, 3> A;
        dealii::Tensor<1, 3> b, c;
        double               d = 1.;

        /** Factorise: A^{-1}, A^{-1} b and S. */
        void
        factorise(const unsigned int m)
        {
          for (unsigned int i = m; i < 3; ++i)
            A[i][i] = 1.;
          A_inv  = dealii::invert(A);
          Ainv_b = A_inv * b;
          schur  = d - c * Ainv_b;
        }

        /** Solve [[A, b], [c^T, d]] (x, x_p) = (r, r_p). */
        void
        solve(const dealii::Tensor<1, 3> &r,
              const double                r_p,
              dealii::Tensor<1, 3>       &x,
              double                     &x_p) const
        {
          const dealii::Tensor<1, 3> y = A_inv * r;
          x_p                          = (r_p - c * y) / schur;
          x                            = y - Ainv_b * x_p;
        }

        dealii::Tensor<2, 3> A_inv;
        dealii::Tensor<1, 3> Ainv_b;
        double               schur = 1.;
      };
    } // namespace



    bool
    MohrCoulomb::return_to_planes(const dealii::ArrayView<const Plane> &planes,
                                  const dealii::Tensor<1, 3> &eps_trial,
                                  const double     plastic_strain_old,
                                  const double     time_step,
                                  const double     stress_scale,
                                  PrincipalReturn &result,
                                  bool            &converged_out) const
    {
      converged_out                = true;
      const unsigned int         m = planes.size();
      const double               k = std::sqrt(2. / 3.);
      dealii::Tensor<1, 3>       dgamma; // entries m..2 stay zero
      double                     eps_p = plastic_strain_old;
      std::array<PlaneData, 3>   p;
      const dealii::Tensor<1, 3> tau_trial = D * eps_trial;
      // rate-dependent friction: the trial pressure P = -tr(tau_trial)/3
      // and dP/d eps_trial_c = -K
      RateState  rate{0.,
                     -(tau_trial[0] + tau_trial[1] + tau_trial[2]) / 3.,
                     time_step};
      const bool rate_dependent =
        strength_parameters.rate_dependent() && time_step > 0.;
      // With a rate-dependent friction the unknown is the increment deps of
      // the plastic strain (eps_p = eps_p,n + deps), which the rate needs
      // to more digits than eps_p holds.
      double     deps          = 0.;
      const auto update_planes = [&]() {
        rate.plastic_strain_increment = deps;
        const PlaneStrength strength =
          plane_strength(strength_parameters, eps_p, rate);
        for (unsigned int i = 0; i < m; ++i)
          p[i] = plane_data(planes[i], strength_parameters, strength);
      };

      // Initial guess: perfectly plastic return at the old plastic strain
      // (exact without softening), then eps_p from it.
      update_planes();
      {
        dealii::Tensor<2, 3> J0;
        dealii::Tensor<1, 3> rhs;
        for (unsigned int i = 0; i < m; ++i)
          {
            rhs[i] = p[i].a * tau_trial - p[i].r;
            for (unsigned int j = 0; j < m; ++j)
              J0[i][j] = p[i].a * (D * p[j].n);
          }
        for (unsigned int i = m; i < 3; ++i)
          J0[i][i] = 1.;
        dgamma = dealii::invert(J0) * rhs;
        dealii::Tensor<1, 3> flow;
        for (unsigned int i = 0; i < m; ++i)
          flow += dgamma[i] * p[i].n;
        deps  = k * flow.norm();
        eps_p = plastic_strain_old + deps;
      }

      BorderedJacobian     J;
      dealii::Tensor<1, 3> R;
      double               R_p = 0.;
      dealii::Tensor<1, 3> tau, flow, dflow;
      double               residual = 0.;
      // residual (R, R_p) and Jacobian J of the local equations at the
      // current (dgamma, eps_p); returns the scaled residual norm
      const auto evaluate = [&]() {
        update_planes();
        flow  = dealii::Tensor<1, 3>();
        dflow = dealii::Tensor<1, 3>();
        for (unsigned int i = 0; i < m; ++i)
          {
            flow += dgamma[i] * p[i].n;
            dflow += dgamma[i] * p[i].dn;
          }
        tau                                = D * (eps_trial - flow);
        const dealii::Tensor<1, 3> dtau_dp = -(D * dflow);
        const double               norm    = flow.norm();
        const dealii::Tensor<1, 3> m_hat =
          (norm > 0. ? flow / norm : dealii::Tensor<1, 3>());
        J        = BorderedJacobian();
        double r = 0.;
        for (unsigned int i = 0; i < m; ++i)
          {
            R[i] = p[i].a * tau - p[i].r;
            r    = std::max(r, std::abs(R[i]) / stress_scale);
            for (unsigned int j = 0; j < m; ++j)
              J.A[i][j] = -(p[i].a * (D * p[j].n));
            J.b[i] = p[i].da * tau + p[i].a * dtau_dp - p[i].dr;
          }
        R_p = (rate_dependent ? deps : eps_p - plastic_strain_old) - k * norm;
        for (unsigned int j = 0; j < m; ++j)
          J.c[j] = -k * (m_hat * p[j].n);
        J.d = 1. - k * (m_hat * dflow);
        if (!std::isfinite(r) || !std::isfinite(R_p))
          fail(plane_names(planes),
               eps_trial,
               plastic_strain_old,
               "non-finite values in the local Newton iteration");
        return std::max(r,
                        std::abs(R_p) / (rate_dependent ?
                                           std::abs(deps) + 1e-12 :
                                           1. + eps_p));
      };

      bool converged = false;
      for (unsigned int it = 0; it < 50; ++it)
        {
          residual = evaluate();
          if (residual <= 1e-13)
            {
              converged = true;
              break;
            }
          J.factorise(m);
          dealii::Tensor<1, 3> dx;
          double               dx_p;
          J.solve(R, R_p, dx, dx_p);
          // With a rate-dependent friction Newton's step from the
          // rate-independent guess overshoots to negative multipliers (the
          // friction saturates in the rate): shorten the step so that no
          // positive multiplier nor the plastic strain increment falls below
          // a tenth of its value.
          if (rate_dependent)
            {
              double alpha = 1.;
              for (unsigned int i = 0; i < m; ++i)
                if (dgamma[i] > 0. && dx[i] > 0.9 * dgamma[i])
                  alpha = std::min(alpha, 0.9 * dgamma[i] / dx[i]);
              if (deps > 0. && dx_p > 0.9 * deps)
                alpha = std::min(alpha, 0.9 * deps / dx_p);
              dx *= alpha;
              dx_p *= alpha;
            }
          for (unsigned int i = 0; i < m; ++i)
            dgamma[i] -= dx[i];
          if (rate_dependent)
            {
              deps -= dx_p;
              eps_p = plastic_strain_old + deps;
            }
          else
            eps_p -= dx_p;
        }
      if (!converged)
        {
          // accept a stagnating iteration only if it is close to round-off
          residual = evaluate();
          // A rate-dependent friction may leave a set of planes without a
          // solution where a larger set has one: try the next candidate.
          if (!(residual <= 1e-10) && rate_dependent)
            {
              converged_out = false;
              return false;
            }
          if (!(residual <= 1e-10))
            fail(plane_names(planes),
                 eps_trial,
                 plastic_strain_old,
                 "the local Newton iteration did not converge in 50 "
                 "iterations");
        }

      // Admissibility: dgamma >= 0, order of the principal stresses kept,
      // no yield surface violated.
      const double tol_stress = 1e-10 * stress_scale;
      const double tol_strain = 1e-10 * stress_scale / elastic.mu;
      for (unsigned int i = 0; i < m; ++i)
        if (dgamma[i] < -tol_strain)
          return false;
      if (tau[0] < tau[1] - tol_stress || tau[1] < tau[2] - tol_stress)
        return false;
      if (rate_dependent)
        {
          // the Mohr-Coulomb function with the friction of this step
          const PlaneData main =
            plane_data(Plane::main,
                       strength_parameters,
                       plane_strength(strength_parameters, eps_p, rate));
          const double         t1 = std::max({tau[0], tau[1], tau[2]});
          const double         t3 = std::min({tau[0], tau[1], tau[2]});
          dealii::Tensor<1, 3> sorted;
          sorted[0] = t1;
          sorted[2] = t3;
          if (main.a * sorted - main.r > tol_stress)
            return false;
        }
      else if (yield_function(tau, eps_p) > tol_stress)
        return false;
      if (tau[0] - strength_parameters.tension_cutoff > tol_stress)
        return false;

      // Consistent tangent: d(dgamma, eps_p)/deps = -J^{-1} dR/deps with
      // dR_i/deps = D a_i (dR_p/deps = 0), J at the converged state.
      J.factorise(m);
      std::array<dealii::Tensor<1, 3>, 3> dgamma_deps;
      dealii::Tensor<1, 3>                dp_deps;
      const double                        K = elastic.bulk_modulus();
      for (unsigned int e = 0; e < 3; ++e)
        {
          dealii::Tensor<1, 3> rhs, x;
          double               x_p;
          // dR_i/d eps_e = (D a_i)_e + (da_i/dP . tau - dr_i/dP) dP/d eps_e
          for (unsigned int i = 0; i < m; ++i)
            rhs[i] = -(D * p[i].a)[e] + K * (p[i].da_dP * tau - p[i].dr_dP);
          J.solve(rhs, 0., x, x_p);
          for (unsigned int i = 0; i < m; ++i)
            dgamma_deps[i][e] = x[i];
          dp_deps[e] = x_p;
        }
      dealii::Tensor<2, 3> dflow_deps = dealii::outer_product(dflow, dp_deps);
      for (unsigned int i = 0; i < m; ++i)
        dflow_deps += dealii::outer_product(p[i].n, dgamma_deps[i]);

      result.tau            = tau;
      result.dtau_deps      = D - D * dflow_deps;
      result.plastic_strain = eps_p;
      return true;
    }



    PrincipalReturn
    MohrCoulomb::principal_return(const dealii::Tensor<1, 3> &eps_trial,
                                  const double plastic_strain_old,
                                  const double time_step) const
    {
      const dealii::Tensor<1, 3> tau_trial = D * eps_trial;
      const GranularStrength    &s         = strength_parameters;
      const double               t         = s.tension_cutoff;
      const double stress_scale            = std::max({std::abs(tau_trial[0]),
                                                       std::abs(tau_trial[1]),
                                                       std::abs(tau_trial[2])}) +
                                  s.cohesion + 1e-12 * elastic.mu;

      const double f_trial     = yield_function(tau_trial, plastic_strain_old);
      const bool   mc_violated = f_trial > 1e-14 * stress_scale;
      const bool   cutoff_violated = tau_trial[0] > t;
      if (!mc_violated && !cutoff_violated)
        return {tau_trial, D, plastic_strain_old, 0};

      struct Candidate
      {
        std::array<Plane, 3> planes;
        unsigned int         n_planes;
        unsigned int         type;
      };
      std::array<Candidate, 9> candidates;
      unsigned int             n_candidates = 0;
      const auto add = [&](const std::initializer_list<Plane> planes,
                           const unsigned int                 type) {
        Candidate &c = candidates[n_candidates++];
        c.n_planes   = 0;
        for (const Plane plane : planes)
          c.planes[c.n_planes++] = plane;
        c.type = type;
      };
      if (mc_violated)
        {
          add({Plane::main}, 1);
          const double spsi = s.sin_cos(s.psi(plastic_strain_old).value).sin;
          const bool   right_first = (1. - spsi) * tau_trial[0] -
                                     2. * tau_trial[1] +
                                     (1. + spsi) * tau_trial[2] >
                                   0.;
          add({Plane::main, right_first ? Plane::right_edge : Plane::left_edge},
              2);
          add({Plane::main, right_first ? Plane::left_edge : Plane::right_edge},
              2);
        }
      if (cutoff_violated)
        {
          add({Plane::cutoff_1}, 4);
          add({Plane::cutoff_1, Plane::cutoff_2}, 4);
          add({Plane::main, Plane::cutoff_1}, 4);
          add({Plane::main, Plane::right_edge, Plane::cutoff_1}, 4);
          add({Plane::main, Plane::left_edge, Plane::cutoff_1}, 4);
          add({Plane::cutoff_1, Plane::cutoff_2, Plane::cutoff_3}, 4);
        }

      PrincipalReturn result;
      bool            all_converged = true;
      for (unsigned int c = 0; c < n_candidates; ++c)
        {
          bool converged = true;
          if (return_to_planes(
                dealii::ArrayView<const Plane>(candidates[c].planes.data(),
                                               candidates[c].n_planes),
                eps_trial,
                plastic_strain_old,
                time_step,
                stress_scale,
                result,
                converged))
            {
              result.return_type = candidates[c].type;
              return result;
            }
          all_converged = all_converged && converged;
        }
      const double apex_stress =
        s.c(plastic_strain_old).value / s.tan(s.phi(plastic_strain_old).value);
      // The apex is the return only for a trial mean stress beyond it (the
      // plane and edge returns keep or lower the mean stress, psi >= 0): a
      // state below it whose plane returns did not converge has no return.
      if (!all_converged && (tau_trial[0] + tau_trial[1] + tau_trial[2]) / 3. <
                              std::min(apex_stress, t))
        fail("plane and edge returns with rate-dependent friction",
             eps_trial,
             plastic_strain_old,
             "no set of planes gave a converged, admissible return, and the "
             "trial mean stress lies below the apex");

      // Apex: tau = min(c cot(phi), t) (1, 1, 1)
      const auto apex = [&s](const double eps_p,
                             const dealii::Tensor<1, 3> &,
                             dealii::Tensor<1, 3> &T,
                             dealii::Tensor<1, 3> &dT_dp,
                             dealii::Tensor<2, 3> &dT_deps) {
        const auto   apex_p  = s.apex_pressure(eps_p);
        const double p_apex  = apex_p.value;
        const double dp_apex = apex_p.derivative;
        for (unsigned int a = 0; a < 3; ++a)
          {
            T[a]     = p_apex;
            dT_dp[a] = dp_apex;
          }
        dT_deps = dealii::Tensor<2, 3>();
      };
      return prescribed_stress_return(
        eps_trial, plastic_strain_old, apex, apex_stress <= t ? 3 : 4, "apex");
    }
  } // namespace Materials
} // namespace Talus
