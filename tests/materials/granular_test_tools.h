// Helpers shared by the unit tests of the granular models (mohr_coulomb.cc,
// drucker_prager.cc): tensors, one material-point step, finite-difference
// tangent, deterministic pseudo-random numbers.

#ifndef talus_tests_granular_test_tools_h
#define talus_tests_granular_test_tools_h

#include <talus/base/input.h>
#include <talus/materials/constitutive_model.h>
#include <talus/materials/granular_plasticity.h>
#include <talus/materials/hencky_elastic.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace GranularTest
{
  using dealii::Tensor;
  using Talus::Materials::ConstitutiveModel;

  inline Tensor<2, 3>
  unit_tensor()
  {
    Tensor<2, 3> I;
    for (unsigned int i = 0; i < 3; ++i)
      I[i][i] = 1.;
    return I;
  }

  inline Tensor<2, 3>
  diagonal(const double a, const double b, const double c)
  {
    Tensor<2, 3> D;
    D[0][0] = a;
    D[1][1] = b;
    D[2][2] = c;
    return D;
  }

  // F = diag(exp(eps_a)): principal logarithmic strains eps
  inline Tensor<2, 3>
  stretch(const double e0, const double e1, const double e2)
  {
    return diagonal(std::exp(e0), std::exp(e1), std::exp(e2));
  }

  inline Tensor<1, 3>
  vector(const double x, const double y, const double z)
  {
    Tensor<1, 3> v;
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
  }

  // Rotation by angle about the (normalized) axis (Rodrigues' formula).
  inline Tensor<2, 3>
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

  template <int rank>
  double
  max_abs(const Tensor<rank, 3> &T)
  {
    double m = 0.;
    for (unsigned int i = 0; i < Tensor<rank, 3>::n_independent_components; ++i)
      m = std::max(m, std::abs(T[T.unrolled_to_component_indices(i)]));
    return m;
  }

  // A material point: accepted history and the deformation gradient
  struct MaterialPoint
  {
    std::vector<double> history;
    Tensor<2, 3>        F;

    explicit MaterialPoint(const ConstitutiveModel &model)
      : history(model.n_history_variables())
      , F(unit_tensor())
    {
      model.initialize_history(dealii::make_array_view(history));
    }
  };

  // One trial evaluation from the accepted state of p (p is not changed)
  struct Step
  {
    Tensor<2, 3>        P;
    Tensor<4, 3>        A;
    std::vector<double> history;
  };

  inline Step
  evaluate(const ConstitutiveModel &model,
           const MaterialPoint     &p,
           const Tensor<2, 3>      &F,
           const bool               tangent   = true,
           const double             time_step = 0.)
  {
    Step s;
    s.history.resize(p.history.size());
    model.compute_stress(p.F,
                         F,
                         dealii::make_array_view(p.history),
                         dealii::make_array_view(s.history),
                         time_step,
                         s.P,
                         tangent ? &s.A : nullptr);
    return s;
  }

  // Accept the step to F (of length time_step [s]; 0: no rate).
  inline Step
  advance(const ConstitutiveModel &model,
          MaterialPoint           &p,
          const Tensor<2, 3>      &F,
          const double             time_step = 0.)
  {
    const Step s = evaluate(model, p, F, true, time_step);
    p.history    = s.history;
    p.F          = F;
    return s;
  }

  // Principal Kirchhoff stresses tau = P F^T, sorted largest first
  inline Tensor<1, 3>
  principal_kirchhoff(const Tensor<2, 3> &P, const Tensor<2, 3> &F)
  {
    const Tensor<2, 3> tau = P * dealii::transpose(F);
    Tensor<2, 3>       sym = 0.5 * (tau + dealii::transpose(tau));
    const auto         sd =
      Talus::Materials::LogarithmicStrain::spectral_decomposition(sym);
    std::vector<double> v(sd.eigenvalues.begin(), sd.eigenvalues.end());
    std::sort(v.begin(), v.end(), std::greater<double>());
    return vector(v[0], v[1], v[2]);
  }

  // max |A - A_fd| / max |A| with central differences of P
  inline double
  tangent_error(const ConstitutiveModel &model,
                const MaterialPoint     &p,
                const Tensor<2, 3>      &F,
                const double             relative_step = 1e-7,
                const double             time_step     = 0.)
  {
    const Tensor<4, 3> A = evaluate(model, p, F, true, time_step).A;
    const double       h = relative_step * std::max(1., max_abs(F));
    Tensor<4, 3>       A_fd;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          Tensor<2, 3> F_plus = F, F_minus = F;
          F_plus[k][L] += h;
          F_minus[k][L] -= h;
          const Tensor<2, 3> dP =
            (evaluate(model, p, F_plus, false, time_step).P -
             evaluate(model, p, F_minus, false, time_step).P) /
            (2. * h);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int J = 0; J < 3; ++J)
              A_fd[i][J][k][L] = dP[i][J];
        }
    const double scale = max_abs(A);
    return scale > 0. ? max_abs(Tensor<4, 3>(A - A_fd)) / scale : max_abs(A_fd);
  }

  // Deterministic pseudo-random numbers in [-1, 1] (same on every platform)
  class Random
  {
  public:
    double
    operator()()
    {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) / 4503599627370496. - 1.;
    }

  private:
    std::uint64_t state = 12345;
  };

  // Steady pure shear at the principal logarithmic strain rates (r, 0, -r)
  // after an isotropic compression e0 (P = 3 K e0, kept by an isochoric
  // flow), 400 steps of 2e-5 each: the principal Kirchhoff stresses of the
  // last step, its plastic shear rate sqrt(3) d eps_p/dt (2 r at steady
  // flow) and its return type.
  struct SteadyShear
  {
    Tensor<1, 3> tau;
    double       plastic_shear_rate;
    double       return_type;
  };

  inline SteadyShear
  steady_pure_shear(const ConstitutiveModel &model,
                    const double             e0,
                    const double             rate)
  {
    const double  delta = 2e-5;
    const double  dt    = delta / rate;
    MaterialPoint p(model);
    advance(model, p, stretch(-e0, -e0, -e0), 1.);
    Step   st;
    double eps_p_before = 0., shear = 0.;
    for (unsigned int n = 0; n < 400; ++n)
      {
        eps_p_before = p.history[6];
        shear += delta;
        st = advance(model, p, stretch(-e0 + shear, -e0, -e0 - shear), dt);
      }
    return {principal_kirchhoff(st.P, p.F),
            std::sqrt(3.) * (p.history[6] - eps_p_before) / dt,
            st.history[8]};
  }

  // max |P - P_static| / max |P_static| for one step from the virgin state
  // to F of length time_step: how far a rate-dependent model is from its
  // static counterpart
  inline double
  static_stress_difference(const ConstitutiveModel &model,
                           const ConstitutiveModel &static_model,
                           const Tensor<2, 3>      &F,
                           const double             time_step)
  {
    const MaterialPoint p(model), q(static_model);
    const Tensor<2, 3>  P_static = evaluate(static_model, q, F).P;
    return max_abs(Tensor<2, 3>(evaluate(model, p, F, true, time_step).P -
                                P_static)) /
           max_abs(P_static);
  }

  // Create the model of the parameter text @p input (subsection Material):
  // prints "rejected" to out, followed by " (<note>)" if the message contains
  // @p needle, or "FAILED, accepted" if the model was created.
  inline void
  report_rejection(std::ostream      &out,
                   const std::string &input,
                   const std::string &needle,
                   const std::string &note)
  {
    dealii::ParameterHandler prm;
    Talus::Materials::declare_parameters(prm);
    prm.parse_input_from_string(input);
    try
      {
        Talus::Materials::create_model(prm);
        out << "FAILED, accepted" << std::endl;
      }
    catch (const Talus::ExcInvalidInput &e)
      {
        const std::string what = e.what();
        out << "rejected"
            << (what.find(needle) != std::string::npos ? " (" + note + ")" :
                                                         std::string())
            << std::endl;
      }
  }

  // prints "what: ok" to out (the number to the screen only)
  inline void
  report(std::ostream      &out,
         const std::string &what,
         const double       error,
         const double       tolerance)
  {
    std::cout << what << ": " << error << std::endl;
    out << what << ": ";
    if (error < tolerance)
      out << "ok" << std::endl;
    else
      out << "FAILED, error " << std::scientific << std::setprecision(3)
          << error << std::defaultfloat << std::endl;
  }

  inline std::string
  return_type_name(const double t)
  {
    switch (static_cast<int>(std::lround(t)))
      {
        case 0:
          return "elastic";
        case 1:
          return "plane/cone";
        case 2:
          return "edge";
        case 3:
          return "apex";
        case 4:
          return "tension cut-off";
        default:
          return "?";
      }
  }

  // The path of the element test "separated volume" (c = 0): stretch
  // 5 % x 5 %, partly close, shear while open, close, compress 1 %; make(r)
  // returns the model with recoverable_separation = r. With 'recoverable'
  // the final stress must equal that of a fresh point.
  template <class MakeModel>
  void
  recoverable_separation_path(std::ostream &out, const MakeModel &make)
  {
    out << std::endl
        << "(j) separated volume: plastic (default) and recoverable, c = 0"
        << std::endl;
    for (const bool recoverable : {false, true})
      {
        const auto    model = make(recoverable);
        MaterialPoint p(model);
        out << (recoverable ? "recoverable" : "plastic") << ":" << std::endl;
        for (const auto &[name, F] :
             std::vector<std::pair<std::string, Tensor<2, 3>>>{
               {"stretch 5 % x 5 %", diagonal(1.05, 1.05, 1.)},
               {"back to 2 % x 2 %", diagonal(1.02, 1.02, 1.)},
               {"shear while open",
                Tensor<2, 3>(diagonal(1.02, 1.02, 1.) +
                             0.01 * outer_product(vector(1., 0., 0.),
                                                  vector(0., 1., 0.)))},
               {"back to F = I", unit_tensor()},
               {"compress 1 %", diagonal(0.99, 1., 1.)}})
          {
            const Step st = advance(model, p, F);
            // reference: the same F from the stress-free initial state
            const Step   ref = evaluate(model, MaterialPoint(model), F);
            const double J   = dealii::determinant(F);
            out
              << "  " << name << " (J = " << std::setprecision(6) << J
              << "): return type " << return_type_name(st.history[8])
              << ", open volumetric strain " << std::setprecision(6)
              << (std::abs(st.history[Talus::Materials::GranularPlasticity::
                                        open_strain_index]) < 1e-14 ?
                    0. :
                    st.history
                      [Talus::Materials::GranularPlasticity::open_strain_index])
              << ", max |P| = " << std::setprecision(4)
              << (max_abs(st.P) < 1e-6 ? 0. : max_abs(st.P))
              << " Pa, stored energy "
              << (model.energy_density(F, dealii::make_array_view(st.history)) <
                      1e-9 ?
                    0. :
                    model.energy_density(F,
                                         dealii::make_array_view(st.history)))
              << " J/m^3";
            if (name == "compress 1 %")
              out << ", |P - P(fresh point)| / |P(fresh point)| "
                  << (max_abs(Tensor<2, 3>(st.P - ref.P)) <=
                          1e-9 * max_abs(ref.P) ?
                        "< 1e-9" :
                        "> 1e-9");
            out << std::endl;
          }
        report(out,
               "  tangent while open",
               tangent_error(model, p, diagonal(1.03, 1.03, 1.)),
               1e-6);
      }
  }
} // namespace GranularTest

#endif
