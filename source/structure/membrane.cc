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
      /** Smaller principal value of a Voigt stress and its direction. */
      double
      minor_principal(const Tensor<1, 3> &S, Tensor<1, 2> &n)
      {
        const double m = 0.5 * (S[0] + S[1]);
        const double R = std::hypot(0.5 * (S[0] - S[1]), S[2]);
        const double theta =
          0.5 * std::atan2(2. * S[2], S[0] - S[1]) + 0.5 * dealii::numbers::PI;
        n[0] = std::cos(theta);
        n[1] = std::sin(theta);
        return m - R;
      }
    } // namespace


    Tensor<1, 3>
    MembraneMaterial::wrinkled_stress(const Tensor<1, 3> &E) const
    {
      const Tensor<2, 3> C = elasticity();
      const Tensor<1, 3> S = C * E + prestress;
      Tensor<1, 2>       n;
      minor_principal(S, n);
      const Tensor<1, 3> a({n[0] * n[0], n[1] * n[1], 2. * n[0] * n[1]});
      const Tensor<1, 3> Ca = C * a;
      return S - (a * S) / (a * Ca) * Ca;
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
      Tensor<1, 2> n;
      if (minor_principal(S, n) > 0.)
        return State::taut;
      const double eps_max =
        0.5 * (E[0] + E[1]) + std::hypot(0.5 * (E[0] - E[1]), 0.5 * E[2]);
      if (eps_max <= 0.)
        {
          S         = 0.;
          C_tangent = slack_stiffness_ratio * C;
          return State::slack;
        }
      S = wrinkled_stress(E);
      // Tangent by central differences (n rotates with E).
      const double h = 1e-6 * std::max(E.norm(), 1e-10);
      for (unsigned int j = 0; j < 3; ++j)
        {
          Tensor<1, 3> Ep = E, Em = E;
          Ep[j] += h;
          Em[j] -= h;
          const Tensor<1, 3> dS =
            (wrinkled_stress(Ep) - wrinkled_stress(Em)) / (2. * h);
          for (unsigned int i = 0; i < 3; ++i)
            C_tangent[i][j] = dS[i];
        }
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
