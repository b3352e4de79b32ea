#include <talus/structure/sliding_cable.h>

#include <cmath>
#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
    namespace
    {
      /** Adds k to the entries (i, j) of segment s (nodes s and s + 1) in
       * the pattern [[1, -1], [-1, 1]]. */
      void
      add_to_segment(dealii::FullMatrix<double> &K,
                     const unsigned int          s,
                     const unsigned int          i,
                     const unsigned int          j,
                     const double                k)
      {
        K(3 * s + i, 3 * s + j) += k;
        K(3 * (s + 1) + i, 3 * (s + 1) + j) += k;
        K(3 * s + i, 3 * (s + 1) + j) -= k;
        K(3 * (s + 1) + i, 3 * s + j) -= k;
      }
    } // namespace

    double
    SlidingCable::compute(const std::vector<dealii::Tensor<1, 3>> &X,
                          const std::vector<dealii::Tensor<1, 3>> &x,
                          dealii::Vector<double>                  &f,
                          dealii::FullMatrix<double>              &K,
                          double                                  *energy) const
    {
      const unsigned int n_nodes = X.size();
      if (n_nodes < 2 || x.size() != n_nodes)
        throw std::runtime_error("A sliding cable needs at least 2 nodes.");
      if (friction_coefficient > 0.)
        {
          K.reinit(3 * n_nodes, 3 * n_nodes);
          const double N0 = friction_forces(X, x, f);
          if (N0 > 0.)
            {
              // One run through all nodes, every node slipping towards the
              // last one; material lengths L_i = l_i / lambda(N_i).
              const AxialLaw      law = this->law();
              std::vector<double> L(n_nodes - 1);
              for (unsigned int i = 0; i + 1 < n_nodes; ++i)
                L[i] =
                  (x[i + 1] - x[i]).norm() / law.stretch(segment_forces[i]);
              const std::vector<int> slip(n_nodes - 1, +1);
              add_tension_tangent(x, L, segment_forces, slip, K);
            }
          if (N0 == 0.)
            {
              // Slack: regularising stiffness only.
              double L = 0.;
              for (unsigned int i = 0; i + 1 < n_nodes; ++i)
                L += (X[i + 1] - X[i]).norm();
              const double k =
                slack_stiffness_ratio * youngs_modulus * area / L;
              for (unsigned int i = 0; i + 1 < n_nodes; ++i)
                for (unsigned int d = 0; d < 3; ++d)
                  add_to_segment(K, i, d, d, k);
            }
          if (energy != nullptr)
            *energy = 0.; // not defined with friction (dissipative)
          return N0;
        }
      f.reinit(3 * n_nodes);
      K.reinit(3 * n_nodes, 3 * n_nodes);

      double                            L = 0., l = 0.;
      std::vector<double>               li(n_nodes - 1);
      std::vector<dealii::Tensor<1, 3>> e(n_nodes - 1);
      for (unsigned int i = 0; i + 1 < n_nodes; ++i)
        {
          L += (X[i + 1] - X[i]).norm();
          li[i] = (x[i + 1] - x[i]).norm();
          if (!(li[i] > 0.))
            throw std::runtime_error(
              "A sliding cable has two coincident consecutive nodes.");
          e[i] = (x[i + 1] - x[i]) / li[i];
          l += li[i];
        }
      // Green-Lagrange: S, N = A S l/L, dN/dl = E A l^2/L^3 + A S/L;
      // engineering: N and dN/dl of AxialLaw (S: the sign of N only).
      const bool   engineering = strain_measure == StrainMeasure::engineering;
      const double eps         = (l * l - L * L) / (2. * L * L);
      const double S =
        engineering ? law().force(l / L) : youngs_modulus * eps + prestress;
      if (energy != nullptr)
        *energy =
          engineering ?
            L * (S <= 0. ? law().slack_energy() : law().energy(l / L)) :
          S <= 0. ?
            -area * L * prestress * prestress / (2. * youngs_modulus) :
            area * L * (0.5 * youngs_modulus * eps * eps + prestress * eps);
      if (S < 0.)
        {
          // Slack: regularising stiffness on every segment only.
          const double k = slack_stiffness_ratio * youngs_modulus * area / L;
          for (unsigned int i = 0; i + 1 < n_nodes; ++i)
            for (unsigned int d = 0; d < 3; ++d)
              add_to_segment(K, i, d, d, k);
          return 0.;
        }
      const double N = engineering ? S : area * S * l / L;

      std::vector<dealii::Tensor<1, 3>> g(n_nodes);
      for (unsigned int i = 0; i + 1 < n_nodes; ++i)
        {
          g[i] -= e[i];
          g[i + 1] += e[i];
        }
      const double k_axial =
        engineering ?
          law().stiffness(l / L) / L :
          youngs_modulus * area * l * l / (L * L * L) + area * S / L;
      // Taut at zero force: the regularising stiffness across every
      // segment (LineElement::slack_stiffness_ratio).
      const double k_zero =
        N == 0. ? slack_stiffness_ratio * youngs_modulus * area / L : 0.;
      for (unsigned int a = 0; a < n_nodes; ++a)
        for (unsigned int i = 0; i < 3; ++i)
          {
            f[3 * a + i] = N * g[a][i];
            for (unsigned int b = 0; b < n_nodes; ++b)
              for (unsigned int j = 0; j < 3; ++j)
                K(3 * a + i, 3 * b + j) = k_axial * g[a][i] * g[b][j];
          }
      for (unsigned int s = 0; s + 1 < n_nodes; ++s)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double k =
                (N / li[s] + k_zero) * ((i == j ? 1. : 0.) - e[s][i] * e[s][j]);
              add_to_segment(K, s, i, j, k);
            }
      return N;
    }


    AxialLaw
    SlidingCable::law() const
    {
      return AxialLaw{strain_measure, youngs_modulus, area, prestress};
    }


    double
    SlidingCable::friction_forces(const std::vector<dealii::Tensor<1, 3>> &X,
                                  const std::vector<dealii::Tensor<1, 3>> &x,
                                  dealii::Vector<double> &f) const
    {
      const unsigned int n_nodes = X.size();
      const unsigned int n_seg   = n_nodes - 1;
      f.reinit(3 * n_nodes);
      double                            L = 0.;
      std::vector<double>               l(n_seg), c(n_seg);
      std::vector<dealii::Tensor<1, 3>> e(n_seg);
      for (unsigned int i = 0; i < n_seg; ++i)
        {
          L += (X[i + 1] - X[i]).norm();
          l[i] = (x[i + 1] - x[i]).norm();
          if (!(l[i] > 0.))
            throw std::runtime_error(
              "A sliding cable has two coincident consecutive nodes.");
          e[i] = (x[i + 1] - x[i]) / l[i];
        }
      // Tension factors from the deviation angles (sliding towards the
      // last node: the tension grows in that direction).
      c[0] = 1.;
      for (unsigned int i = 1; i < n_seg; ++i)
        {
          const double cos_theta = std::max(-1., std::min(1., e[i - 1] * e[i]));
          c[i] =
            c[i - 1] * std::exp(friction_coefficient * std::acos(cos_theta));
        }
      const double   EA = youngs_modulus * area, As0 = area * prestress;
      const AxialLaw law = this->law();
      // Stretch of a segment under force N.
      const auto stretch = [&](const double N) { return law.stretch(N); };
      // Material length in the cable at base tension N0, minus L.
      const auto excess = [&](const double N0) {
        double m = 0.;
        for (unsigned int i = 0; i < n_seg; ++i)
          m += l[i] / stretch(N0 * c[i]);
        return m - L;
      };
      segment_forces.assign(n_seg, 0.);
      if (excess(0.) <= 0.)
        return 0.; // slack
      double hi = EA * 1e-6 + std::abs(As0);
      while (excess(hi) > 0.)
        hi *= 2.;
      double lo = 0.;
      for (unsigned int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k)
        {
          const double mid             = 0.5 * (lo + hi);
          (excess(mid) > 0. ? lo : hi) = mid;
        }
      const double N0 = 0.5 * (lo + hi);
      for (unsigned int i = 0; i < n_seg; ++i)
        {
          segment_forces[i] = N0 * c[i];
          for (unsigned int d = 0; d < 3; ++d)
            {
              f[3 * i + d] -= segment_forces[i] * e[i][d];
              f[3 * (i + 1) + d] += segment_forces[i] * e[i][d];
            }
        }
      return N0;
    }
    double
    SlidingCable::compute(const std::vector<dealii::Tensor<1, 3>> &X,
                          const std::vector<dealii::Tensor<1, 3>> &x,
                          const std::vector<double>               &old_lengths,
                          dealii::Vector<double>                  &f,
                          dealii::FullMatrix<double>              &K,
                          std::vector<double> &new_lengths) const
    {
      const unsigned int n_nodes = X.size();
      if (n_nodes < 2 || x.size() != n_nodes ||
          old_lengths.size() != n_nodes - 1)
        throw std::runtime_error("A sliding cable needs at least 2 nodes.");
      std::vector<int> slip;
      const double     N0 =
        stick_slip_forces(x, old_lengths, f, new_lengths, &slip);
      const std::vector<double> saved = segment_forces;
      K.reinit(3 * n_nodes, 3 * n_nodes);
      add_tension_tangent(x, new_lengths, saved, slip, K);
      // Slack segments: regularising stiffness only.
      for (unsigned int i = 0; i + 1 < n_nodes; ++i)
        if (saved[i] == 0.)
          {
            const double k =
              slack_stiffness_ratio * youngs_modulus * area / old_lengths[i];
            for (unsigned int d = 0; d < 3; ++d)
              add_to_segment(K, i, d, d, k);
          }
      return N0;
    }


    double
    SlidingCable::stick_slip_forces(const std::vector<dealii::Tensor<1, 3>> &x,
                                    const std::vector<double> &old_lengths,
                                    dealii::Vector<double>    &f,
                                    std::vector<double>       &L,
                                    std::vector<int>          *slip) const
    {
      const unsigned int n_seg = x.size() - 1;
      f.reinit(3 * (n_seg + 1));
      std::vector<double>               l(n_seg), mu_theta(n_seg, 0.);
      std::vector<dealii::Tensor<1, 3>> e(n_seg);
      for (unsigned int i = 0; i < n_seg; ++i)
        {
          l[i] = (x[i + 1] - x[i]).norm();
          if (!(l[i] > 0.))
            throw std::runtime_error(
              "A sliding cable has two coincident consecutive nodes.");
          e[i] = (x[i + 1] - x[i]) / l[i];
        }
      // mu theta_k at interior node k (between segments k-1 and k).
      for (unsigned int k = 1; k < n_seg; ++k)
        mu_theta[k] = friction_coefficient *
                      std::acos(std::max(-1., std::min(1., e[k - 1] * e[k])));
      const AxialLaw law     = this->law();
      const auto     tension = [&](const double lambda) {
        return std::max(0., law.force(lambda));
      };
      const auto stretch = [&](const double N) { return law.stretch(N); };
      // Node states: 0 stick, +1 slip with N_k = N_{k-1} exp(mu theta_k)
      // (material moves into segment k), -1 the reverse.
      std::vector<int>    state(n_seg, 0);
      std::vector<double> N(n_seg);
      double              M_total = 0.;
      for (const double Li : old_lengths)
        M_total += Li;
      L = old_lengths;
      // Per segment: in a run whose material was redistributed.
      std::vector<bool> solved(n_seg, false);
      for (unsigned int iteration = 0; iteration < 4 * n_seg + 10; ++iteration)
        {
          // Runs of segments [a, b) joined by slipping nodes.
          L = old_lengths;
          solved.assign(n_seg, false);
          for (unsigned int a = 0; a < n_seg;)
            {
              unsigned int b = a + 1;
              while (b < n_seg && state[b] != 0)
                ++b;
              if (b > a + 1)
                {
                  std::vector<double> c(b - a, 1.);
                  double              M = 0.;
                  for (unsigned int i = a; i < b; ++i)
                    {
                      if (i > a)
                        c[i - a] =
                          c[i - a - 1] * std::exp(state[i] * mu_theta[i]);
                      M += old_lengths[i];
                    }
                  const auto excess = [&](const double Na) {
                    double m = 0.;
                    for (unsigned int i = a; i < b; ++i)
                      m += l[i] / stretch(Na * c[i - a]);
                    return m - M;
                  };
                  if (excess(0.) > 0.)
                    {
                      double hi = youngs_modulus * area * 1e-6 +
                                  std::abs(area * prestress);
                      while (excess(hi) > 0.)
                        hi *= 2.;
                      double lo = 0.;
                      for (unsigned int k = 0; k < 200 && hi - lo > 1e-15 * hi;
                           ++k)
                        {
                          const double mid             = 0.5 * (lo + hi);
                          (excess(mid) > 0. ? lo : hi) = mid;
                        }
                      const double Na = 0.5 * (lo + hi);
                      for (unsigned int i = a; i < b; ++i)
                        L[i] = l[i] / stretch(Na * c[i - a]);
                      // Round-off of the bisection: keep the run's material.
                      double m = 0.;
                      for (unsigned int i = a; i < b; ++i)
                        m += L[i];
                      for (unsigned int i = a; i < b; ++i)
                        {
                          L[i] *= M / m;
                          solved[i] = true;
                        }
                    }
                }
              a = b;
            }
          for (unsigned int i = 0; i < n_seg; ++i)
            N[i] = tension(l[i] / L[i]);
          // Update the active set.
          bool         changed = false;
          double       moved   = 0.; // s_k - s_k^old
          const double tol     = 1e-12 * M_total;
          for (unsigned int k = 1; k < n_seg; ++k)
            {
              moved += L[k - 1] - old_lengths[k - 1];
              const double limit = std::exp(mu_theta[k]) * (1. + 1e-12);
              if (state[k] == 0)
                {
                  if (N[k] > N[k - 1] * limit)
                    state[k] = +1, changed = true;
                  else if (N[k - 1] > N[k] * limit)
                    state[k] = -1, changed = true;
                }
              else if ((state[k] == +1 && moved > tol) ||
                       (state[k] == -1 && moved < -tol))
                state[k] = 0, changed = true;
            }
          if (!changed)
            break;
        }
      segment_forces = N;
      if (slip != nullptr)
        {
          // Nodes inside a redistributed run keep their slip direction;
          // the segments of a slack run behave as stuck ones.
          slip->assign(n_seg, 0);
          for (unsigned int k = 1; k < n_seg; ++k)
            if (state[k] != 0 && solved[k])
              (*slip)[k] = state[k];
        }
      for (unsigned int i = 0; i < n_seg; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            f[3 * i + d] -= N[i] * e[i][d];
            f[3 * (i + 1) + d] += N[i] * e[i][d];
          }
      return N[0];
    }


    void
    SlidingCable::add_tension_tangent(
      const std::vector<dealii::Tensor<1, 3>> &x,
      const std::vector<double>               &L,
      const std::vector<double>               &N,
      const std::vector<int>                  &slip,
      dealii::FullMatrix<double>              &K) const
    {
      const unsigned int                n_seg = x.size() - 1;
      const unsigned int                n     = 3 * (n_seg + 1);
      const AxialLaw                    law   = this->law();
      std::vector<double>               l(n_seg), lambda(n_seg), w(n_seg);
      std::vector<dealii::Tensor<1, 3>> e(n_seg);
      for (unsigned int i = 0; i < n_seg; ++i)
        {
          l[i]      = (x[i + 1] - x[i]).norm();
          e[i]      = (x[i + 1] - x[i]) / l[i];
          lambda[i] = l[i] / L[i];
          // dN/dlambda of the axial law
          const double dN = law.stiffness(lambda[i]);
          // w_i = -dL_i/dN_i at fixed l_i = L_i / (lambda_i dN/dlambda)
          w[i] = L[i] / (lambda[i] * dN);
        }
      // Gradient of the segment length l_i (dense row of length n).
      const auto add_dl = [&](const unsigned int      i,
                              const double            factor,
                              dealii::Vector<double> &g) {
        for (unsigned int d = 0; d < 3; ++d)
          {
            g[3 * i + d] -= factor * e[i][d];
            g[3 * (i + 1) + d] += factor * e[i][d];
          }
      };
      // Gradient of mu theta_k, theta_k the deviation angle at node k:
      // d theta = -u.(dx_k - dx_{k-1})/l_{k-1} - v.(dx_{k+1} - dx_k)/l_k,
      // u = (e_k - cos e_{k-1})/sin, v = (e_{k-1} - cos e_k)/sin; zero for
      // a straight node (theta = |angle| has no derivative there; its
      // central difference vanishes).
      const auto add_dmu_theta = [&](const unsigned int      k,
                                     const double            factor,
                                     dealii::Vector<double> &g) {
        const double c = e[k - 1] * e[k];
        const double s = dealii::cross_product_3d(e[k - 1], e[k]).norm();
        if (!(s > 1e-12))
          return;
        const dealii::Tensor<1, 3> u = (e[k] - c * e[k - 1]) / s,
                                   v = (e[k - 1] - c * e[k]) / s;
        const double a               = factor * friction_coefficient;
        for (unsigned int d = 0; d < 3; ++d)
          {
            g[3 * (k - 1) + d] += a * u[d] / l[k - 1];
            g[3 * k + d] -= a * u[d] / l[k - 1];
            g[3 * k + d] += a * v[d] / l[k];
            g[3 * (k + 1) + d] -= a * v[d] / l[k];
          }
      };
      // dN_i for every segment.
      std::vector<dealii::Vector<double>> dN(n_seg, dealii::Vector<double>(n));
      for (unsigned int a = 0; a < n_seg;)
        {
          unsigned int b = a + 1;
          while (b < n_seg && slip[b] != 0)
            ++b;
          if (b == a + 1)
            {
              // Stuck segment: N_a = N(l_a / L_a) with L_a fixed.
              if (N[a] > 0.)
                add_dl(a, 1. / (lambda[a] * w[a]), dN[a]);
            }
          else
            {
              // Run: N_i = N_a c_i, c_i = prod_{a<k<=i} exp(s_k mu theta_k),
              // sum_i l_i / lambda(N_i) fixed, so
              //   dN_a sum w_i c_i = sum dl_i / lambda_i - N_a sum w_i dc_i,
              //   dc_i = c_i sum_{a<k<=i} s_k d(mu theta_k).
              std::vector<dealii::Vector<double>> dc(b - a,
                                                     dealii::Vector<double>(n));
              dealii::Vector<double>              rhs(n), dtheta(n);
              double                              denominator = 0.;
              for (unsigned int i = a; i < b; ++i)
                {
                  const double c_i = N[i] / N[a];
                  if (i > a)
                    add_dmu_theta(i, slip[i], dtheta);
                  dc[i - a].add(c_i, dtheta);
                  add_dl(i, 1. / lambda[i], rhs);
                  rhs.add(-N[a] * w[i], dc[i - a]);
                  denominator += w[i] * c_i;
                }
              dN[a].add(1. / denominator, rhs);
              for (unsigned int i = a + 1; i < b; ++i)
                {
                  dN[i].add(N[i] / N[a], dN[a]);
                  dN[i].add(N[a], dc[i - a]);
                }
            }
          a = b;
        }
      // f_i -= N_i e_i, f_{i+1} += N_i e_i: material and geometric parts.
      for (unsigned int i = 0; i < n_seg; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            for (unsigned int j = 0; j < n; ++j)
              {
                K(3 * i + d, j) -= e[i][d] * dN[i][j];
                K(3 * (i + 1) + d, j) += e[i][d] * dN[i][j];
              }
            for (unsigned int c = 0; c < 3; ++c)
              {
                const double k =
                  N[i] / l[i] * ((d == c ? 1. : 0.) - e[i][d] * e[i][c]);
                add_to_segment(K, i, d, c, k);
              }
          }
    }
  } // namespace Structure
} // namespace Talus
