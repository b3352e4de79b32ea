// Unit test of the elastic constitutive models (LinearElastic, NeoHookean,
// HenckyElastic):
//  - creation from a ParameterHandler and rejection of invalid input,
//  - zero stress and energy at F = I,
//  - uniaxial strain F = diag(s, 1, 1) against the closed-form stresses,
//  - the analytic tangent A = dP/dF against central finite differences of
//    P, at F = I, at a general F (rotation and shear) and at deformation
//    gradients with repeated principal stretches,
//  - major symmetry of A and, at F = I, A = linear elasticity tensor,
//  - objectivity P(QF) = Q P(F) of the finite-strain models,
//  - P = d(energy_density)/dF by finite differences,
//  - ExcInvertedMaterialPoint for det F <= 0.
// Numbers that depend on round-off are only printed as "ok"/not ok.

#include <talus/base/input.h>
#include <talus/materials/constitutive_model.h>
#include <talus/materials/exceptions.h>
#include <talus/materials/hencky_elastic.h>
#include <talus/materials/linear_elastic.h>
#include <talus/materials/neo_hookean.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace dealii;
using namespace Talus;
using namespace Talus::Materials;

namespace
{
  std::ofstream out("output");

  const double E_test  = 1e7;
  const double nu_test = 0.25; // lambda = mu = 4e6 Pa


  Tensor<2, 3>
  unit_tensor()
  {
    Tensor<2, 3> I;
    for (unsigned int i = 0; i < 3; ++i)
      I[i][i] = 1.;
    return I;
  }


  Tensor<2, 3>
  diagonal(const double a, const double b, const double c)
  {
    Tensor<2, 3> D;
    D[0][0] = a;
    D[1][1] = b;
    D[2][2] = c;
    return D;
  }


  // Rotation by angle about the (normalized) axis (Rodrigues' formula).
  Tensor<2, 3>
  rotation(Tensor<1, 3> axis, const double angle)
  {
    axis /= axis.norm();
    Tensor<2, 3> K;
    K[0][1] = -axis[2];
    K[0][2] = axis[1];
    K[1][0] = axis[2];
    K[1][2] = -axis[0];
    K[2][0] = -axis[1];
    K[2][1] = axis[0];
    return unit_tensor() + std::sin(angle) * K + (1. - std::cos(angle)) * K * K;
  }


  Tensor<1, 3>
  vector(const double x, const double y, const double z)
  {
    Tensor<1, 3> v;
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
  }


  template <int rank>
  double
  max_abs(const Tensor<rank, 3> &T)
  {
    double m = 0.;
    for (unsigned int i = 0; i < Tensor<rank, 3>::n_independent_components; ++i)
      m = std::max(m, std::abs(T[T.unrolled_to_component_indices(i)]));
    return m;
  }


  Tensor<2, 3>
  stress(const ConstitutiveModel &model,
         const Tensor<2, 3>      &F,
         Tensor<4, 3>            *A = nullptr)
  {
    std::vector<double> history_old(model.n_history_variables());
    std::vector<double> history_new(model.n_history_variables());
    model.initialize_history(make_array_view(history_old));
    Tensor<2, 3> P;
    model.compute_stress(unit_tensor(),
                         F,
                         make_array_view(std::as_const(history_old)),
                         make_array_view(history_new),
                         0.,
                         P,
                         A);
    return P;
  }


  double
  energy(const ConstitutiveModel &model, const Tensor<2, 3> &F)
  {
    std::vector<double> history(model.n_history_variables());
    model.initialize_history(make_array_view(history));
    return model.energy_density(F, make_array_view(std::as_const(history)));
  }


  void
  report(const std::string &what,
         const double       relative_error,
         const double       tolerance)
  {
    // the actual numbers go to the screen only (they depend on round-off)
    std::cout << what << ": " << relative_error << std::endl;
    out << what << ": ";
    if (relative_error < tolerance)
      out << "ok" << std::endl;
    else
      out << "FAILED, relative error " << std::scientific
          << std::setprecision(3) << relative_error << std::defaultfloat
          << std::endl;
  }


  // max |A - A_fd| / max |A|, A_fd by central differences of P with step
  // 1e-6 relative to the size of F.
  double
  tangent_error(const ConstitutiveModel &model, const Tensor<2, 3> &F)
  {
    Tensor<4, 3> A;
    stress(model, F, &A);
    const double h = 1e-6 * std::max(1., max_abs(F));
    Tensor<4, 3> A_fd;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          Tensor<2, 3> F_plus = F, F_minus = F;
          F_plus[k][L] += h;
          F_minus[k][L] -= h;
          const Tensor<2, 3> dP =
            (stress(model, F_plus) - stress(model, F_minus)) / (2. * h);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int J = 0; J < 3; ++J)
              A_fd[i][J][k][L] = dP[i][J];
        }
    return max_abs(Tensor<4, 3>(A - A_fd)) / max_abs(A);
  }


  // max |A_iJkL - A_kLiJ| / max |A|
  double
  asymmetry(const ConstitutiveModel &model, const Tensor<2, 3> &F)
  {
    Tensor<4, 3> A;
    stress(model, F, &A);
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            m = std::max(m, std::abs(A[i][J][k][L] - A[k][L][i][J]));
    return m / max_abs(A);
  }


  // max |P - d psi/dF| / max |P| by central differences of the energy
  double
  energy_error(const ConstitutiveModel &model, const Tensor<2, 3> &F)
  {
    const Tensor<2, 3> P = stress(model, F);
    const double       h = 1e-6 * std::max(1., max_abs(F));
    Tensor<2, 3>       P_fd;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          Tensor<2, 3> F_plus = F, F_minus = F;
          F_plus[k][L] += h;
          F_minus[k][L] -= h;
          P_fd[k][L] =
            (energy(model, F_plus) - energy(model, F_minus)) / (2. * h);
        }
    return max_abs(Tensor<2, 3>(P - P_fd)) / max_abs(P);
  }


  struct TestCase
  {
    std::string  name;
    Tensor<2, 3> F;
  };


  std::vector<TestCase>
  test_cases()
  {
    const Tensor<2, 3> Q = rotation(vector(1., 2., -0.5), 0.7);
    Tensor<2, 3>       M; // stretch and shear
    M[0][0] = 1.2;
    M[0][1] = 0.15;
    M[0][2] = -0.05;
    M[1][0] = 0.1;
    M[1][1] = 0.9;
    M[1][2] = 0.08;
    M[2][0] = 0.02;
    M[2][1] = -0.03;
    M[2][2] = 1.1;

    Tensor<2, 3> M_compression = 0.8 * M; // J < 1
    M_compression[0][0]        = 0.7;

    Tensor<2, 3> plane_strain; // F(2,2) = 1, no out-of-plane shear
    plane_strain[0][0] = 1.1;
    plane_strain[0][1] = 0.2;
    plane_strain[1][0] = -0.1;
    plane_strain[1][1] = 0.95;
    plane_strain[2][2] = 1.;

    const Tensor<2, 3> Q_z = rotation(vector(0., 0., 1.), 0.4);

    std::vector<TestCase> cases;
    cases.push_back({"F=I", unit_tensor()});
    cases.push_back({"general", Tensor<2, 3>(Q * M)});
    cases.push_back({"general compression", Tensor<2, 3>(Q * M_compression)});
    cases.push_back({"plane strain", plane_strain});
    cases.push_back({"plane strain equal stretches",
                     Tensor<2, 3>(Q_z * diagonal(1.15, 1.15, 1.))});
    cases.push_back({"uniaxial strain", diagonal(1.2, 1., 1.)});
    cases.push_back({"rotated dilation", Tensor<2, 3>(1.1 * Q)});
    cases.push_back({"nearly equal stretches",
                     Tensor<2, 3>(Q * diagonal(1.2, 1.2 + 1e-9, 0.9))});
    return cases;
  }


  std::unique_ptr<ConstitutiveModel>
  create(ParameterHandler &prm, const std::string &model_name)
  {
    prm.parse_input_from_string("subsection Material\n"
                                "  set model = " +
                                model_name +
                                "\n"
                                "  set Young's modulus = 1e7\n"
                                "  set Poisson's ratio = 0.25\n"
                                "end\n");
    return create_model(prm);
  }


  void
  check_invalid_input(ParameterHandler  &prm,
                      const std::string &entry,
                      const std::string &value)
  {
    prm.parse_input_from_string("subsection Material\n"
                                "  set model = Hencky\n"
                                "  set Young's modulus = 1e7\n"
                                "  set Poisson's ratio = 0.25\n"
                                "  set " +
                                entry + " = " + value +
                                "\n"
                                "end\n");
    out << "invalid input " << entry << " = " << value << ": ";
    try
      {
        create_model(prm);
        out << "FAILED, accepted" << std::endl;
      }
    catch (const ExcInvalidInput &)
      {
        out << "rejected" << std::endl;
      }
    // create_model must have left subsection "Material" also on error
    prm.enter_subsection("Material");
    prm.get("model");
    prm.leave_subsection();
  }


  void
  check_inverted(const ConstitutiveModel &model)
  {
    for (const Tensor<2, 3> &F : {diagonal(-1., 1., 1.), diagonal(1., 0., 1.)})
      {
        out << "inverted point " << model.name()
            << " det F = " << determinant(F) << ": ";
        try
          {
            Tensor<4, 3> A;
            stress(model, F, &A);
            out << "FAILED, no exception" << std::endl;
          }
        catch (const ExcInvertedMaterialPoint &e)
          {
            out << "ExcInvertedMaterialPoint";
            try
              {
                energy(model, F);
                out << ", energy FAILED, no exception" << std::endl;
              }
            catch (const ExcInvertedMaterialPoint &)
              {
                out << " (also from energy_density)" << std::endl;
              }
          }
      }
  }


  // closed-form uniaxial-strain stresses P11, P22 = P33 for F = diag(s,1,1)
  std::pair<double, double>
  uniaxial_closed_form(const std::string &model, const double s)
  {
    const double lambda =
      E_test * nu_test / ((1 + nu_test) * (1 - 2 * nu_test));
    const double mu = E_test / (2 * (1 + nu_test));
    if (model == "linear elastic")
      return {(lambda + 2 * mu) * (s - 1), lambda * (s - 1)};
    if (model == "neo-Hookean")
      return {mu * (s - 1 / s) + lambda * std::log(s) / s,
              lambda * std::log(s)};
    // Hencky: tau11 = (lambda + 2 mu) ln s, tau22 = lambda ln s, P = tau F^-T
    return {(lambda + 2 * mu) * std::log(s) / s, lambda * std::log(s)};
  }
} // namespace



int
main()
{
  out << std::setprecision(10);

  ParameterHandler prm;
  declare_parameters(prm);
  out << "model names: " << model_names() << std::endl;

  for (const auto &[entry, value] :
       std::vector<std::pair<std::string, std::string>>{
         {"Young's modulus", "0"},
         {"Young's modulus", "-1e6"},
         {"Poisson's ratio", "0.5"},
         {"Poisson's ratio", "-1"}})
    check_invalid_input(prm, entry, value);

  const LinearElastic linear_reference(E_test, nu_test);
  Tensor<4, 3>        A_linear;
  stress(linear_reference, unit_tensor(), &A_linear);

  for (const std::string model_name :
       {"linear elastic", "neo-Hookean", "Hencky"})
    {
      const std::unique_ptr<ConstitutiveModel> model = create(prm, model_name);
      const ConstitutiveModel                 &m     = *model;
      out << std::endl
          << "model " << m.name() << ": history variables "
          << m.n_history_variables() << ", P-wave modulus "
          << m.p_wave_modulus() << " Pa" << std::endl;

      // (a) zero stress and energy at F = I
      {
        Tensor<4, 3>       A;
        const Tensor<2, 3> P = stress(m, unit_tensor(), &A);
        report("zero stress at F=I " + m.name(), max_abs(P) / E_test, 1e-12);
        report("zero energy at F=I " + m.name(),
               std::abs(energy(m, unit_tensor())) / E_test,
               1e-12);
        report("tangent at F=I equals linear elasticity " + m.name(),
               max_abs(Tensor<4, 3>(A - A_linear)) / max_abs(A_linear),
               1e-12);
      }

      // (b) uniaxial strain
      for (const double s : {1.2, 0.8})
        {
          const Tensor<2, 3> P           = stress(m, diagonal(s, 1., 1.));
          const auto         closed_form = uniaxial_closed_form(m.name(), s);
          out << "uniaxial strain " << m.name() << " stretch " << s
              << ": P11 = " << std::setprecision(8) << P[0][0]
              << " Pa, P22 = " << P[1][1] << " Pa, P33 = " << P[2][2] << " Pa"
              << std::endl;
          out << "  closed form: P11 = " << closed_form.first
              << " Pa, P22 = P33 = " << closed_form.second << " Pa"
              << std::setprecision(10) << std::endl;
          const double error = std::max({std::abs(P[0][0] - closed_form.first),
                                         std::abs(P[1][1] - closed_form.second),
                                         std::abs(P[2][2] - closed_form.second),
                                         std::abs(P[0][1]),
                                         std::abs(P[0][2]),
                                         std::abs(P[1][2]),
                                         std::abs(P[1][0]),
                                         std::abs(P[2][0]),
                                         std::abs(P[2][1])}) /
                               std::abs(closed_form.first);
          report("  uniaxial strain " + m.name(), error, 1e-12);
        }

      // (c) tangent against finite differences, and its major symmetry
      for (const TestCase &c : test_cases())
        {
          report("tangent check " + m.name() + " " + c.name,
                 tangent_error(m, c.F),
                 1e-6);
          report("major symmetry " + m.name() + " " + c.name,
                 asymmetry(m, c.F),
                 1e-10);
        }

      // (d) objectivity
      {
        const Tensor<2, 3> Q = rotation(vector(-0.3, 1., 0.6), 1.1);
        for (const TestCase &c : test_cases())
          {
            if (c.name == "F=I")
              continue;
            const Tensor<2, 3> P    = stress(m, c.F);
            const Tensor<2, 3> P_QF = stress(m, Tensor<2, 3>(Q * c.F));
            const double       error =
              max_abs(Tensor<2, 3>(P_QF - Q * P)) / max_abs(P);
            if (m.name() == "linear elastic")
              out << "objectivity " << m.name() << " " << c.name << ": "
                  << (error > 1e-2 ? "not objective (as documented)" :
                                     "UNEXPECTED")
                  << std::endl;
            else
              report("objectivity " + m.name() + " " + c.name, error, 1e-10);
          }
      }

      // (e) P = d psi / dF
      for (const TestCase &c : test_cases())
        if (c.name != "F=I")
          report("energy derivative " + m.name() + " " + c.name,
                 energy_error(m, c.F),
                 1e-6);

      if (m.name() != "linear elastic")
        check_inverted(m);
    }

  // Consistency of the three models for small strains
  {
    Tensor<2, 3> F = unit_tensor();
    F[0][0] += 1e-7;
    F[0][1] += 2e-7;
    F[2][1] -= 1e-7;
    const Tensor<2, 3> P_linear = stress(linear_reference, F);
    report("small strain: neo-Hookean = linear elastic",
           max_abs(
             Tensor<2, 3>(stress(NeoHookean(E_test, nu_test), F) - P_linear)) /
             max_abs(P_linear),
           1e-5);
    report("small strain: Hencky = linear elastic",
           max_abs(Tensor<2, 3>(stress(HenckyElastic(E_test, nu_test), F) -
                                P_linear)) /
             max_abs(P_linear),
           1e-5);
  }

  out << std::endl << "done" << std::endl;
  return 0;
}
