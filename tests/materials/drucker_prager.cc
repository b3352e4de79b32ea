// Unit test of the finite-strain Drucker-Prager model, driving the
// deformation gradient of one material point directly. Kirchhoff stresses,
// tension positive, p = tr(tau)/3, J2 = s:s/2.
//  - creation from parameters, description(), rejection of invalid input
//  - (g) cone fits: sqrt(J2)/(-p) for c = 0 at phi = 19.8 deg (0.332 plane
//        strain, 0.441 triaxial compression, 0.351 triaxial extension,
//        VERIFICATION.md 2.2), from the coefficients and from returns
//  - (a) yield onset at the analytic cone for proportional paths and simple
//        shear
//  - (b) after every return the stress is on the yield surface
//  - (c) consistent tangent vs central differences per return type (cone,
//        apex, mean-stress cut-off cap and corner), with and without
//        softening, for the three fits
//  - (d) cohesionless material: F = I and tensile states
//  - (e) softening to the residual strength
//  - (f) isochoric plastic flow for psi = 0, dilatancy for psi > 0
//  - (h) objectivity, energy density of the elastic strain
//  - (k) rate-dependent friction mu(I): steady pure shear at constant rate
//        against the closed form for the three fits, the static limit,
//        tangents of the cone return
// Numbers that depend on round-off are printed as "ok" only.

#include <talus/materials/drucker_prager.h>
#include <talus/materials/exceptions.h>

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

  using Fit = DruckerPrager::ConeFit;

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

  std::string
  fit_name(const Fit fit)
  {
    return fit == Fit::plane_strain ?
             "plane strain" :
             (fit == Fit::triaxial_compression ? "triaxial compression" :
                                                 "triaxial extension");
  }

  // the cone coefficient eta, written out independently of the model
  double
  eta_by_hand(const Fit fit, const double phi)
  {
    const double s = std::sin(phi), t = std::tan(phi);
    if (fit == Fit::plane_strain)
      return 3. * t / std::sqrt(9. + 12. * t * t);
    if (fit == Fit::triaxial_compression)
      return 6. * s / (std::sqrt(3.) * (3. - s));
    return 6. * s / (std::sqrt(3.) * (3. + s));
  }

  double
  xi_by_hand(const Fit fit, const double phi)
  {
    const double s = std::sin(phi), t = std::tan(phi);
    if (fit == Fit::plane_strain)
      return 3. / std::sqrt(9. + 12. * t * t);
    if (fit == Fit::triaxial_compression)
      return 6. * std::cos(phi) / (std::sqrt(3.) * (3. - s));
    return 6. * std::cos(phi) / (std::sqrt(3.) * (3. + s));
  }

  // sqrt(J2) and p of principal stresses
  std::pair<double, double>
  invariants(const Tensor<1, 3> &tau)
  {
    const double p  = (tau[0] + tau[1] + tau[2]) / 3.;
    double       J2 = 0.;
    for (unsigned int a = 0; a < 3; ++a)
      J2 += 0.5 * (tau[a] - p) * (tau[a] - p);
    return {std::sqrt(J2), p};
  }


  void
  check_input()
  {
    ParameterHandler prm;
    declare_parameters(prm);
    prm.parse_input_from_string("subsection Material\n"
                                "  set model = Drucker-Prager\n"
                                "  set Young's modulus = 1e7\n"
                                "  set Poisson's ratio = 0.25\n"
                                "  subsection Drucker-Prager\n"
                                "    set cone fit = triaxial compression\n"
                                "    set friction angle = 19.8\n"
                                "  end\n"
                                "end\n");
    const auto model = create_model(prm);
    out << "created: " << model->description() << std::endl;
    for (const std::string bad : {"set friction angle = -5",
                                  "set dilatancy angle = 45",
                                  "set cohesion = -1",
                                  "set tension cut-off = -1",
                                  "set residual friction angle = 40"})
      {
        out << "invalid input <" << bad << ">: ";
        report_rejection(out,
                         "subsection Material\n"
                         "  set model = Drucker-Prager\n"
                         "  subsection Drucker-Prager\n    " +
                           bad + "\n  end\nend\n",
                         "Material/Drucker-Prager",
                         "names Material/Drucker-Prager");
      }
  }


  void
  check_cone_ratios()
  {
    out << std::endl
        << "(g) cone fits at phi = 19.8 deg, c = 0: sqrt(J2)/(-p)" << std::endl;
    for (const Fit fit : {Fit::plane_strain,
                          Fit::triaxial_compression,
                          Fit::triaxial_extension})
      {
        const DruckerPrager model(IsotropicElasticity(E, nu),
                                  strength(19.8, 0., 0.),
                                  fit);
        const double        by_hand = eta_by_hand(fit, 19.8 * deg);
        // a compressive trial state far outside the cone
        const Tensor<2, 3> F =
          rotation(vector(1., 2., 3.), 0.4) * stretch(0.004, -0.002, -0.010);
        const MaterialPoint p(model);
        const Step          st = evaluate(model, p, F);
        const auto [sJ2, mean] = invariants(principal_kirchhoff(st.P, F));
        out << fit_name(fit) << ": eta = " << std::setprecision(3)
            << model.eta(19.8 * deg).value << ", by hand " << by_hand
            << ", after a " << return_type_name(st.history[8])
            << " return sqrt(J2)/(-p) = " << sJ2 / (-mean)
            << std::setprecision(10) << std::endl;
        report(out,
               "  eta and xi = formulas",
               std::abs(model.eta(19.8 * deg).value - by_hand) +
                 std::abs(model.xi(19.8 * deg).value -
                          xi_by_hand(fit, 19.8 * deg)),
               1e-14);
        report(out,
               "  returned state on the cone",
               std::abs(sJ2 / (-mean) - by_hand),
               1e-10);
      }
  }


  template <class Path>
  double
  yield_onset(const DruckerPrager &model, const Path &F_of_s)
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
    out << std::endl
        << "(a) yield onset, phi = 30 deg, c = 1e4 Pa, psi = 10 deg"
        << std::endl;
    const IsotropicElasticity el(E, nu);
    const Tensor<2, 3>        Q = rotation(vector(1., -2., 0.5), 0.6);
    for (const Fit fit : {Fit::plane_strain,
                          Fit::triaxial_compression,
                          Fit::triaxial_extension})
      {
        const DruckerPrager model(el, strength(30., 1e4, 10.), fit);
        const double        eta = eta_by_hand(fit, 30. * deg);
        const double        xic = xi_by_hand(fit, 30. * deg) * 1e4;
        for (const auto &[name, d] :
             std::vector<std::pair<std::string, Tensor<1, 3>>>{
               {"triaxial compression path", vector(0.1, 0.1, -1.)},
               {"triaxial extension path", vector(0.3, -0.5, -0.5)}})
          {
            const auto F_of_s = [&, d = d](const double s) {
              return Tensor<2, 3>(Q * stretch(s * d[0], s * d[1], s * d[2]));
            };
            Tensor<1, 3> tau1;
            for (unsigned int a = 0; a < 3; ++a)
              tau1[a] = el.lambda * (d[0] + d[1] + d[2]) + 2. * el.mu * d[a];
            const auto [sJ2, mean]  = invariants(tau1);
            const double s_analytic = xic / (sJ2 + eta * mean);
            const double s_y        = yield_onset(model, F_of_s);
            out << fit_name(fit) << " fit, " << name
                << ": onset at s = " << std::setprecision(6) << s_y
                << " (analytic xi c/(sqrt(J2) "
                << "+ eta p) per unit s = " << s_analytic << ")"
                << std::setprecision(10) << std::endl;
            report(out,
                   "  onset strain",
                   std::abs(s_y / s_analytic - 1.),
                   1e-10);
          }
        // simple shear: sqrt(J2) = 2 mu ln(l), p = 0: g = 2 sinh(xi c/(2mu))
        const auto F_of_g = [](const double g) {
          Tensor<2, 3> F = unit_tensor();
          F[0][1]        = g;
          return F;
        };
        const double g_y        = yield_onset(model, F_of_g);
        const double g_analytic = 2. * std::sinh(xic / (2. * el.mu));
        out << fit_name(fit)
            << " fit, simple shear: onset at gamma = " << std::setprecision(6)
            << g_y << " (analytic " << g_analytic << ")"
            << std::setprecision(10) << std::endl;
        report(out, "  onset strain", std::abs(g_y / g_analytic - 1.), 1e-10);
      }
  }


  void
  check_returns_on_surface()
  {
    out << std::endl
        << "(b) stress on the yield surface after the return" << std::endl;
    Random random;
    for (const Fit fit : {Fit::plane_strain,
                          Fit::triaxial_compression,
                          Fit::triaxial_extension})
      for (const auto &[name, s] :
           std::vector<std::pair<std::string, GranularStrength>>{
             {"no cut-off", strength(30., 1e4, 10.)},
             {"cut-off t = 2e3 Pa", strength(30., 1e4, 10., 2e3)},
             {"softening, cut-off", strength(30., 1e4, 10., 2e3, 25., 2e3, 0.)},
             {"c = 0, psi = 0", strength(19.8, 0., 0.)}})
        {
          const DruckerPrager model(IsotropicElasticity(E, nu), s, fit);
          unsigned int        counts[5] = {0, 0, 0, 0, 0};
          double              worst     = 0.;
          unsigned int        n         = 0;
          for (unsigned int i = 0; i < 200; ++i)
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
                  const double eps_p     = st.history[6];
                  const double scale     = s.cohesion + max_abs(tau) + 1.;
                  const double f         = model.yield_function(tau, eps_p);
                  const auto [sJ2, mean] = invariants(tau);
                  const double t         = s.tension_cutoff;
                  double       error     = std::max(0., f) / scale;
                  error                  = std::max(error, (mean - t) / scale);
                  if (type == 1 || type == 3)
                    error = std::max(error, std::abs(f) / scale);
                  if (type == 4)
                    error = std::max(error, std::abs(mean - t) / scale);
                  error =
                    std::max(error, (dissipation_old - p.history[7]) / scale);
                  worst = std::max(worst, error);
                }
            }
          out << fit_name(fit) << ", " << name << ": " << n
              << " steps, return types:";
          for (unsigned int t = 0; t < 5; ++t)
            out << ' ' << return_type_name(t) << ' ' << counts[t];
          out << std::endl;
          report(out,
                 "  |f| / scale <= 1e-10 after every return",
                 worst,
                 1e-10);
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
    const Tensor<2, 3> I        = unit_tensor();
    const auto         plain    = strength(30., 1e4, 10.);
    const auto         soft     = strength(30., 1e4, 10., 1e30, 25., 2e3, 2.);
    const auto         cut      = strength(30., 1e4, 10., 2e3);
    const auto         cut_soft = strength(30., 1e4, 10., 2e3, 25., 2e3, 2.);
    Tensor<2, 3>       shear    = I; // plane-strain simple shear
    shear[0][1]                 = 0.012;
    shear[1][1]                 = 0.996;

    const std::vector<TangentCase> cases = {
      {"elastic", plain, I, Q * stretch(0.0002, -0.0001, -0.0006), 0},
      {"cone", plain, I, Q * stretch(0.003, -0.001, -0.008), 1},
      {"cone, softening", soft, I, Q * stretch(0.003, -0.001, -0.008), 1},
      {"cone, plane strain shear", plain, I, shear, 1},
      {"cone, softening, second step",
       soft,
       Q * stretch(0.003, -0.001, -0.008),
       Q * stretch(0.0035, -0.0012, -0.0095),
       1},
      {"apex", plain, I, Q * stretch(0.004, 0.003, 0.002), 3},
      {"apex, softening", soft, I, Q * stretch(0.004, 0.003, 0.002), 3},
      {"cut-off cap (p = t)", cut, I, Q * stretch(0.0004, 0.0002, 0.0001), 4},
      {"cut-off cap, softening",
       cut_soft,
       I,
       Q * stretch(0.0004, 0.0002, 0.0001),
       4},
      {"cut-off corner (p = t on the cone)",
       cut,
       I,
       Q * stretch(0.003, 0., -0.0005),
       4},
      {"cut-off corner, softening",
       cut_soft,
       I,
       Q * stretch(0.003, 0., -0.0005),
       4}};
    for (const Fit fit : {Fit::plane_strain,
                          Fit::triaxial_compression,
                          Fit::triaxial_extension})
      for (const TangentCase &c : cases)
        {
          const DruckerPrager model(IsotropicElasticity(E, nu),
                                    c.strength,
                                    fit);
          MaterialPoint       p(model);
          if (c.F_previous != I)
            advance(model, p, c.F_previous);
          const Step         st   = evaluate(model, p, c.F);
          const unsigned int type = static_cast<unsigned int>(st.history[8]);
          out << fit_name(fit) << ", " << c.name << ": return type "
              << return_type_name(type);
          if (type != c.expected_type)
            out << " UNEXPECTED (expected " << return_type_name(c.expected_type)
                << ")";
          if (type == 4)
            {
              // p = t, and on the cone (corner) or inside it (cap)
              const auto [sJ2, mean] =
                invariants(principal_kirchhoff(st.P, c.F));
              const double f =
                model.yield_function(principal_kirchhoff(st.P, c.F),
                                     st.history[6]);
              out << ", p - t "
                  << (std::abs(mean - c.strength.tension_cutoff) < 1e-9 * sJ2 ?
                        "= 0" :
                        "NOT 0")
                  << ", "
                  << (std::abs(f) < 1e-9 * sJ2 ? "on the cone" :
                                                 "inside the cone");
            }
          out << std::endl;
          report(out, "  tangent", tangent_error(model, p, c.F), 1e-6);
        }
  }


  void
  check_cohesionless()
  {
    out << std::endl << "(d) cohesionless material (c = 0)" << std::endl;
    const DruckerPrager model(IsotropicElasticity(E, nu),
                              strength(19.8, 0., 0.),
                              Fit::plane_strain);
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
          finite =
            finite &&
            std::isfinite(st.A[Tensor<4, 3>::unrolled_to_component_indices(i)]);
        for (const double h : st.history)
          finite = finite && std::isfinite(h);
        out << name << ": return type " << return_type_name(st.history[8])
            << ", max |P| = " << max_abs(st.P) << " Pa, max |A| "
            << (max_abs(st.A) == 0. ? "= 0" : "> 0")
            << (finite ? ", all finite" : ", NOT FINITE") << std::endl;
      }
  }


  // (j) separated volume (c = 0, plane-strain fit): as for Mohr-Coulomb
  void
  check_recoverable_separation()
  {
    recoverable_separation_path(out, [](const bool recoverable) {
      GranularStrength s       = strength(19.8, 0., 0.);
      s.recoverable_separation = recoverable;
      return DruckerPrager(IsotropicElasticity(E, nu), s, Fit::plane_strain);
    });
  }


  void
  check_softening()
  {
    out << std::endl
        << "(e) softening in plane-strain simple shear (plane-strain fit)"
        << std::endl;
    const GranularStrength s = strength(35., 2e4, 0., 1e30, 25., 1e3, 0., 0.02);
    const DruckerPrager model(IsotropicElasticity(E, nu), s, Fit::plane_strain);
    MaterialPoint       p(model);
    const unsigned int  n = 400;
    for (unsigned int i = 1; i <= n; ++i)
      {
        Tensor<2, 3> F         = unit_tensor();
        F[0][1]                = 0.5 * i / n;
        const Step         st  = advance(model, p, F);
        const Tensor<1, 3> tau = principal_kirchhoff(st.P, F);
        if (i == n)
          {
            const auto [sJ2, mean] = invariants(tau);
            const double residual =
              xi_by_hand(Fit::plane_strain, 25. * deg) * 1e3;
            out << "gamma = 0.5: eps_p > 10 eta "
                << (st.history[6] > 0.2 ? "yes" : "NO")
                << ", sqrt(J2) = " << std::setprecision(5) << sJ2
                << " Pa, residual xi(phi_r) c_r = " << residual << " Pa"
                << std::setprecision(10) << std::endl;
            report(out,
                   "  residual strength reached",
                   std::abs(sJ2 / residual - 1.),
                   1e-3);
            report(out,
                   "  on the current yield surface",
                   std::abs(model.yield_function(tau, st.history[6])) / sJ2,
                   1e-10);
          }
      }
  }


  void
  check_volume_change()
  {
    out << std::endl
        << "(f) plastic volume change, cone return (det G = J_p^-2)"
        << std::endl;
    for (const double psi : {0., 10.})
      {
        const DruckerPrager model(IsotropicElasticity(E, nu),
                                  strength(30., 1e4, psi),
                                  Fit::plane_strain);
        MaterialPoint       p(model);
        const Step   st = advance(model, p, stretch(0.003, -0.001, -0.008));
        Tensor<2, 3> G;
        G[0][0] = st.history[0];
        G[1][1] = st.history[1];
        G[2][2] = st.history[2];
        G[0][1] = G[1][0] = st.history[3];
        G[1][2] = G[2][1] = st.history[4];
        G[0][2] = G[2][0]   = st.history[5];
        const double eps_vp = -0.5 * std::log(determinant(G));
        out << "psi = " << psi << " (" << return_type_name(st.history[8])
            << "): ";
        if (psi == 0.)
          {
            out << std::endl;
            report(out, "  det G = 1", std::abs(determinant(G) - 1.), 1e-13);
          }
        else
          {
            // eps_v^p = eta_bar dgamma, eps_p = sqrt(2/3) sqrt(1/2 +
            // eta_bar^2/3) dgamma
            const double eb = eta_by_hand(Fit::plane_strain, psi * deg);
            const double ratio =
              eb / (std::sqrt(2. / 3.) * std::sqrt(0.5 + eb * eb / 3.));
            out << "eps_v^p / eps_p = " << std::setprecision(6)
                << eps_vp / st.history[6] << " (analytic " << ratio << ")"
                << std::setprecision(10) << std::endl;
            report(out,
                   "  dilatancy ratio",
                   std::abs(eps_vp / st.history[6] / ratio - 1.),
                   1e-8);
          }
      }
  }


  void
  check_objectivity_and_energy()
  {
    out << std::endl << "(h) objectivity and stored energy" << std::endl;
    const DruckerPrager model(IsotropicElasticity(E, nu),
                              strength(30., 1e4, 10., 2e3, 25., 2e3, 5., 0.05),
                              Fit::triaxial_compression);
    const Tensor<2, 3>  R = rotation(vector(-0.3, 1., 0.6), 1.1);
    const Tensor<2, 3>  Q = rotation(vector(0.3, -1., 0.7), 0.8);
    for (const auto &[name, F] :
         std::vector<std::pair<std::string, Tensor<2, 3>>>{
           {"elastic", Q * stretch(0.0002, -0.0001, -0.0006)},
           {"cone", Q * stretch(0.003, -0.001, -0.008)},
           {"cap", Q * stretch(0.0004, 0.0002, 0.0001)},
           {"corner", Q * stretch(0.003, 0., -0.0005)}})
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


  // (k) The mu(I) friction (Jop, Forterre & Pouliquen 2006, glass beads):
  // phi_s = 20.9 deg, phi_2 = 32.76 deg, I_0 = 0.279, d = 0.5 mm,
  // rho_s = 2450 kg/m^3; the cone coefficients follow phi(I).
  void
  check_rate_dependent_friction()
  {
    out << std::endl << "(k) rate-dependent friction mu(I)" << std::endl;
    GranularStrength s = strength(20.9, 0., 0.);
    s.friction_coefficient_increment =
      std::tan(32.76 * deg) - std::tan(20.9 * deg);
    s.reference_inertial_number = 0.279;
    s.grain_diameter            = 5e-4;
    s.grain_density             = 2450.;
    const double mu_s = std::tan(20.9 * deg), mu_2 = std::tan(32.76 * deg);
    const double e0 = 1e-3;
    const double P  = 3. * IsotropicElasticity(E, nu).bulk_modulus() * e0;

    // Steady pure shear (r, 0, -r) under P: the plastic rate is the total
    // rate, gamma_p = 2 r, I = 2 r d/sqrt(P/rho_s), and the stress lies on
    // the cone sqrt(J2) = eta(phi(I)) P with tan(phi(I)) = mu(I).
    for (const Fit fit : {Fit::plane_strain,
                          Fit::triaxial_compression,
                          Fit::triaxial_extension})
      {
        const DruckerPrager model(IsotropicElasticity(E, nu), s, fit);
        out << model.description() << std::endl;
        double worst = 0., worst_rate = 0.;
        for (const double I_target : {1e-3, 0.1, 1., 10.})
          {
            const double r = I_target * std::sqrt(P / s.grain_density) /
                             (2. * s.grain_diameter);
            const SteadyShear st = steady_pure_shear(model, e0, r);
            const double      p  = (st.tau[0] + st.tau[1] + st.tau[2]) / 3.;
            double            J2 = 0.;
            for (unsigned int a = 0; a < 3; ++a)
              J2 += 0.5 * (st.tau[a] - p) * (st.tau[a] - p);
            const double mu = mu_s + (mu_2 - mu_s) * I_target /
                                       (s.reference_inertial_number + I_target);
            const double exact = model.eta(std::atan(mu)).value;
            worst =
              std::max(worst, std::abs(std::sqrt(J2) / (-p) - exact) / exact);
            worst_rate =
              std::max(worst_rate,
                       std::abs(st.plastic_shear_rate - 2. * r) / (2. * r));
            if (st.return_type != 1)
              worst = 1.;
          }
        report(out,
               "  I = 1e-3 .. 10: sqrt(J2)/P = eta(phi(I)) on the cone to 1e-8",
               worst,
               1e-8);
        report(out, "  plastic shear rate = 2 r to 1e-8", worst_rate, 1e-8);
      }

    const DruckerPrager model(IsotropicElasticity(E, nu), s, Fit::plane_strain);
    const DruckerPrager static_model(IsotropicElasticity(E, nu),
                                     strength(20.9, 0., 0.),
                                     Fit::plane_strain);
    const Tensor<2, 3>  Q = rotation(vector(0.3, -1., 0.7), 0.8);
    const Tensor<2, 3>  F = Q * stretch(0.002, -0.001, -0.006);
    report(out,
           "  time step 0: the static stress (relative difference < 1e-14)",
           static_stress_difference(model, static_model, F, 0.),
           1e-14);

    // Consistent tangent of the cone return with the rate.
    GranularStrength cohesive         = s;
    cohesive.cohesion                 = 1e4;
    cohesive.residual_cohesion        = 1e4;
    GranularStrength softening        = s;
    softening.residual_friction_angle = 15. * deg;
    struct Case
    {
      std::string      name;
      GranularStrength strength;
      Fit              fit;
      double           dt;
    };
    for (const Case &c : std::vector<Case>{
           {"cone, plane strain, I ~ 0.3", s, Fit::plane_strain, 1e-4},
           {"cone, plane strain, I ~ 30", s, Fit::plane_strain, 1e-6},
           {"cone, triaxial compression", s, Fit::triaxial_compression, 1e-4},
           {"cone, c = 1e4 Pa", cohesive, Fit::plane_strain, 1e-4},
           {"cone, softening", softening, Fit::plane_strain, 1e-4}})
      {
        const DruckerPrager m(IsotropicElasticity(E, nu), c.strength, c.fit);
        const MaterialPoint pt(m);
        const Step          st        = evaluate(m, pt, F, true, c.dt);
        const Step          st_static = evaluate(m, pt, F, true, 0.);
        out << c.name << ": return type " << return_type_name(st.history[8])
            << ", stress raised by the rate: "
            << (max_abs(st.P) > max_abs(st_static.P) * (1. + 1e-3) ? "yes" :
                                                                     "NO")
            << std::endl;
        report(out, "  tangent", tangent_error(m, pt, F, 1e-7, c.dt), 1e-6);
      }
  }
} // namespace



int
main()
{
  out << std::setprecision(10);
  check_input();
  check_cone_ratios();
  check_yield_onset();
  check_returns_on_surface();
  check_tangents();
  check_cohesionless();
  check_recoverable_separation();
  check_softening();
  check_volume_change();
  check_objectivity_and_energy();
  check_rate_dependent_friction();
  out << std::endl << "done" << std::endl;
  return 0;
}
