#include <talus/base/eisenstat_walker.h>
#include <talus/base/input.h>

#include <algorithm>
#include <cmath>

namespace Talus
{
  void
  EisenstatWalkerForcing::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    using dealii::Patterns::Selection;
    prm.declare_entry(
      "linear solver forcing",
      "fixed",
      Selection("fixed|Eisenstat-Walker"),
      "Relative tolerance of the iterative linear solves within Newton [-]: "
      "'fixed' ('linear solver tolerance' in every iteration) or "
      "'Eisenstat-Walker' (inexact Newton, Eisenstat and Walker 1996 "
      "choice 2: eta_k = gamma (|R_k|/|R_k-1|)^alpha, the first eta_max, "
      "never looser than 'maximum forcing term' nor tighter than half the "
      "Newton tolerance over the residual or 'linear solver tolerance'). "
      "Only with 'linear solver = CG' or 'GMRES'.");
    prm.declare_entry("maximum forcing term",
                      "0.1",
                      Double(0., 1.),
                      "Eisenstat-Walker: the largest relative tolerance "
                      "eta_max of a linear solve, also that of a step's "
                      "first Newton iteration (0 < eta_max < 1) [-].");
    prm.declare_entry("forcing factor",
                      "0.9",
                      Double(0., 1.),
                      "Eisenstat-Walker: gamma in eta_k = gamma "
                      "(|R_k|/|R_k-1|)^alpha (0 < gamma <= 1) [-].");
    prm.declare_entry("forcing exponent",
                      "2",
                      Double(1., 2.),
                      "Eisenstat-Walker: alpha in eta_k = gamma "
                      "(|R_k|/|R_k-1|)^alpha (1 < alpha <= 2) [-].");
  }



  void
  EisenstatWalkerForcing::parse_parameters(dealii::ParameterHandler &prm,
                                           const std::string        &subsection)
  {
    active  = prm.get("linear solver forcing") == "Eisenstat-Walker";
    eta_max = prm.get_double("maximum forcing term");
    gamma   = prm.get_double("forcing factor");
    alpha   = prm.get_double("forcing exponent");
    if (!(eta_max > 0. && eta_max < 1.))
      InputFile::reject(subsection,
                        "maximum forcing term",
                        prm.get("maximum forcing term"),
                        "0 < eta_max < 1");
    if (!(gamma > 0.))
      InputFile::reject(subsection,
                        "forcing factor",
                        prm.get("forcing factor"),
                        "0 < gamma <= 1");
    if (!(alpha > 1.))
      InputFile::reject(subsection,
                        "forcing exponent",
                        prm.get("forcing exponent"),
                        "1 < alpha <= 2");
  }



  void
  EisenstatWalkerForcing::start()
  {
    previous_residual = 0.;
    previous_eta      = 0.;
  }



  double
  EisenstatWalkerForcing::next(const double residual,
                               const double converged_residual,
                               const double floor)
  {
    double eta = eta_max;
    if (previous_residual > 0. && residual > 0.)
      {
        eta = gamma * std::pow(residual / previous_residual, alpha);
        const double safeguard = gamma * std::pow(previous_eta, alpha);
        if (safeguard > 0.1)
          eta = std::max(eta, safeguard);
        eta = std::min(eta, eta_max);
      }
    if (residual > 0.)
      eta =
        std::min(eta_max, std::max(eta, 0.5 * converged_residual / residual));
    eta               = std::max(eta, floor);
    previous_residual = residual;
    previous_eta      = eta;
    return eta;
  }
} // namespace Talus
