#include <talus/base/input.h>
#include <talus/structure/continuum_solid.h>
#include <talus/structure/mesh_input.h>

#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/fe/fe_values_extractors.h>

#include <cmath>
#include <sstream>

namespace Talus
{
  namespace Structure
  {
    template <int dim>
    void
    ContinuumSolid<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Young's modulus",
                        "2.1e11",
                        dealii::Patterns::Double(),
                        "Young's modulus E of the St. Venant-Kirchhoff solid "
                        "[Pa], > 0.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        dealii::Patterns::Double(),
                        "Poisson's ratio nu of the solid [-], strictly "
                        "between -1 and 0.5.");
      prm.declare_entry("density",
                        "7850",
                        dealii::Patterns::Double(),
                        "Density rho_0 of the solid (reference "
                        "configuration) [kg/m^3], >= 0.");
      prm.declare_entry("degree",
                        "1",
                        dealii::Patterns::Integer(1, 4),
                        "Polynomial degree of the FE_Q elements of the solid "
                        "[-] (Gauss quadrature with degree + 1 points per "
                        "direction; ties to other meshes are at the cell "
                        "vertices).");
      prm.declare_entry(
        "material law",
        "St. Venant-Kirchhoff",
        dealii::Patterns::Selection("St. Venant-Kirchhoff|neo-Hookean"),
        "Hyperelastic law of the solid, both with the Lame constants of "
        "'Young's modulus' and 'Poisson's ratio': 'St. Venant-Kirchhoff', "
        "S = lambda tr(E) I + 2 mu E with the Green-Lagrange strain E (for "
        "moderate strains; it softens in strong compression); "
        "'neo-Hookean', P = mu (F - F^-T) + lambda ln J F^-T, the law of "
        "the MPM's 'neo-Hookean' material (large strains).");
    }


    template <int dim>
    void
    ContinuumSolid<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                          const std::string        &subsection)
    {
      youngs_modulus = get_positive(prm, subsection, "Young's modulus");
      poissons_ratio =
        get_in_open_interval(prm, subsection, "Poisson's ratio", -1., 0.5);
      density = get_non_negative(prm, subsection, "density");
      degree  = prm.get_integer("degree");
      law     = prm.get("material law") == "neo-Hookean" ?
                  Law::neo_hookean :
                  Law::saint_venant_kirchhoff;
    }


    template <int dim>
    std::string
    ContinuumSolid<dim>::law_name() const
    {
      return law == Law::neo_hookean ? "neo-Hookean" : "St. Venant-Kirchhoff";
    }


    template <int dim>
    dealii::Tensor<2, dim>
    ContinuumSolid<dim>::piola_stress(const dealii::Tensor<2, dim> &F,
                                      double                       &energy,
                                      dealii::Tensor<4, dim>       *A) const
    {
      const double lambda = lame_lambda();
      const double mu     = shear_modulus();
      const auto   I      = dealii::unit_symmetric_tensor<dim>();
      if (law == Law::saint_venant_kirchhoff)
        {
          const dealii::Tensor<2, dim> H = F - dealii::Tensor<2, dim>(I);
          const dealii::SymmetricTensor<2, dim> E =
            dealii::symmetrize(H) +
            0.5 * dealii::symmetrize(dealii::transpose(H) * H);
          const dealii::Tensor<2, dim> S = stress(E);
          energy                         = energy_density(E);
          if (A != nullptr)
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int J = 0; J < dim; ++J)
                for (unsigned int k = 0; k < dim; ++k)
                  for (unsigned int L = 0; L < dim; ++L)
                    {
                      // A_iJkL = d_ik S_JL + F_iM C_MJNL F_kN
                      double c = i == k ? S[J][L] : 0.;
                      for (unsigned int M = 0; M < dim; ++M)
                        for (unsigned int N = 0; N < dim; ++N)
                          c += F[i][M] * F[k][N] *
                               ((M == J && N == L ? lambda : 0.) +
                                mu * ((M == N && J == L ? 1. : 0.) +
                                      (M == L && J == N ? 1. : 0.)));
                      (*A)[i][J][k][L] = c;
                    }
          return F * S;
        }
      const double J = dealii::determinant(F);
      AssertThrow(J > 0. && std::isfinite(J),
                  dealii::ExcMessage(
                    "neo-Hookean solid: inverted quadrature point (det F = " +
                    std::to_string(J) +
                    " <= 0); reduce the time step or "
                    "refine the mesh."));
      const double                 lnJ   = std::log(J);
      const dealii::Tensor<2, dim> F_inv = dealii::invert(F);
      // tr(F^T F) - 3 with F_33 = 1 in plane strain: tr over dim - dim
      energy = 0.5 * mu * (dealii::scalar_product(F, F) - dim) - mu * lnJ +
               0.5 * lambda * lnJ * lnJ;
      if (A != nullptr)
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int L = 0; L < dim; ++L)
                (*A)[i][a][k][L] =
                  (i == k && a == L ? mu : 0.) +
                  (mu - lambda * lnJ) * F_inv[L][i] * F_inv[a][k] +
                  lambda * F_inv[a][i] * F_inv[L][k];
      return mu * F + (lambda * lnJ - mu) * dealii::transpose(F_inv);
    }


    template <int dim>
    double
    ContinuumSolid<dim>::lame_lambda() const
    {
      return youngs_modulus * poissons_ratio /
             ((1. + poissons_ratio) * (1. - 2. * poissons_ratio));
    }


    template <int dim>
    double
    ContinuumSolid<dim>::shear_modulus() const
    {
      return youngs_modulus / (2. * (1. + poissons_ratio));
    }


    template <int dim>
    dealii::SymmetricTensor<2, dim>
    ContinuumSolid<dim>::stress(const dealii::SymmetricTensor<2, dim> &E) const
    {
      return lame_lambda() * dealii::trace(E) *
               dealii::unit_symmetric_tensor<dim>() +
             2. * shear_modulus() * E;
    }


    template <int dim>
    double
    ContinuumSolid<dim>::energy_density(
      const dealii::SymmetricTensor<2, dim> &E) const
    {
      const double trE = dealii::trace(E);
      return 0.5 * lame_lambda() * trE * trE + shear_modulus() * (E * E);
    }


    namespace
    {
      /** Add the von Mises and mean stress of the Cauchy stress @p sigma
       * (sigma_33 = @p sigma_33 for dim = 2, plane strain) times @p JxW. */
      template <int dim>
      void
      add_stress_output(const dealii::Tensor<2, dim> &sigma,
                        const double                  sigma_33,
                        const double                  JxW,
                        double                       &von_mises,
                        double                       &mean)
      {
        dealii::SymmetricTensor<2, 3> sigma3;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            sigma3[a][b] = 0.5 * (sigma[a][b] + sigma[b][a]);
        if (dim == 2)
          sigma3[2][2] = sigma_33;
        const dealii::SymmetricTensor<2, 3> s = dealii::deviator(sigma3);
        von_mises += std::sqrt(1.5 * (s * s)) * JxW;
        mean += dealii::trace(sigma3) / 3. * JxW;
      }
    } // namespace


    template <int dim>
    void
    ContinuumSolid<dim>::neo_hookean_point(
      const dealii::Tensor<2, dim>              &F,
      const std::vector<dealii::Tensor<2, dim>> &grad_phi,
      const double                               JxW,
      dealii::Vector<double>                    &r,
      dealii::FullMatrix<double>                &K) const
    {
      const unsigned int n      = grad_phi.size();
      const double       lambda = lame_lambda();
      const double       mu     = shear_modulus();
      double             W      = 0.;
      const auto         P      = piola_stress(F, W);
      const double       lnJ    = std::log(dealii::determinant(F));
      const auto         F_iT   = dealii::transpose(dealii::invert(F));
      for (unsigned int j = 0; j < n; ++j)
        {
          const auto &G = grad_phi[j];
          // A : G = mu G + (mu - lambda ln J) F^-T G^T F^-T
          //         + lambda (F^-T : G) F^-T
          const dealii::Tensor<2, dim> AG =
            mu * G +
            (mu - lambda * lnJ) * (F_iT * dealii::transpose(G) * F_iT) +
            lambda * dealii::scalar_product(F_iT, G) * F_iT;
          r(j) += dealii::scalar_product(P, G) * JxW;
          for (unsigned int i = 0; i < n; ++i)
            K(i, j) += dealii::scalar_product(grad_phi[i], AG) * JxW;
        }
    }


    template <int dim>
    template <int spacedim>
    void
    ContinuumSolid<dim>::compute(
      const dealii::FEValues<dim, spacedim> &fe_values,
      const std::vector<double>             &u,
      dealii::Vector<double>                &r,
      dealii::FullMatrix<double>            &K,
      SolidCellOutput                       *output) const
    {
      const unsigned int n = fe_values.get_fe().n_dofs_per_cell();
      r.reinit(n);
      K.reinit(n, n);
      const dealii::FEValuesExtractors::Vector     displacement(0);
      const double                                 lambda = lame_lambda();
      const double                                 mu     = shear_modulus();
      std::vector<dealii::Tensor<2, dim>>          grad_phi(n);
      std::vector<dealii::SymmetricTensor<2, dim>> dE(n);
      std::vector<double>                          tr_dE(n);
      double energy = 0., volume = 0., von_mises = 0., mean = 0.;
      for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          // H = Grad u; E = (H + H^T + H^T H)/2 without forming F^T F - I
          // (which loses the digits of small strains).
          dealii::Tensor<2, dim> H;
          for (unsigned int i = 0; i < n; ++i)
            {
              // The in-plane block (all of it for spacedim = dim).
              const auto g = fe_values[displacement].gradient(i, q);
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  grad_phi[i][a][b] = g[a][b];
              H += u[i] * grad_phi[i];
            }
          const dealii::Tensor<2, dim> F =
            H + dealii::Tensor<2, dim>(dealii::unit_symmetric_tensor<dim>());
          if (law == Law::neo_hookean)
            {
              neo_hookean_point(F, grad_phi, fe_values.JxW(q), r, K);
              if (output != nullptr)
                {
                  double       W   = 0.;
                  const auto   P   = piola_stress(F, W);
                  const double J   = dealii::determinant(F);
                  const double JxW = fe_values.JxW(q);
                  energy += W * JxW;
                  volume += JxW;
                  add_stress_output(P * dealii::transpose(F) / J,
                                    lambda * std::log(J) / J,
                                    JxW,
                                    von_mises,
                                    mean);
                }
              continue;
            }
          const dealii::SymmetricTensor<2, dim> E =
            dealii::symmetrize(H) +
            0.5 * dealii::symmetrize(dealii::transpose(H) * H);
          const dealii::SymmetricTensor<2, dim> S   = stress(E);
          const dealii::Tensor<2, dim>          St  = S;
          const dealii::Tensor<2, dim>          P   = F * St;
          const double                          JxW = fe_values.JxW(q);
          for (unsigned int i = 0; i < n; ++i)
            {
              dE[i]    = dealii::symmetrize(dealii::transpose(F) * grad_phi[i]);
              tr_dE[i] = dealii::trace(dE[i]);
              r(i) += dealii::scalar_product(P, grad_phi[i]) * JxW;
            }
          for (unsigned int i = 0; i < n; ++i)
            {
              const dealii::Tensor<2, dim> grad_i_S = grad_phi[i] * St;
              for (unsigned int j = 0; j < n; ++j)
                K(i, j) +=
                  (lambda * tr_dE[i] * tr_dE[j] + 2. * mu * (dE[i] * dE[j]) +
                   dealii::scalar_product(grad_i_S, grad_phi[j])) *
                  JxW;
            }
          if (output != nullptr)
            {
              energy += energy_density(E) * JxW;
              volume += JxW;
              const double J = dealii::determinant(F);
              // Plane strain (dim = 2): F_33 = 1, sigma_33 = lambda tr E/J.
              add_stress_output(P * dealii::transpose(F) / J,
                                lambda * dealii::trace(E) / J,
                                JxW,
                                von_mises,
                                mean);
            }
        }
      if (output != nullptr)
        {
          output->strain_energy = energy;
          output->von_mises     = von_mises / volume;
          output->mean_stress   = mean / volume;
        }
    }


    void
    SolidGeometry::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("mesh file",
                        "",
                        dealii::Patterns::Anything(),
                        "Gmsh (.msh) file of hexahedra for the solid; empty: "
                        "the box 'lower corner' to 'upper corner' with "
                        "'subdivisions' cells, its faces x_min, x_max, y_min, "
                        "y_max, z_min, z_max with boundary ids 0 to 5.");
      prm.declare_entry("lower corner",
                        "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               3,
                                               3),
                        "Corner of the generated box with the smallest "
                        "coordinates [m].");
      prm.declare_entry("upper corner",
                        "1, 0.1, 0.1",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               3,
                                               3),
                        "Opposite corner of the generated box [m], larger in "
                        "every coordinate.");
      prm.declare_entry("subdivisions",
                        "10, 1, 1",
                        dealii::Patterns::List(dealii::Patterns::Integer(1),
                                               3,
                                               3),
                        "Cells of the generated box along x, y, z on level 0 "
                        "(doubled on every level of a convergence study) "
                        "[-].");
      prm.declare_entry("fixed boundary ids",
                        "",
                        dealii::Patterns::List(
                          dealii::Patterns::Integer(0, 255)),
                        "Boundary ids whose faces are clamped (every "
                        "component of every DoF on them fixed) [-].");
      prm.declare_entry("support boxes",
                        "",
                        dealii::Patterns::Anything(),
                        "Supports by position, separated by ';', each "
                        "'x0, y0, z0, x1, y1, z1, components': the listed "
                        "components (a word of x, y, z, e.g. 'xz') of every "
                        "DoF of the solid whose support point lies in the "
                        "box [x0, x1] x [y0, y1] x [z0, z1] are fixed "
                        "(coordinates in m; a flat box selects a plane, "
                        "e.g. a symmetry plane).");
      prm.declare_entry("traction boundary id",
                        "-1",
                        dealii::Patterns::Integer(-1, 255),
                        "Boundary id that carries 'traction'; -1: none [-].");
      prm.declare_entry("thickness",
                        "1",
                        dealii::Patterns::Double(),
                        "Out-of-plane thickness t of the plane-strain solid "
                        "of the 'plane solid', 'plane cantilever', 'plane "
                        "axial bar' and 'plane hanging block' models (a "
                        "Triangulation<2,2> in the x-y plane of a 2D "
                        "problem) [m], > 0: its forces, mass and reactions "
                        "are those of a slice of thickness t. These models "
                        "use the x and y coordinates of the corners and the "
                        "first two subdivisions (boundary ids 0 to 3 on "
                        "x_min, x_max, y_min, y_max); the z entries must "
                        "still form a valid box and are not used.");
      prm.declare_entry("traction",
                        "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               3,
                                               3),
                        "Dead surface load on the faces of 'traction boundary "
                        "id', per reference area, scaled by the load factor "
                        "[Pa].");
    }


    namespace
    {
      dealii::Point<3>
      get_point(dealii::ParameterHandler &prm, const std::string &entry)
      {
        const auto v = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(prm.get(entry)));
        return dealii::Point<3>(v[0], v[1], v[2]);
      }
    } // namespace


    void
    SolidGeometry::parse_parameters(dealii::ParameterHandler &prm,
                                    const std::string        &subsection)
    {
      mesh_file    = prm.get("mesh file");
      lower_corner = get_point(prm, "lower corner");
      upper_corner = get_point(prm, "upper corner");
      const auto s = dealii::Utilities::string_to_int(
        dealii::Utilities::split_string_list(prm.get("subdivisions")));
      subdivisions.assign(s.begin(), s.end());
      if (mesh_file.empty())
        for (unsigned int d = 0; d < 3; ++d)
          if (!(upper_corner[d] > lower_corner[d]))
            InputFile::reject(subsection,
                              "upper corner",
                              prm.get("upper corner"),
                              "the box needs upper corner > lower corner (" +
                                prm.get("lower corner") +
                                ") in every coordinate");
      fixed_boundary_ids.clear();
      for (const int id : dealii::Utilities::string_to_int(
             dealii::Utilities::split_string_list(
               prm.get("fixed boundary ids"))))
        fixed_boundary_ids.push_back(id);

      support_boxes.clear();
      const std::string boxes = prm.get("support boxes");
      for (const auto &text : dealii::Utilities::split_string_list(boxes, ';'))
        {
          if (text.empty())
            continue;
          const auto fields = dealii::Utilities::split_string_list(text, ',');
          SupportBox box;
          bool       ok = fields.size() == 7;
          try
            {
              for (unsigned int d = 0; ok && d < 3; ++d)
                {
                  box.lower[d] = std::stod(fields[d]);
                  box.upper[d] = std::stod(fields[3 + d]);
                  ok           = ok && box.upper[d] >= box.lower[d];
                }
            }
          catch (const std::exception &)
            {
              ok = false;
            }
          if (ok)
            {
              ok = !fields[6].empty();
              for (const char c : fields[6])
                if (c >= 'x' && c <= 'z')
                  box.components[c - 'x'] = true;
                else
                  ok = false;
            }
          if (!ok)
            InputFile::reject(subsection,
                              "support boxes",
                              boxes,
                              "each box separated by ';' must be 'x0, y0, z0, "
                              "x1, y1, z1, components' with x0 <= x1, y0 <= "
                              "y1, z0 <= z1 and components a word of x, y, z "
                              "(not <" +
                                text + ">)");
          support_boxes.push_back(box);
        }
      thickness            = get_positive(prm, subsection, "thickness");
      traction_boundary_id = prm.get_integer("traction boundary id");
      const auto t         = get_point(prm, "traction");
      for (unsigned int d = 0; d < 3; ++d)
        traction[d] = t[d];
    }


    void
    SolidGeometry::create_triangulation(dealii::Triangulation<3> &tria,
                                        const unsigned int        level,
                                        const std::string &subsection) const
    {
      if (!mesh_file.empty())
        {
          read_gmsh_mesh(tria, mesh_file, subsection, "mesh file", "hexahedra");
          return;
        }
      std::vector<unsigned int> n(3);
      for (unsigned int d = 0; d < 3; ++d)
        n[d] = subdivisions[d] << level;
      dealii::GridGenerator::subdivided_hyper_rectangle(
        tria, n, lower_corner, upper_corner, true);
    }


    void
    SolidGeometry::create_triangulation(dealii::Triangulation<2> &tria,
                                        const unsigned int        level,
                                        const std::string &subsection) const
    {
      if (!mesh_file.empty())
        InputFile::reject(subsection,
                          "mesh file",
                          mesh_file,
                          "the plane-strain solid of the 'plane' models is "
                          "the generated rectangle of 'lower corner', "
                          "'upper corner' and 'subdivisions' (x, y); leave "
                          "'mesh file' empty");
      std::vector<unsigned int> n(2);
      for (unsigned int d = 0; d < 2; ++d)
        n[d] = subdivisions[d] << level;
      dealii::GridGenerator::subdivided_hyper_rectangle(
        tria,
        n,
        dealii::Point<2>(lower_corner[0], lower_corner[1]),
        dealii::Point<2>(upper_corner[0], upper_corner[1]),
        true);
    }


    template class ContinuumSolid<2>;
    template class ContinuumSolid<3>;
    template void
    ContinuumSolid<2>::compute(const dealii::FEValues<2, 2> &,
                               const std::vector<double> &,
                               dealii::Vector<double> &,
                               dealii::FullMatrix<double> &,
                               SolidCellOutput *) const;
    template void
    ContinuumSolid<2>::compute(const dealii::FEValues<2, 3> &,
                               const std::vector<double> &,
                               dealii::Vector<double> &,
                               dealii::FullMatrix<double> &,
                               SolidCellOutput *) const;
    template void
    ContinuumSolid<3>::compute(const dealii::FEValues<3, 3> &,
                               const std::vector<double> &,
                               dealii::Vector<double> &,
                               dealii::FullMatrix<double> &,
                               SolidCellOutput *) const;
  } // namespace Structure
} // namespace Talus
