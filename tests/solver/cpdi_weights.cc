// The CPDI1 weights of 'shape functions = CPDI'
// (Talus::MPM::internal::cpdi_weights, include/talus/mpm/point_tensors.h;
// Sadeghirad, Brannon and Burghardt 2011): the Q1 functions of a Cartesian
// grid (h = 0.25 m x 0.25 m x 0.4 m) averaged over the corners of a point's
// parallelogram (2D) or parallelepiped (3D) spanned by r_i = F r_i^0,
// r_i^0 = l0 e_i with l0 = h/4 (2 points per cell per direction), for
// points spread over their cell and the deformation gradients F = I, a
// rotation by 90 degrees, a rotation by 30 degrees with stretch, a shear,
// and (3D) a general F with det F > 0:
//  - partition of unity sum_I S_I = 1, sum_I grad S_I = 0 (to 1e-13);
//  - reproduction of linear fields: sum_I S_I x_I = x_p and
//    sum_I x_I (x) grad S_I = I (to 1e-12);
//  - F = I with the domain inside the point's cell: the uGIMP weights and
//    gradients (the exact average of the bilinear N_I), to 1e-14;
//  - a rotation by 90 degrees maps the square domain onto itself: the
//    weights and gradients of F = I (cpGIMP's diagonal stretch would give
//    a zero-width domain there);
//  - 2D: the gradient equals eq. (31)-(32) of the paper written out with
//    the corners x1 = x_p - r1 - r2, x2 = x_p + r1 - r2, x3 = x_p + r1 +
//    r2, x4 = x_p - r1 + r2 and V = 4 |r1 x r2| (to 1e-12);
//  - continuity across a cell face: the same point seen from the two cells
//    (to 1e-8);
//  - a domain whose corners would leave the grid is scaled down (scale <
//    1), its corners then lie on the grid's boundary and the partition of
//    unity still holds.
#include <talus/mpm/point_tensors.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
  int failures = 0;

  void
  check(const std::string &what, const double error, const double tolerance)
  {
    const bool ok = error <= tolerance;
    std::cout << what << ": " << (ok ? "ok" : "WRONG") << '\n';
    if (!ok)
      std::cout << "  error " << error << " > " << tolerance << '\n';
    failures += ok ? 0 : 1;
  }

  template <int dim>
  std::vector<std::array<int, dim>>
  patch()
  {
    std::vector<std::array<int, dim>> nodes;
    for (unsigned int a = 0; a < (1u << (2 * dim)); ++a)
      {
        std::array<int, dim> n;
        for (unsigned int d = 0, rest = a; d < dim; ++d, rest /= 4)
          n[d] = static_cast<int>(rest % 4) - 1;
        nodes.push_back(n);
      }
    return nodes;
  }

  template <int dim>
  dealii::Tensor<1, dim>
  cell_size()
  {
    dealii::Tensor<1, dim> h;
    const double           sizes[3] = {0.25, 0.25, 0.4};
    for (unsigned int d = 0; d < dim; ++d)
      h[d] = sizes[d];
    return h;
  }

  // R = F diag(l0), l0 = h/4
  template <int dim>
  dealii::Tensor<2, dim>
  half_vectors(const dealii::Tensor<2, dim> &F)
  {
    const auto             h = cell_size<dim>();
    dealii::Tensor<2, dim> R;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        R[i][j] = F[i][j] * h[j] / 4.;
    return R;
  }

  // the properties that hold for any F: partition of unity and the
  // reproduction of linear fields, at points all over the cell
  template <int dim>
  void
  check_consistency(const std::string &name, const dealii::Tensor<2, dim> &F)
  {
    const auto             h     = cell_size<dim>();
    const auto             nodes = patch<dim>();
    const auto             R     = half_vectors<dim>(F);
    dealii::Tensor<1, dim> lowest, highest;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lowest[d]  = -1.;
        highest[d] = 2.;
      }
    std::vector<double>                 S(nodes.size());
    std::vector<dealii::Tensor<1, dim>> G(nodes.size());
    double unity = 0., gradient_sum = 0., linear = 0., identity = 0.,
           scaled                      = 0.;
    const unsigned int n_per_direction = 5;
    const unsigned int n_points        = std::pow(n_per_direction, dim);
    for (unsigned int p = 0; p < n_points; ++p)
      {
        dealii::Point<dim> xi;
        for (unsigned int d = 0, rest = p; d < dim;
             ++d, rest /= n_per_direction)
          xi[d] = (rest % n_per_direction + 0.37) / n_per_direction;
        const double scale = Talus::MPM::internal::cpdi_weights<dim>(
          xi, R, h, lowest, highest, nodes, S.data(), G.data());
        scaled                     = std::max(scaled, std::abs(1. - scale));
        double                 sum = 0.;
        dealii::Tensor<1, dim> gsum, xsum;
        dealii::Tensor<2, dim> xg;
        for (unsigned int j = 0; j < nodes.size(); ++j)
          {
            dealii::Tensor<1, dim> x_I;
            for (unsigned int d = 0; d < dim; ++d)
              x_I[d] = nodes[j][d] * h[d];
            sum += S[j];
            gsum += G[j];
            xsum += S[j] * x_I;
            xg += dealii::outer_product(x_I, G[j]);
          }
        dealii::Tensor<1, dim> x_p;
        for (unsigned int d = 0; d < dim; ++d)
          x_p[d] = xi[d] * h[d];
        unity        = std::max(unity, std::abs(sum - 1.));
        gradient_sum = std::max(gradient_sum, gsum.norm() * h[0]);
        linear       = std::max(linear, (xsum - x_p).norm());
        identity     = std::max(identity,
                            (xg - dealii::unit_symmetric_tensor<dim>()).norm());
      }
    const std::string where = " (" + std::to_string(dim) + "D, " + name + ")";
    check("domain inside the patch, not scaled" + where, scaled, 0.);
    check("partition of unity" + where, unity, 1e-13);
    check("gradients sum to zero" + where, gradient_sum, 1e-13);
    check("reproduces x" + where, linear, 1e-13);
    check("sum x_I (x) grad S_I = I" + where, identity, 1e-12);
  }

  // F = I inside the cell: uGIMP; and the 90 degree rotation
  template <int dim>
  void
  check_undeformed(const dealii::Tensor<2, dim> &rotation)
  {
    const auto             h     = cell_size<dim>();
    const auto             nodes = patch<dim>();
    dealii::Tensor<1, dim> lowest, highest;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lowest[d]  = -1.;
        highest[d] = 2.;
      }
    const auto I = dealii::Tensor<2, dim>(dealii::unit_symmetric_tensor<dim>());
    std::vector<double>                 S(nodes.size()), S_rot(nodes.size());
    std::vector<dealii::Tensor<1, dim>> G(nodes.size()), G_rot(nodes.size());
    double                              ugimp = 0., rotated = 0.;
    for (unsigned int p = 0; p < 16; ++p)
      {
        // points whose domain (half-width 1/4 cell) stays in the cell
        dealii::Point<dim> xi;
        for (unsigned int d = 0; d < dim; ++d)
          xi[d] = 0.25 + 0.5 * ((p * (d + 3) + d) % 16) / 15.;
        Talus::MPM::internal::cpdi_weights<dim>(xi,
                                                half_vectors<dim>(I),
                                                h,
                                                lowest,
                                                highest,
                                                nodes,
                                                S.data(),
                                                G.data());
        Talus::MPM::internal::cpdi_weights<dim>(xi,
                                                half_vectors<dim>(rotation),
                                                h,
                                                lowest,
                                                highest,
                                                nodes,
                                                S_rot.data(),
                                                G_rot.data());
        for (unsigned int j = 0; j < nodes.size(); ++j)
          {
            double U[dim], dU[dim];
            for (unsigned int d = 0; d < dim; ++d)
              U[d] = Talus::MPM::internal::ugimp_weight(
                (xi[d] - nodes[j][d]) * h[d], h[d], h[d] / 4., dU[d]);
            double                 value = 1.;
            dealii::Tensor<1, dim> gradient;
            for (unsigned int d = 0; d < dim; ++d)
              {
                value *= U[d];
                gradient[d] = dU[d];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    gradient[d] *= U[e];
              }
            ugimp   = std::max(ugimp,
                             std::abs(value - S[j]) +
                               h[0] * (gradient - G[j]).norm());
            rotated = std::max(rotated,
                               std::abs(S_rot[j] - S[j]) +
                                 h[0] * (G_rot[j] - G[j]).norm());
          }
      }
    const std::string where = " (" + std::to_string(dim) + "D)";
    check("F = I in the cell: the uGIMP weights" + where, ugimp, 1e-14);
    check("rotation by 90 degrees: the weights of F = I" + where,
          rotated,
          1e-14);
  }
} // namespace

int
main()
{
  using namespace dealii;
  const double pi = M_PI;
  {
    Tensor<2, 2> I, rot90, rot30_stretch, shear;
    I[0][0] = I[1][1] = 1.;
    rot90[0][1]       = -1.;
    rot90[1][0]       = 1.;
    const double c = std::cos(pi / 6.), s = std::sin(pi / 6.);
    // R(30) diag(1.6, 0.7)
    rot30_stretch[0][0] = 1.6 * c;
    rot30_stretch[0][1] = -0.7 * s;
    rot30_stretch[1][0] = 1.6 * s;
    rot30_stretch[1][1] = 0.7 * c;
    shear               = I;
    shear[0][1]         = 1.5;
    check_consistency<2>("F = I", I);
    check_consistency<2>("rotation by 90 degrees", rot90);
    check_consistency<2>("rotation by 30 degrees, stretch 1.6 and 0.7",
                         rot30_stretch);
    check_consistency<2>("shear 1.5", shear);
    check_undeformed<2>(rot90);

    // eq. (31)-(32) of Sadeghirad et al. 2011 written out
    const auto                h     = cell_size<2>();
    const auto                nodes = patch<2>();
    const Tensor<2, 2>        R = half_vectors<2>(rot30_stretch + 0.3 * shear);
    const Tensor<1, 2>        lowest({-1., -1.}), highest({2., 2.});
    const Point<2>            xi(0.61, 0.18);
    std::vector<double>       S(nodes.size());
    std::vector<Tensor<1, 2>> G(nodes.size());
    Talus::MPM::internal::cpdi_weights<2>(
      xi, R, h, lowest, highest, nodes, S.data(), G.data());
    const Tensor<1, 2> r1({R[0][0], R[1][0]}), r2({R[0][1], R[1][1]});
    const double       V = 4. * std::abs(r1[0] * r2[1] - r1[1] * r2[0]);
    const Tensor<1, 2> x_p({xi[0] * h[0], xi[1] * h[1]});
    const Tensor<1, 2> corners[4] = {x_p - r1 - r2,
                                     x_p + r1 - r2,
                                     x_p + r1 + r2,
                                     x_p - r1 + r2};
    double             paper      = 0.;
    for (unsigned int j = 0; j < nodes.size(); ++j)
      {
        double f[4];
        for (unsigned int k = 0; k < 4; ++k)
          f[k] =
            std::max(0., 1. - std::abs(corners[k][0] / h[0] - nodes[j][0])) *
            std::max(0., 1. - std::abs(corners[k][1] / h[1] - nodes[j][1]));
        const Tensor<1, 2> a({r1[1] - r2[1], r2[0] - r1[0]});
        const Tensor<1, 2> b({r1[1] + r2[1], -r1[0] - r2[0]});
        const Tensor<1, 2> g     = ((f[0] - f[2]) * a + (f[1] - f[3]) * b) / V;
        const double       value = (f[0] + f[1] + f[2] + f[3]) / 4.;
        paper =
          std::max(paper, std::abs(value - S[j]) + h[0] * (g - G[j]).norm());
      }
    check("eq. (31)-(32) of the paper (2D)", paper, 1e-12);

    // continuity across the face x = h between cells A (xi_x = 1 - e) and
    // B (xi_x = e - 1 + 1 = e): node offset k of A is k - 1 of B
    const double              e = 1e-10;
    std::vector<double>       SB(nodes.size());
    std::vector<Tensor<1, 2>> GB(nodes.size());
    Talus::MPM::internal::cpdi_weights<2>(
      Point<2>(1. - e, 0.4), R, h, lowest, highest, nodes, S.data(), G.data());
    Talus::MPM::internal::cpdi_weights<2>(
      Point<2>(e, 0.4), R, h, lowest, highest, nodes, SB.data(), GB.data());
    double jump = 0.;
    for (unsigned int j = 0; j < nodes.size(); ++j)
      for (unsigned int k = 0; k < nodes.size(); ++k)
        if (nodes[k][0] == nodes[j][0] - 1 && nodes[k][1] == nodes[j][1])
          jump =
            std::max(jump,
                     std::abs(S[j] - SB[k]) + h[0] * (G[j] - GB[k]).norm());
    check("continuous across a cell face (2D)", jump, 1e-8);

    // a cell at the grid's lower-left corner (no nodes below offset 0):
    // the stretched domain of a point near the corner is scaled down
    const Tensor<1, 2>              at_corner({0., 0.});
    std::vector<std::array<int, 2>> inside;
    for (const auto &n : nodes)
      if (n[0] >= 0 && n[1] >= 0)
        inside.push_back(n);
    const Tensor<2, 2>        R_big = half_vectors<2>(2. * rot30_stretch);
    const Point<2>            near(0.2, 0.3);
    std::vector<double>       Sc(inside.size());
    std::vector<Tensor<1, 2>> Gc(inside.size());
    const double              scale = Talus::MPM::internal::cpdi_weights<2>(
      near, R_big, h, at_corner, highest, inside, Sc.data(), Gc.data());
    double lowest_corner = 1e300, sum = 0.;
    for (unsigned int k = 0; k < 4; ++k)
      {
        Tensor<1, 2>       s({k & 1 ? 1. : -1., k & 2 ? 1. : -1.});
        const Tensor<1, 2> o = scale * (R_big * s);
        lowest_corner        = std::min(
          {lowest_corner, near[0] + o[0] / h[0], near[1] + o[1] / h[1]});
      }
    for (const double v : Sc)
      sum += v;
    check("scaled down at the grid's boundary", scale < 1. ? 0. : 1., 0.);
    check("scaled corners on the grid's boundary",
          std::abs(lowest_corner),
          1e-14);
    check("partition of unity after scaling", std::abs(sum - 1.), 1e-14);
  }
  {
    Tensor<2, 3> I, rot90, general;
    I[0][0] = I[1][1] = I[2][2] = 1.;
    rot90[0][1]                 = -1.;
    rot90[1][0]                 = 1.;
    rot90[2][2]                 = 1.;
    general                     = I;
    general[0][0]               = 1.3;
    general[0][1]               = 0.4;
    general[1][2]               = -0.5;
    general[2][0]               = 0.3;
    general[2][2]               = 0.8;
    check_consistency<3>("F = I", I);
    check_consistency<3>("general F", general);
    check_undeformed<3>(rot90);
  }
  std::cout << (failures == 0 ? "all checks passed" : "FAILURES") << '\n';
  return failures == 0 ? 0 : 1;
}
