#include <talus/structure/membrane.h>

#include <cmath>

namespace Talus
{
  namespace Structure
  {
    using dealii::Tensor;

    void
    MembraneMaterial::set_isotropic(const double E, const double nu)
    {
      youngs_modulus_1 = E;
      youngs_modulus_2 = E;
      poissons_ratio   = nu;
      shear_modulus    = E / (2. * (1. + nu));
    }


    Tensor<2, 3>
    MembraneMaterial::elasticity() const
    {
      const double nu21 = poissons_ratio * youngs_modulus_2 / youngs_modulus_1;
      const double D    = 1. - poissons_ratio * nu21;
      Tensor<2, 3> C;
      C[0][0] = youngs_modulus_1 / D;
      C[1][1] = youngs_modulus_2 / D;
      C[0][1] = C[1][0] = poissons_ratio * youngs_modulus_2 / D;
      C[2][2]           = shear_modulus;
      return C;
    }


    namespace
    {
      /** Smaller principal value of a Voigt stress S = [S11, S22, S12] and
       * the angle theta of its direction n = (cos theta, sin theta). */
      double
      minor_principal(const Tensor<1, 3> &S, double &theta)
      {
        const double m = 0.5 * (S[0] + S[1]);
        const double R = std::hypot(0.5 * (S[0] - S[1]), S[2]);
        theta =
          0.5 * std::atan2(2. * S[2], S[0] - S[1]) + 0.5 * dealii::numbers::PI;
        return m - R;
      }

      /** a(theta) = [n1^2, n2^2, 2 n1 n2], so that a.S = n.S n. */
      Tensor<1, 3>
      direction_vector(const double theta)
      {
        const double c = std::cos(theta), s = std::sin(theta);
        return Tensor<1, 3>({c * c, s * s, 2. * c * s});
      }
    } // namespace


    Tensor<1, 3>
    MembraneMaterial::wrinkled_stress(const Tensor<1, 3> &E,
                                      Tensor<2, 3>       *tangent) const
    {
      const Tensor<2, 3> C = elasticity();
      const Tensor<1, 3> S = C * E + prestress;
      // Wrinkle strain beta a(theta) (a contraction along n): the relaxed
      // stress S_w = S - beta C a with beta = (a.S)/(a.C a) carries no
      // normal stress along n; the angle makes it carry no shear either,
      // F(theta) = a'(theta).S_w = 0, which is the stationarity of
      // q(theta) = (a.S)^2/(a.C a), the strain energy released by the
      // wrinkles: theta maximises q over the directions of compression
      // a.S < 0 (Roddeman et al. 1987; Raible et al. 2005, Jarasjarungkiat
      // et al. 2008 for orthotropic sheets). Isotropic: q is largest along
      // the minor principal stress.
      const auto a_of  = [](const double th) { return direction_vector(th); };
      const auto da_of = [](const double th) {
        return Tensor<1, 3>(
          {-std::sin(2. * th), std::sin(2. * th), 2. * std::cos(2. * th)});
      };
      const auto dda_of = [](const double th) {
        return Tensor<1, 3>({-2. * std::cos(2. * th),
                             2. * std::cos(2. * th),
                             -4. * std::sin(2. * th)});
      };
      // F and dF/dtheta at theta.
      const auto F = [&](const double th, double &dF) {
        const Tensor<1, 3> a = a_of(th), da = da_of(th), b = C * a;
        const double       psi = a * b, beta = (a * S) / psi;
        const Tensor<1, 3> S_w   = S - beta * b;
        const double       dbeta = (da * S) / psi - 2. * beta * (da * b) / psi;
        const Tensor<1, 3> dS_w  = -dbeta * b - beta * (C * da);
        dF                       = dda_of(th) * S_w + da * dS_w;
        return da * S_w;
      };

      double theta;
      minor_principal(S, theta);
      {
        // Start: the best of the minor principal direction and 64 angles.
        const auto q = [&](const double th) {
          const Tensor<1, 3> a   = a_of(th);
          const double       phi = a * S;
          return phi < 0. ? phi * phi / (a * (C * a)) : -1.;
        };
        const unsigned int n_samples = 64;
        const double       h         = dealii::numbers::PI / n_samples;
        double             q_best    = q(theta);
        for (unsigned int k = 0; k < n_samples; ++k)
          if (const double qk = q(k * h); qk > q_best)
            {
              q_best = qk;
              theta  = k * h;
            }
        // Safeguarded Newton on F = 0 (bisection where F changes sign in
        // [theta - h, theta + h]).
        double       dF;
        double       lo = theta - h, hi = theta + h;
        double       F_lo      = F(lo, dF);
        const double F_hi      = F(hi, dF);
        const bool   bracketed = F_lo * F_hi < 0.;
        const double scale     = S.norm() + 1e-300;
        for (unsigned int it = 0; it < 100; ++it)
          {
            const double f = F(theta, dF);
            if (f == 0.)
              break;
            double next = theta - f / dF;
            if (bracketed)
              {
                if ((f < 0.) == (F_lo < 0.))
                  {
                    lo   = theta;
                    F_lo = f;
                  }
                else
                  hi = theta;
                if (!(next > lo && next < hi))
                  next = 0.5 * (lo + hi);
              }
            else if (!std::isfinite(next) || std::abs(dF) < 1e-12 * scale ||
                     std::abs(next - theta) > h)
              break;
            const bool done = std::abs(next - theta) <= 1e-15;
            theta           = next;
            if (done)
              break;
          }
      }

      const Tensor<1, 3> a = a_of(theta), b = C * a;
      const double       psi = a * b, beta = (a * S) / psi;
      const Tensor<1, 3> S_w = S - beta * b;
      if (tangent != nullptr)
        {
          // Consistent tangent. At fixed theta, dS_w/dE = D = C - b b/psi;
          // theta follows E by F(theta, E) = 0:
          //   dtheta/dE = -F_E/F_theta, F_E = D a',
          // and dS_w/dtheta = -beta D a' there, so
          //   dS_w/dE = D + (beta/F_theta) F_E F_E   (symmetric: the
          // second derivative of the relaxed energy).
          const Tensor<2, 3> D   = C - outer_product(b, b) / psi;
          const Tensor<1, 3> F_E = D * da_of(theta);
          double             F_theta;
          F(theta, F_theta);
          *tangent = D;
          if (std::abs(F_theta) > 1e-12 * (S.norm() + 1e-300))
            *tangent += (beta / F_theta) * outer_product(F_E, F_E);
        }
      return S_w;
    }


    MembraneMaterial::State
    MembraneMaterial::stress(const Tensor<1, 3> &E,
                             Tensor<1, 3>       &S,
                             Tensor<2, 3>       &C_tangent) const
    {
      const Tensor<2, 3> C = elasticity();
      S                    = C * E + prestress;
      C_tangent            = C;
      if (!wrinkling)
        return State::taut;
      double theta;
      if (minor_principal(S, theta) > 0.)
        return State::taut;
      // Slack where no direction is stretched: the larger principal value
      // of the elastic strain E + C^-1 S_0 (the pre-stress as a pre-strain)
      // is <= 0 (Raible et al. 2005 without pre-stress). At this boundary
      // the relaxed stress S_w (uniaxial) vanishes, so the stress is
      // continuous; a uniaxial S_w without tension is slack as well.
      const Tensor<1, 3> E_el = E + dealii::invert(C) * prestress;
      const double       eps_max =
        0.5 * (E_el[0] + E_el[1]) +
        std::hypot(0.5 * (E_el[0] - E_el[1]), 0.5 * E_el[2]);
      Tensor<2, 3>       C_w;
      const Tensor<1, 3> S_w =
        eps_max > 0. ? wrinkled_stress(E, &C_w) : Tensor<1, 3>();
      if (eps_max <= 0. || S_w[0] + S_w[1] <= 0.)
        {
          S         = 0.;
          C_tangent = slack_stiffness_ratio * C;
          return State::slack;
        }
      S         = S_w;
      C_tangent = C_w;
      return State::wrinkled;
    }


    Membrane::Membrane()
    {
      fibre_direction[0] = 1.;
    }


    void
    Membrane::compute(const dealii::FEValues<2, 3> &fe_values,
                      const std::vector<double>    &u,
                      const double                  load_factor,
                      dealii::Vector<double>       &r,
                      dealii::FullMatrix<double>   &K,
                      MembraneCellOutput           *output) const
    {
      const auto        &fe     = fe_values.get_fe();
      const unsigned int n_dofs = fe.n_dofs_per_cell();
      r.reinit(n_dofs);
      K.reinit(n_dofs, n_dofs);
      if (output != nullptr)
        *output = MembraneCellOutput();
      const double t = material.thickness;

      std::vector<unsigned int> comp(n_dofs);
      for (unsigned int i = 0; i < n_dofs; ++i)
        comp[i] = fe.system_to_component_index(i).first;
      std::vector<std::array<double, 2>> dN(n_dofs);

      for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
        {
          const auto  &J = fe_values.jacobian(q);
          Tensor<1, 3> a1, a2;
          for (unsigned int d = 0; d < 3; ++d)
            {
              a1[d] = J[d][0];
              a2[d] = J[d][1];
            }
          Tensor<1, 3> normal = cross_product_3d(a1, a2);
          normal /= normal.norm();
          Tensor<1, 3> t1 =
            fibre_direction - (fibre_direction * normal) * normal;
          if (t1.norm() < 1e-8)
            t1 = a1;
          t1 /= t1.norm();
          const Tensor<1, 3> t2 = cross_product_3d(normal, t1);

          // N_I,a and g_a = F t_a.
          Tensor<1, 3> g1 = t1, g2 = t2;
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              const Tensor<1, 3> grad =
                fe_values.shape_grad_component(i, q, comp[i]);
              dN[i] = {{grad * t1, grad * t2}};
              g1[comp[i]] += u[i] * dN[i][0];
              g2[comp[i]] += u[i] * dN[i][1];
            }
          const Tensor<1, 3> E(
            {0.5 * (g1 * g1 - 1.), 0.5 * (g2 * g2 - 1.), g1 * g2});
          Tensor<1, 3> S;
          Tensor<2, 3> C;
          const auto   state = material.stress(E, S, C);
          const double dA    = fe_values.JxW(q);

          // B_i (Voigt) for each dof.
          std::vector<Tensor<1, 3>> B(n_dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              const unsigned int c = comp[i];
              B[i]                 = Tensor<1, 3>({dN[i][0] * g1[c],
                                                   dN[i][1] * g2[c],
                                                   dN[i][0] * g2[c] + dN[i][1] * g1[c]});
            }
          const Tensor<1, 3> area_vector = cross_product_3d(g1, g2);
          const double       p           = load_factor * pressure;
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              const double Ni = fe_values.shape_value_component(i, q, comp[i]);
              r[i] += t * (B[i] * S) * dA - p * Ni * area_vector[comp[i]] * dA;
              const Tensor<1, 3> CBi = C * B[i];
              for (unsigned int j = 0; j < n_dofs; ++j)
                {
                  double k = t * (CBi * B[j]);
                  if (comp[i] == comp[j])
                    k +=
                      t *
                      (S[0] * dN[i][0] * dN[j][0] + S[1] * dN[i][1] * dN[j][1] +
                       S[2] * (dN[i][0] * dN[j][1] + dN[i][1] * dN[j][0]));
                  if (p != 0.)
                    {
                      // d(g1 x g2)/du_j = N_j,1 e_c x g2 + N_j,2 g1 x e_c
                      Tensor<1, 3> ec;
                      ec[comp[j]] = 1.;
                      const Tensor<1, 3> dA_vec =
                        dN[j][0] * cross_product_3d(ec, g2) +
                        dN[j][1] * cross_product_3d(g1, ec);
                      k -= p * Ni * dA_vec[comp[i]];
                    }
                  K(i, j) += k * dA;
                }
            }

          if (output != nullptr)
            {
              // Cauchy stress sigma = F S F^T / J in the current basis.
              const double       J_area = area_vector.norm();
              Tensor<2, 3>       sigma;
              const double       S_ab[2][2] = {{S[0], S[2]}, {S[2], S[1]}};
              const Tensor<1, 3> g[2]       = {g1, g2};
              for (unsigned int a = 0; a < 2; ++a)
                for (unsigned int b = 0; b < 2; ++b)
                  sigma += S_ab[a][b] / J_area * outer_product(g[a], g[b]);
              // In-plane principal values: on the current tangent plane.
              Tensor<1, 3> c1 = g1 / g1.norm();
              Tensor<1, 3> c2 = g2 - (g2 * c1) * c1;
              c2 /= c2.norm();
              const double s11 = c1 * (sigma * c1), s22 = c2 * (sigma * c2),
                           s12 = c1 * (sigma * c2);
              const double m   = 0.5 * (s11 + s22);
              const double R   = std::hypot(0.5 * (s11 - s22), s12);
              output->area += dA;
              const Tensor<1, 3> CE = material.elasticity() * E;
              output->strain_energy +=
                t * (0.5 * (E * CE) + material.prestress * E) * dA;
              output->mean_stress += m * dA;
              output->max_principal += (m + R) * dA;
              output->min_principal += (m - R) * dA;
              if (state == MembraneMaterial::State::wrinkled)
                ++output->n_wrinkled;
              if (state == MembraneMaterial::State::slack)
                ++output->n_slack;
            }
        }
      if (output != nullptr && output->area > 0.)
        {
          output->mean_stress /= output->area;
          output->max_principal /= output->area;
          output->min_principal /= output->area;
        }
    }
  } // namespace Structure
} // namespace Talus
