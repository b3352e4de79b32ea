#include <talus/structure/sliding_cable.h>

#include <cmath>
#include <stdexcept>

namespace Talus
{
  namespace Structure
  {
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
      const double eps = (l * l - L * L) / (2. * L * L);
      const double S   = youngs_modulus * eps + prestress;
      if (energy != nullptr)
        *energy =
          S <= 0. ?
            -area * L * prestress * prestress / (2. * youngs_modulus) :
            area * L * (0.5 * youngs_modulus * eps * eps + prestress * eps);
      if (S < 0.)
        {
          // Slack: regularising stiffness on every segment only.
          const double k = slack_stiffness_ratio * youngs_modulus * area / L;
          for (unsigned int i = 0; i + 1 < n_nodes; ++i)
            for (unsigned int d = 0; d < 3; ++d)
              {
                K(3 * i + d, 3 * i + d) += k;
                K(3 * (i + 1) + d, 3 * (i + 1) + d) += k;
                K(3 * i + d, 3 * (i + 1) + d) -= k;
                K(3 * (i + 1) + d, 3 * i + d) -= k;
              }
          return 0.;
        }
      const double N = area * S * l / L;

      std::vector<dealii::Tensor<1, 3>> g(n_nodes);
      for (unsigned int i = 0; i + 1 < n_nodes; ++i)
        {
          g[i] -= e[i];
          g[i + 1] += e[i];
        }
      const double k_axial =
        youngs_modulus * area * l * l / (L * L * L) + area * S / L;
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
                N / li[s] * ((i == j ? 1. : 0.) - e[s][i] * e[s][j]);
              K(3 * s + i, 3 * s + j) += k;
              K(3 * (s + 1) + i, 3 * (s + 1) + j) += k;
              K(3 * s + i, 3 * (s + 1) + j) -= k;
              K(3 * (s + 1) + i, 3 * s + j) -= k;
            }
      return N;
    }
  } // namespace Structure
} // namespace Talus
