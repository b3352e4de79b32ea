// Unit test of the finite-strain Mohr-Coulomb model (element tests of
// VERIFICATION.md 2.1), driving the deformation gradient of one material
// point directly. Stresses are Kirchhoff stresses, tension positive; in the
// printed formulas sigma_I >= sigma_III are the major and minor principal
// stresses in compression (sigma_I = -tau_3, sigma_III = -tau_1).
//  - creation from parameters, description(), rejection of invalid input
//  - (a) yield onset at the analytic Mohr-Coulomb stress: triaxial
//        compression, triaxial extension, uniaxial compression, simple shear
//  - (b) after every return the stress is on the yield surface (random
//        states, with and without tension cut-off and softening)
//  - (c) consistent tangent vs central differences of P per return type;
//        in plane strain, the in-plane block (set_tangent_dimension(2))
//        equals that block of the checked tangent and the rest is zero
//  - (d) cohesionless material: F = I and tensile states
//  - (e) softening to the residual strength
//  - (f) isochoric plastic flow for psi = 0, dilatancy for psi > 0
//  - (h) objectivity, energy density of the elastic strain
//  - (i) ExcReturnMappingFailed when the local problem has no solution
//  - (j) major symmetry of the tangent for associative flow only
//  - (k) rate-dependent friction mu(I): steady pure shear at constant rate
//        against the closed form, the static limits, tangents, bad input
// Numbers that depend on round-off are printed as "ok" only.

#include <talus/materials/exceptions.h>
#include <talus/materials/mohr_coulomb.h>

#include "granular_test_tools.h"

using namespace dealii;
using namespace Talus;
using namespace Talus::Materials;
using namespace GranularTest;

namespace
{
  std::ofstream out("output");

  const double E   = 1e7;
  const double nu  = 0.25; // lambda = mu = 4e6 Pa
  const double deg = M_PI / 180.;

  GranularStrength
  strength(const double phi,
           const double c,
           const double psi,
           const double t         = 1e30,
           const double phi_r     = -1,
           const double c_r       = -1,
           const double psi_r     = -1,
           const double softening = 0.02)
  {
    return {phi * deg,
            c,
            psi * deg,
            (phi_r < 0 ? phi : phi_r) * deg,
            (c_r < 0 ? c : c_r),
            (psi_r < 0 ? psi : psi_r) * deg,
            softening,
            t};
  }

  double
  N_phi(const double phi)
  {
    return (1. + std::sin(phi)) / (1. - std::sin(phi));
  }


  void
  check_input()
  {
    ParameterHandler prm;
    declare_parameters(prm);
    const std::string head = "subsection Material\n"
                             "  set model = Mohr-Coulomb\n"
                             "  set Young's modulus = 1e7\n"
                             "  set Poisson's ratio = 0.25\n"
                             "  subsection Mohr-Coulomb\n";
    prm.parse_input_from_string(head + "    set friction angle = 19.8\n"
                                       "    set cohesion = 0\n"
                                       "    set dilatancy angle = 0\n"
                                       "  end\n"
                                       "end\n");
    const auto model = create_model(prm);
    out << "created: " << model->description() << std::endl;
    out << "history:";
    for (const auto &n : model->history_names())
      out << ' ' << n;
    out << std::endl;

    for (const std::string bad : {"set friction angle = 0",
                                  "set friction angle = 90",
                                  "set dilatancy angle = -1",
                                  "set dilatancy angle = 31",
                                  "set cohesion = -1",
                                  "set tension cut-off = -1",
                                  "set residual friction angle = 31",
                                  "set residual cohesion = 2",
                                  "set residual dilatancy angle = 11",
                                  "set residual cohesion = soft",
                                  "set softening plastic strain = 0"})
      {
        out << "invalid input <" << bad << ">: ";
        report_rejection(out,
                         head +
                           "    set friction angle = 30\n"
                           "    set cohesion = 1\n"
                           "    set dilatancy angle = 10\n"
                           "    set residual cohesion = 0.5\n    " +
                           bad + "\n  end\nend\n",
                         "Material/Mohr-Coulomb",
                         "names Material/Mohr-Coulomb");
      }
  }


  // smallest s with a plastic return from the stress-free state, by
  // bisection (the model is rate independent: one step from F = I)
  template <class Path>
  double
  yield_onset(const MohrCoulomb &model, const Path &F_of_s)
  {
    const MaterialPoint p(model);
    double              lo = 0., hi = 1e-4;
    while (evaluate(model, p, F_of_s(hi), false).history[8] == 0.)
      {
        hi *= 2.;
        AssertThrow(hi < 1., ExcMessage("no yield on this path"));
      }
    for (unsigned int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        if (evaluate(model, p, F_of_s(mid), false).history[8] == 0.)
          lo = mid;
        else
          hi = mid;
      }
    return lo;
  }


  void
  check_yield_onset()
  {
    out << std::endl << "(a) yield onset" << std::endl;
    const double      phi = 30., c = 1e4;
    const MohrCoulomb model(IsotropicElasticity(E, nu), strength(phi, c, 10.));
    const double      Nphi = N_phi(phi * deg);
    out << "phi = 30 deg, c = 1e4 Pa, psi = 10 deg, N_phi = " << Nphi
        << std::endl;
    const Tensor<2, 3>        Q = rotation(vector(1., -2., 0.5), 0.6);
    const IsotropicElasticity el(E, nu);

    // proportional paths in principal logarithmic strain, rotated by Q
    const std::vector<std::pair<std::string, Tensor<1, 3>>> paths = {
      {"triaxial compression (tau_1 = tau_2)", vector(0.1, 0.1, -1.)},
      {"triaxial extension (tau_2 = tau_3)", vector(0.3, -0.5, -0.5)},
      {"uniaxial compression (tau_1 = tau_2 = 0)", vector(nu, nu, -1.)}};
    for (const auto &[name, d] : paths)
      {
        const auto F_of_s = [&, d = d](const double s) {
          return Tensor<2, 3>(Q * stretch(s * d[0], s * d[1], s * d[2]));
        };
        // analytic: tau = s D d, f linear in s
        Tensor<1, 3> tau1;
        for (unsigned int a = 0; a < 3; ++a)
          tau1[a] = el.lambda * (d[0] + d[1] + d[2]) + 2. * el.mu * d[a];
        const double f1 =
          (tau1[0] - tau1[2]) + (tau1[0] + tau1[2]) * std::sin(phi * deg);
        const double       s_analytic = 2. * c * std::cos(phi * deg) / f1;
        const double       s_y        = yield_onset(model, F_of_s);
        const Tensor<1, 3> tau        = principal_kirchhoff(
          evaluate(model, MaterialPoint(model), F_of_s(s_y)).P, F_of_s(s_y));
        const double sigma_I = -tau[2], sigma_III = -tau[0];
        const double mc = sigma_III * Nphi + 2. * c * std::sqrt(Nphi);
        out << name << ": onset at log strain s = " << std::setprecision(6)
            << s_y << " (analytic " << s_analytic << "), sigma_I = " << sigma_I
            << " Pa, sigma_III N_phi + 2c sqrt(N_phi) = " << mc << " Pa"
            << std::setprecision(10) << std::endl;
        if (name.find("uniaxial") != std::string::npos)
          out << "  uniaxial compressive strength 2c sqrt(N_phi) = "
              << std::setprecision(6) << 2. * c * std::sqrt(Nphi)
              << " Pa, sigma_III "
              << (std::abs(sigma_III) < 1e-8 * c ? "= 0" : "NOT 0")
              << std::setprecision(10) << std::endl;
        report(out, "  onset strain", std::abs(s_y / s_analytic - 1.), 1e-10);
        report(out, "  onset stress", std::abs(sigma_I - mc) / c, 1e-8);
      }

    // simple shear (plane strain): principal log strains +-ln(l),
    // l = g/2 + sqrt(1 + g^2/4), tau_1 = -tau_3 = 2 mu ln(l), tau_2 = 0;
    // yield at tau_1 = c cos(phi): g = 2 sinh(c cos(phi)/(2 mu))
    {
      const auto F_of_g = [](const double g) {
        Tensor<2, 3> F = unit_tensor();
        F[0][1]        = g;
        return F;
      };
      const double g_y = yield_onset(model, F_of_g);
      const double g_analytic =
        2. * std::sinh(c * std::cos(phi * deg) / (2. * el.mu));
      const Tensor<1, 3> tau = principal_kirchhoff(
        evaluate(model, MaterialPoint(model), F_of_g(g_y)).P, F_of_g(g_y));
      const double sigma_I = -tau[2], sigma_III = -tau[0];
      const double mc = sigma_III * Nphi + 2. * c * std::sqrt(Nphi);
      out << "simple shear: onset at gamma = " << std::setprecision(6) << g_y
          << " (analytic " << g_analytic << "), sigma_I = " << sigma_I
          << " Pa, sigma_III N_phi + 2c sqrt(N_phi) = " << mc
          << " Pa, tau_1 = max. shear stress = " << tau[0]
          << " Pa (analytic c cos(phi) = " << c * std::cos(phi * deg) << ")"
          << std::setprecision(10) << std::endl;
      report(out, "  onset strain", std::abs(g_y / g_analytic - 1.), 1e-10);
      report(out, "  onset stress", std::abs(sigma_I - mc) / c, 1e-8);
    }
  }


  // (b) random states: returned stress on the surface
  void
  check_returns_on_surface()
  {
    out << std::endl
        << "(b) stress on the yield surface after the return" << std::endl;
    Random random;
    for (const auto &[name, s] :
         std::vector<std::pair<std::string, GranularStrength>>{
           {"no cut-off", strength(30., 1e4, 10.)},
           {"cut-off t = 5e3 Pa", strength(30., 1e4, 10., 5e3)},
           {"softening, cut-off", strength(30., 1e4, 10., 5e3, 25., 2e3, 0.)},
           {"c = 0, psi = 0", strength(19.8, 0., 0.)}})
      {
        const MohrCoulomb model(IsotropicElasticity(E, nu), s);
        unsigned int      counts[5] = {0, 0, 0, 0, 0};
        double            worst     = 0.;
        unsigned int      n         = 0;
        for (unsigned int i = 0; i < 400; ++i)
          {
            MaterialPoint p(model);
            for (unsigned int step = 0; step < 2; ++step)
              {
                const Tensor<2, 3> Q =
                  rotation(vector(random(), random(), random() + 1.5),
                           3. * random());
                const Tensor<2, 3> F =
                  Q *
                  stretch(0.01 * random(), 0.01 * random(), 0.01 * random());
                const double       dissipation_old = p.history[7];
                const Step         st              = advance(model, p, F);
                const Tensor<1, 3> tau = principal_kirchhoff(st.P, F);
                const unsigned int type =
                  static_cast<unsigned int>(st.history[8]);
                ++counts[type];
                ++n;
                const double eps_p = st.history[6];
                const double scale = s.cohesion + max_abs(tau) + 1.;
                const double f     = model.yield_function(tau, eps_p);
                const double t     = s.tension_cutoff;
                double       error = std::max(0., f) / scale;  // f <= 0
                error = std::max(error, (tau[0] - t) / scale); // tau_1 <= t
                if (type == 1 || type == 2 || type == 3)
                  error = std::max(error, std::abs(f) / scale);
                if (type == 4)
                  error = std::max(error, std::abs(tau[0] - t) / scale);
                // dissipation increment >= 0
                error =
                  std::max(error, (dissipation_old - p.history[7]) / scale);
                worst = std::max(worst, error);
              }
          }
        out << name << ": " << n << " steps, return types:";
        for (unsigned int t = 0; t < 5; ++t)
          out << ' ' << return_type_name(t) << ' ' << counts[t];
        out << std::endl;
        report(out, "  |f| / scale <= 1e-10 after every return", worst, 1e-10);
      }
  }


  struct TangentCase
  {
    std::string      name;
    GranularStrength strength;
    Tensor<2, 3>     F_previous; // accepted step before (I: none)
    Tensor<2, 3>     F;
    unsigned int     expected_type;
  };


  void
  check_tangents()
  {
    out << std::endl
        << "(c) consistent tangent vs central differences" << std::endl;
    const Tensor<2, 3> Q        = rotation(vector(0.3, -1., 0.7), 0.8);
    const Tensor<2, 3> Qz       = rotation(vector(0., 0., 1.), 0.5);
    const Tensor<2, 3> I        = unit_tensor();
    const auto         plain    = strength(30., 1e4, 10.);
    const auto         soft     = strength(30., 1e4, 10., 1e30, 25., 2e3, 2.);
    const auto         cut      = strength(30., 1e4, 10., 5e3);
    const auto         cut_soft = strength(30., 1e4, 10., 5e3, 25., 2e3, 2.);
    Tensor<2, 3>       shear    = I; // plane-strain simple shear + compression
    shear[0][1]                 = 0.012;
    shear[1][1]                 = 0.996;

    const std::vector<TangentCase> cases = {
      {"elastic", plain, I, Q * stretch(0.0002, -0.0001, -0.0006), 0},
      {"main plane", plain, I, Q * stretch(0.002, -0.001, -0.006), 1},
      {"main plane, softening", soft, I, Q * stretch(0.002, -0.001, -0.006), 1},
      {"main plane, plane strain shear", plain, I, Qz * shear, 1},
      {"main plane, softening, second step",
       soft,
       Q * stretch(0.002, -0.001, -0.006),
       Q * stretch(0.0025, -0.0012, -0.0075),
       1},
      {"left edge (tau_1 = tau_2)",
       plain,
       I,
       Q * stretch(0.0015, 0.0012, -0.006),
       2},
      {"left edge, softening", soft, I, Q * stretch(0.0015, 0.0012, -0.006), 2},
      {"right edge (tau_2 = tau_3)",
       plain,
       I,
       Q * stretch(0.004, -0.006, -0.0064),
       2},
      {"right edge, softening",
       soft,
       I,
       Q * stretch(0.004, -0.006, -0.0064),
       2},
      {"main plane, plane strain compression",
       plain,
       I,
       Qz * stretch(0.0015, -0.008, 0.),
       1},
      {"apex", plain, I, Q * stretch(0.004, 0.003, 0.002), 3},
      {"apex, softening", soft, I, Q * stretch(0.004, 0.003, 0.002), 3},
      {"tension cut-off (tau_1 = t)",
       cut,
       I,
       Q * stretch(0.0015, -0.0005, -0.001),
       4},
      {"tension cut-off, softening",
       cut_soft,
       I,
       Q * stretch(0.0015, -0.0005, -0.001),
       4},
      {"tension cut-off corner (tau_1 = tau_2 = t)",
       cut,
       I,
       Q * stretch(0.0015, 0.0014, -0.0002),
       4},
      {"tension cut-off and main plane",
       cut,
       I,
       Q * stretch(0.00475, -0.00025, -0.004),
       4},
      {"tension cut-off and main plane, softening",
       cut_soft,
       I,
       Q * stretch(0.00475, -0.00025, -0.004),
       4},
      {"tension cut-off apex (tau = t)",
       cut,
       I,
       Q * stretch(0.004, 0.003, 0.002),
       4}};
    for (const TangentCase &c : cases)
      {
        const MohrCoulomb model(IsotropicElasticity(E, nu), c.strength);
        MaterialPoint     p(model);
        if (c.F_previous != I)
          advance(model, p, c.F_previous);
        const Step         st   = evaluate(model, p, c.F);
        const unsigned int type = static_cast<unsigned int>(st.history[8]);
        out << c.name << ": return type " << return_type_name(type);
        if (type != c.expected_type)
          out << " UNEXPECTED (expected " << return_type_name(c.expected_type)
              << ")";
        if (type != 0)
          {
            // which surfaces the returned stress lies on
            const Tensor<1, 3> tau = principal_kirchhoff(st.P, c.F);
            const double       tol = 1e-9 * (max_abs(tau) + 1e4);
            const double       t   = c.strength.tension_cutoff;
            out << ", on:";
            if (std::abs(model.yield_function(tau, st.history[6])) < tol)
              out << " MC";
            if (std::abs(tau[0] - tau[1]) < tol)
              out << " tau_1=tau_2";
            if (std::abs(tau[1] - tau[2]) < tol)
              out << " tau_2=tau_3";
            for (unsigned int a = 0; a < 3; ++a)
              if (std::abs(tau[a] - t) < tol)
                out << " tau_" << a + 1 << "=t";
          }
        out << std::endl;
        report(out, "  tangent", tangent_error(model, p, c.F), 1e-6);

        // Plane strain (F_33 = 1, no out-of-plane shear): the tangent
        // restricted to the in-plane block (set_tangent_dimension(2), what
        // the 2D solver uses) equals that block of the full tangent checked
        // above, and is zero elsewhere; the stress is unchanged.
        if (c.name.find("plane strain") != std::string::npos)
          {
            MohrCoulomb restricted(IsotropicElasticity(E, nu), c.strength);
            restricted.set_tangent_dimension(2);
            MaterialPoint p2(restricted);
            if (c.F_previous != I)
              advance(restricted, p2, c.F_previous);
            const Step st2 = evaluate(restricted, p2, c.F);
            double error = max_abs(Tensor<2, 3>(st2.P - st.P)) / max_abs(st.P);
            const double scale = max_abs(st.A);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int J = 0; J < 3; ++J)
                for (unsigned int k = 0; k < 3; ++k)
                  for (unsigned int L = 0; L < 3; ++L)
                    {
                      const bool   in_plane = i < 2 && J < 2 && k < 2 && L < 2;
                      const double expected = in_plane ? st.A[i][J][k][L] : 0.;
                      error                 = std::max(error,
                                       std::abs(st2.A[i][J][k][L] - expected) /
                                         scale);
                    }
            report(out, "  in-plane tangent block (dimension 2)", error, 1e-12);
          }
      }
  }


  void
  check_cohesionless()
  {
    out << std::endl << "(d) cohesionless material (c = 0)" << std::endl;
    for (const double psi : {0., 10.})
      {
        const MohrCoulomb   model(IsotropicElasticity(E, nu),
                                strength(19.8, 0., psi));
        const MaterialPoint p(model);
        for (const auto &[name, F] :
             std::vector<std::pair<std::string, Tensor<2, 3>>>{
               {"F = I", unit_tensor()},
               {"isotropic tension", diagonal(1.01, 1.01, 1.01)},
               {"tension 3D",
                Tensor<2, 3>(rotation(vector(1., 1., 0.), 0.3) *
                             diagonal(1.1, 1.05, 1.02))},
               {"plane strain tension", diagonal(1.1, 1.05, 1.)},
               {"uniaxial tension", diagonal(1.001, 1., 1.)}})
          {
            const Step st     = evaluate(model, p, F);
            bool       finite = true;
            for (unsigned int i = 0; i < 81; ++i)
              finite = finite &&
                       std::isfinite(
                         st.A[Tensor<4, 3>::unrolled_to_component_indices(i)]);
            for (const double h : st.history)
              finite = finite && std::isfinite(h);
            out << "psi = " << psi << ", " << name << ": return type "
                << return_type_name(st.history[8])
                << ", max |P| = " << max_abs(st.P) << " Pa, max |A| "
                << (max_abs(st.A) == 0. ? "= 0" : "> 0")
                << (finite ? ", all finite" : ", NOT FINITE") << std::endl;
          }
      }
  }


  // (j) recoverable separation: a cohesionless point stretched beyond the
  // apex keeps the excess volume as a stress-free opening and recompacts
  // without stress; with the default (plastic) the dilation is permanent.
  void
  check_recoverable_separation()
  {
    recoverable_separation_path(out, [](const bool recoverable) {
      GranularStrength s       = strength(19.8, 0., 0.);
      s.recoverable_separation = recoverable;
      return MohrCoulomb(IsotropicElasticity(E, nu), s);
    });
  }


  void
  check_softening()
  {
    out << std::endl
        << "(e) softening in plane-strain simple shear" << std::endl;
    // peak phi = 35 deg, c = 2e4 Pa -> residual 25 deg, 1e3 Pa; psi = 0,
    // eta = 0.02. Isochoric: the mean stress stays 0 and the yield
    // condition is (tau_1 - tau_3)/2 = c(eps_p) cos(phi(eps_p)).
    const GranularStrength s = strength(35., 2e4, 0., 1e30, 25., 1e3, 0., 0.02);
    const MohrCoulomb      model(IsotropicElasticity(E, nu), s);
    MaterialPoint          p(model);
    const unsigned int     n        = 400;
    double                 max_half = 0.;
    for (unsigned int i = 1; i <= n; ++i)
      {
        Tensor<2, 3> F          = unit_tensor();
        F[0][1]                 = 0.5 * i / n; // simple shear to gamma = 0.5
        const Step         st   = advance(model, p, F);
        const Tensor<1, 3> tau  = principal_kirchhoff(st.P, F);
        const double       half = 0.5 * (tau[0] - tau[2]);
        max_half                = std::max(max_half, half);
        if (i == n / 40 || i == n / 8 || i == n)
          {
            const double ep = st.history[6];
            out << "gamma = " << F[0][1] << ": eps_p = " << std::setprecision(3)
                << ep << ", phi = " << s.phi(ep).value / deg
                << " deg, c = " << s.c(ep).value
                << " Pa, (tau_1 - tau_3)/2 = " << half << " Pa, c cos(phi) = "
                << s.c(ep).value * std::cos(s.phi(ep).value)
                << " Pa, mean stress "
                << (std::abs(tau[0] + tau[1] + tau[2]) < 1e-8 * half ? "0" :
                                                                       "NOT 0")
                << std::setprecision(10) << std::endl;
            report(out,
                   "  on the current yield surface",
                   std::abs(model.yield_function(tau, ep)) / max_abs(tau),
                   1e-10);
          }
        if (i == n)
          report(out,
                 "  residual strength c_r cos(phi_r) = 906.3 Pa reached",
                 std::abs(half / (1e3 * std::cos(25. * deg)) - 1.),
                 1e-3);
      }
    out << "peak (tau_1 - tau_3)/2 = " << std::setprecision(4) << max_half
        << " Pa (c cos(phi) = " << 2e4 * std::cos(35. * deg)
        << " Pa at the peak)" << std::setprecision(10) << std::endl;
  }


  void
  check_volume_change()
  {
    out << std::endl
        << "(f) plastic volume change (det G = det C_p^-1 = J_p^-2)"
        << std::endl;
    for (const double psi : {0., 10.})
      for (const auto &[name, F] :
           std::vector<std::pair<std::string, Tensor<2, 3>>>{
             {"main plane", stretch(0.002, -0.001, -0.006)},
             {"left edge", stretch(0.0015, 0.0012, -0.006)},
             {"right edge", stretch(0.004, -0.006, -0.0064)}})
        {
          const MohrCoulomb model(IsotropicElasticity(E, nu),
                                  strength(30., 1e4, psi));
          MaterialPoint     p(model);
          const Step        st = advance(model, p, F);
          Tensor<2, 3>      G;
          G[0][0] = st.history[0];
          G[1][1] = st.history[1];
          G[2][2] = st.history[2];
          G[0][1] = G[1][0] = st.history[3];
          G[1][2] = G[2][1] = st.history[4];
          G[0][2] = G[2][0] = st.history[5];
          // plastic volumetric log strain eps_v^p = -1/2 ln det G
          const double eps_vp = -0.5 * std::log(determinant(G));
          out << "psi = " << psi << ", " << name << " ("
              << return_type_name(st.history[8]) << "): ";
          if (psi == 0.)
            {
              out << std::endl;
              report(out, "  det G = 1", std::abs(determinant(G) - 1.), 1e-13);
            }
          else if (name == "main plane")
            {
              // eps_v^p = 2 sin(psi) dgamma, eps_p = sqrt(2/3)
              // sqrt(2 (1 + sin^2 psi)) dgamma
              const double sp = std::sin(psi * deg);
              const double ratio =
                2. * sp / (std::sqrt(2. / 3.) * std::sqrt(2. * (1. + sp * sp)));
              out << "eps_v^p / eps_p = " << std::setprecision(6)
                  << eps_vp / st.history[6] << " (analytic " << ratio << ")"
                  << std::setprecision(10) << std::endl;
              report(out,
                     "  dilatancy ratio",
                     std::abs(eps_vp / st.history[6] / ratio - 1.),
                     1e-8);
            }
          else
            out << "eps_v^p " << (eps_vp > 0. ? "> 0 (dilatant)" : "<= 0 WRONG")
                << std::endl;
        }
  }


  void
  check_objectivity_and_energy()
  {
    out << std::endl << "(h) objectivity and stored energy" << std::endl;
    const MohrCoulomb  model(IsotropicElasticity(E, nu),
                            strength(30., 1e4, 10., 5e3, 25., 2e3, 5., 0.05));
    const Tensor<2, 3> R = rotation(vector(-0.3, 1., 0.6), 1.1);
    const Tensor<2, 3> Q = rotation(vector(0.3, -1., 0.7), 0.8);
    for (const auto &[name, F] :
         std::vector<std::pair<std::string, Tensor<2, 3>>>{
           {"elastic", Q * stretch(0.0002, -0.0001, -0.0006)},
           {"main plane", Q * stretch(0.002, -0.001, -0.006)},
           {"edge", Q * stretch(0.0015, 0.0012, -0.006)},
           {"tension cut-off", Q * stretch(0.0015, -0.0005, -0.001)},
           {"tensile", Q * stretch(0.004, 0.003, 0.002)}})
      {
        MaterialPoint p(model);
        const Step    a  = evaluate(model, p, F);
        const Step    b  = evaluate(model, p, Tensor<2, 3>(R * F));
        double        dh = 0.;
        for (unsigned int i = 6; i < 9; ++i)
          dh = std::max(dh, std::abs(a.history[i] - b.history[i]));
        report(out,
               "P(RF) = R P(F), " + name + " (" +
                 return_type_name(a.history[8]) + ")",
               max_abs(Tensor<2, 3>(b.P - R * a.P)) / max_abs(a.P) + dh,
               1e-10);
        // stored energy = 1/2 tau : D^-1 tau of the returned stress
        advance(model, p, F);
        const Tensor<1, 3>        tau = principal_kirchhoff(a.P, F);
        const IsotropicElasticity el(E, nu);
        const double              K   = el.bulk_modulus();
        const double              tr  = tau[0] + tau[1] + tau[2];
        double                    s_s = 0.;
        for (unsigned int i = 0; i < 3; ++i)
          s_s += (tau[i] - tr / 3.) * (tau[i] - tr / 3.);
        const double psi_expected = tr * tr / (18. * K) + s_s / (4. * el.mu);
        report(out,
               "  energy_density(F, G_new) = elastic energy of tau",
               std::abs(model.energy_density(F, make_array_view(p.history)) -
                        psi_expected) /
                 psi_expected,
               1e-8);
      }
  }

  // max |A_iJkL - A_kLiJ| / max |A|
  double
  asymmetry(const Tensor<4, 3> &A)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            m = std::max(m, std::abs(A[i][J][k][L] - A[k][L][i][J]));
    return m / max_abs(A);
  }


  void
  check_symmetry()
  {
    out << std::endl
        << "(j) major symmetry of the tangent (which linear solver)"
        << std::endl;
    const Tensor<2, 3> Q = rotation(vector(0.3, -1., 0.7), 0.8);
    for (const auto &[name, F] :
         std::vector<std::pair<std::string, Tensor<2, 3>>>{
           {"main plane", Q * stretch(0.002, -0.001, -0.006)},
           {"left edge", Q * stretch(0.0015, 0.0012, -0.006)},
           {"right edge", Q * stretch(0.004, -0.006, -0.0064)}})
      for (const double psi : {30., 10.})
        {
          const MohrCoulomb model(IsotropicElasticity(E, nu),
                                  strength(30., 1e4, psi));
          const double      a =
            asymmetry(evaluate(model, MaterialPoint(model), F).A);
          out << name << ", psi = " << psi << ": "
              << (a < 1e-10 ? "symmetric" :
                              (a > 1e-3 ? "not symmetric" : "UNCLEAR"))
              << std::endl;
        }
  }


  void
  check_failure()
  {
    out << std::endl
        << "(i) local return that cannot be solved (snap-back)" << std::endl;
    // extreme softening of the cohesion (1e6 -> 0 Pa over eps_p ~ 1e-6):
    // the apex equation has no solution for a tensile trial state
    const MohrCoulomb model(IsotropicElasticity(E, nu),
                            strength(30., 1e6, 10., 1e30, 30., 0., 10., 1e-6));
    MaterialPoint     p(model);
    try
      {
        evaluate(model, p, stretch(0.2, 0.2, 0.2));
        out << "FAILED, no exception" << std::endl;
      }
    catch (const ExcReturnMappingFailed &e)
      {
        const std::string what = e.what();
        std::cout << what << std::endl;
        out << "ExcReturnMappingFailed"
            << (what.find("Mohr-Coulomb return mapping (apex)") !=
                    std::string::npos ?
                  " naming the model and the return" :
                  "")
            << std::endl;
      }
  }

  // (k) The mu(I) friction (Jop, Forterre & Pouliquen 2006, glass beads):
  // phi_s = 20.9 deg, phi_2 = 32.76 deg, I_0 = 0.279, d = 0.5 mm,
  // rho_s = 2450 kg/m^3.
  GranularStrength
  rate_strength(const double friction_angle = 20.9)
  {
    GranularStrength s = strength(friction_angle, 0., 0.);
    s.friction_coefficient_increment =
      std::tan(32.76 * deg) - std::tan(20.9 * deg);
    s.reference_inertial_number = 0.279;
    s.grain_diameter            = 5e-4;
    s.grain_density             = 2450.;
    return s;
  }


  void
  check_rate_dependent_friction()
  {
    out << std::endl << "(k) rate-dependent friction mu(I)" << std::endl;
    const GranularStrength s = rate_strength();
    const MohrCoulomb      model(IsotropicElasticity(E, nu), s);
    out << model.description() << std::endl;
    const double mu_s = std::tan(20.9 * deg), mu_2 = std::tan(32.76 * deg);

    // Steady pure shear at the principal log strain rates (r, 0, -r) after
    // an isotropic compression e0 (P = 3 K e0, kept by the isochoric flow):
    // at steady flow the plastic rate is the total rate, gamma_p = 2 r,
    // I = 2 r d/sqrt(P/rho_s), and the stress lies on the Mohr-Coulomb
    // surface with tan(phi) = mu_s + (mu_2 - mu_s) I/(I_0 + I):
    // (tau_1 - tau_3)/(-(tau_1 + tau_3)) = sin(phi).
    const double e0 = 1e-3;
    const double K  = IsotropicElasticity(E, nu).bulk_modulus();
    const double P  = 3. * K * e0;
    out << "steady pure shear, P = " << P << " Pa:" << std::endl;
    out << "  I (closed form)  tan(phi) closed form  measured" << std::endl;
    double worst = 0., worst_rate = 0.;
    for (const double I_target : {1e-3, 1e-2, 0.1, 0.279, 1., 10.})
      {
        const double r =
          I_target * std::sqrt(P / s.grain_density) / (2. * s.grain_diameter);
        const SteadyShear  st       = steady_pure_shear(model, e0, r);
        const Tensor<1, 3> tau      = st.tau;
        const double       sin_phi  = (tau[0] - tau[2]) / (-(tau[0] + tau[2]));
        const double       measured = std::tan(std::asin(sin_phi));
        const double       exact    = mu_s + (mu_2 - mu_s) * I_target /
                                      (s.reference_inertial_number + I_target);
        worst = std::max(worst, std::abs(measured - exact) / exact);
        worst_rate =
          std::max(worst_rate,
                   std::abs(st.plastic_shear_rate - 2. * r) / (2. * r));
        out << "  " << std::setw(15) << I_target << "  " << std::setw(20)
            << exact << "  " << std::setw(10) << std::setprecision(6)
            << measured << std::setprecision(10) << "  (return type "
            << return_type_name(st.return_type) << ")" << std::endl;
      }
    report(out, "  tan(phi) = mu(I) to 1e-8", worst, 1e-8);
    report(out, "  plastic shear rate = 2 r to 1e-8", worst_rate, 1e-8);

    // Limits: no rate (time step 0) and a very slow step give the static
    // model's stress; mu_2 is approached for I -> infinity.
    {
      const MohrCoulomb   static_model(IsotropicElasticity(E, nu),
                                     strength(20.9, 0., 0.));
      const Tensor<2, 3>  Q = rotation(vector(0.3, -1., 0.7), 0.8);
      const Tensor<2, 3>  F = Q * stretch(0.002, -0.001, -0.006);
      const MaterialPoint p(model);
      report(out,
             "  time step 0: the static stress (relative difference < 1e-14)",
             static_stress_difference(model, static_model, F, 0.),
             1e-14);
      report(
        out,
        "  time step 1e6 s: the static stress (relative difference < 1e-9)",
        static_stress_difference(model, static_model, F, 1e6),
        1e-9);
      const Tensor<1, 3> tau =
        principal_kirchhoff(evaluate(model, p, F, true, 1e-12).P, F);
      const double sin_phi = (tau[0] - tau[2]) / (-(tau[0] + tau[2]));
      report(out,
             "  time step 1e-12 s: tan(phi) = mu_2 (relative error < 1e-4)",
             std::abs(std::tan(std::asin(sin_phi)) - mu_2) / mu_2,
             1e-4);
    }

    // Consistent tangent with the rate (central differences of P).
    {
      const Tensor<2, 3> Q              = rotation(vector(0.3, -1., 0.7), 0.8);
      const Tensor<2, 3> Qz             = rotation(vector(0., 0., 1.), 0.5);
      Tensor<2, 3>       shear          = unit_tensor();
      shear[0][1]                       = 0.012;
      shear[1][1]                       = 0.996;
      GranularStrength cohesive         = rate_strength(20.9);
      cohesive.cohesion                 = 1e4;
      cohesive.residual_cohesion        = 1e4;
      GranularStrength softening        = rate_strength(30.);
      softening.residual_friction_angle = 25. * deg;
      softening.softening_strain        = 0.02;
      softening.friction_coefficient_increment =
        std::tan(40. * deg) - std::tan(30. * deg);
      struct Case
      {
        std::string      name;
        GranularStrength strength;
        Tensor<2, 3>     F;
        double           dt;
        unsigned int     expected_type;
      };
      const std::vector<Case> cases = {
        {"main plane, I ~ 0.3", s, Q * stretch(0.002, -0.001, -0.006), 1e-4, 1},
        {"main plane, I ~ 30", s, Q * stretch(0.002, -0.001, -0.006), 1e-6, 1},
        {"main plane, c = 1e4 Pa",
         cohesive,
         Q * stretch(0.002, -0.001, -0.006),
         1e-4,
         1},
        {"main plane, softening",
         softening,
         Q * stretch(0.002, -0.001, -0.006),
         1e-4,
         1},
        {"edge, plane strain shear", s, Qz * shear, 1e-4, 2},
        {"left edge", s, Q * stretch(0.0015, 0.0012, -0.006), 1e-4, 2},
        {"right edge", s, Q * stretch(0.004, -0.006, -0.0064), 1e-4, 2},
        {"right edge, c = 1e4 Pa",
         cohesive,
         Q * stretch(0.004, -0.006, -0.0064),
         1e-4,
         2}};
      for (const Case &c : cases)
        {
          const MohrCoulomb   m(IsotropicElasticity(E, nu), c.strength);
          const MaterialPoint p(m);
          const Step          st   = evaluate(m, p, c.F, true, c.dt);
          const unsigned int  type = static_cast<unsigned int>(st.history[8]);
          const double        dphi =
            c.strength
              .phi(st.history[6],
                   st.history[6], // the increment from eps_p = 0
                   -(trace(Tensor<2, 3>(st.P * transpose(c.F)))) / 3.,
                   c.dt)
              .value -
            c.strength.phi(st.history[6]).value;
          out << c.name << ": return type " << return_type_name(type)
              << (type != c.expected_type ? " UNEXPECTED" : "")
              << ", friction raised by the rate: "
              << (dphi > 0.1 * deg ? "yes" : "NO") << std::endl;
          report(out, "  tangent", tangent_error(m, p, c.F, 1e-7, c.dt), 1e-6);
        }
    }

    // Bad input.
    const std::string head = "subsection Material\n"
                             "  set model = Mohr-Coulomb\n"
                             "  set density = 2000\n"
                             "  subsection Mohr-Coulomb\n"
                             "    set friction angle = 30\n";
    {
      ParameterHandler prm;
      declare_parameters(prm);
      prm.parse_input_from_string(head +
                                  "    set limiting friction angle = 40\n"
                                  "    set grain diameter = 0.001\n"
                                  "  end\nend\n");
      const auto  m = create_model(prm);
      const auto &g = dynamic_cast<const MohrCoulomb &>(*m).strength();
      out << "grain density 0 takes the material density: "
          << (g.grain_density == 2000. ? "yes" : "NO") << std::endl;
    }
    for (const std::string bad : {"set limiting friction angle = 30",
                                  "set limiting friction angle = 90",
                                  "set limiting friction angle = fast",
                                  "set reference inertial number = 0",
                                  "set grain diameter = 0",
                                  "set grain density = -1"})
      {
        const bool sets_angle = bad.find("limiting") != std::string::npos;
        out << "invalid input <" << bad << ">: ";
        report_rejection(out,
                         head +
                           (sets_angle ?
                              std::string() :
                              std::string(
                                "    set limiting friction angle = 40\n")) +
                           (bad.find("diameter") != std::string::npos ?
                              std::string() :
                              std::string("    set grain diameter = 0.001\n")) +
                           "    " + bad + "\n  end\nend\n",
                         bad.substr(4, bad.find(" =") - 4),
                         "names the parameter");
      }
  }
} // namespace



int
main()
{
  out << std::setprecision(10);
  check_input();
  check_yield_onset();
  check_returns_on_surface();
  check_tangents();
  check_cohesionless();
  check_recoverable_separation();
  check_softening();
  check_volume_change();
  check_objectivity_and_energy();
  check_failure();
  check_symmetry();
  check_rate_dependent_friction();
  out << std::endl << "done" << std::endl;
  return 0;
}
