#include <talus/base/input.h>
#include <talus/base/step_size_controller.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace Talus
{
  void
  TruncationErrorControl::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    prm.declare_entry(
      "error tolerance",
      "0",
      Double(),
      "Tolerance of the estimated local truncation error of a step, "
      "relative to the step's displacement increment [-], >= 0; 0: off (a "
      "fixed step, see 'adaptive time step'). When > 0 the step is chosen "
      "by the error (Zienkiewicz and Xie 1991: e = dt^2 (beta - 1/6) "
      "(a_{n+1} - a_n), mass weighted RMS over the grid nodes, divided by "
      "the RMS of the increment plus 'error displacement floor'; "
      "doc/theory.md), 'time step' is the first step and the largest "
      "unless 'maximum time step' is set, and the steps land on the output "
      "and report times and the end time. The global error follows the "
      "tolerance about linearly; 1e-3 is a period error of about 0.1 % per "
      "radian. Not with 'adaptive time step' or a quasi-static analysis. "
      "A coupled problem: see 'coupled error norm'.");
    prm.declare_entry(
      "coupled error norm",
      "larger field",
      dealii::Patterns::Selection("larger field|mass weighted"),
      "The error of a coupled step chosen by 'error tolerance' (problem = "
      "coupled; rejected otherwise). 'larger field': the larger of the "
      "relative errors of the MPM (grid) and of a dynamic structure (its "
      "Bossak-Newmark step, lumped mass), each as above; the step resolves "
      "every mode of either field, also those of a light structure that "
      "the interface excites. 'mass weighted': one RMS over the dofs of "
      "both fields, each weighted by its mass, divided by the RMS of both "
      "fields' increments: the error of the whole system, in which a "
      "structure counts by its share of the mass (doc/coupling.md, 'Time "
      "step chosen by the error').");
    prm.declare_entry("error safety factor",
                      "0.9",
                      Double(),
                      "Safety factor s of the step controller dt_new = dt "
                      "s (tolerance/error)^(1/2) [-], 0 < s <= 1.");
    prm.declare_entry("error growth limit",
                      "2",
                      Double(),
                      "Largest factor by which the error lets the step "
                      "grow from one step to the next [-], > 1.");
    prm.declare_entry("error shrink limit",
                      "0.2",
                      Double(),
                      "Smallest factor by which the error shrinks the step "
                      "(also of a rejected step) [-], 0 < f < 1.");
    prm.declare_entry("error rejection factor",
                      "2",
                      Double(),
                      "A step whose estimated error exceeds this factor "
                      "times 'error tolerance' is rejected and repeated "
                      "with the smaller step the controller gives [-], "
                      ">= 1. A step at 'minimum time step' is accepted "
                      "whatever its error.");
    prm.declare_entry("error displacement floor",
                      "1e-9",
                      Double(),
                      "Absolute floor u_0 added to the RMS of the step's "
                      "displacement increment in the error's denominator "
                      "[m], >= 0: keeps the relative error finite for a "
                      "body at rest. Choose it below any displacement of "
                      "interest per step.");
    prm.declare_entry("maximum time step",
                      "0",
                      Double(),
                      "Largest step the error may choose [s], >= 0; 0: "
                      "'time step'. Used only with 'error tolerance' > 0.");
  }


  void
  TruncationErrorControl::parse_parameters(dealii::ParameterHandler &prm,
                                           const double              time_step)
  {
    tolerance = get_non_negative(prm, "Time", "error tolerance");
    safety    = prm.get_double("error safety factor");
    if (!(safety > 0. && safety <= 1.))
      InputFile::reject("Time",
                        "error safety factor",
                        prm.get("error safety factor"),
                        "it must lie in (0, 1]");
    growth_limit = prm.get_double("error growth limit");
    if (!(growth_limit > 1.))
      InputFile::reject("Time",
                        "error growth limit",
                        prm.get("error growth limit"),
                        "it must be larger than 1");
    shrink_limit = prm.get_double("error shrink limit");
    if (!(shrink_limit > 0. && shrink_limit < 1.))
      InputFile::reject("Time",
                        "error shrink limit",
                        prm.get("error shrink limit"),
                        "it must lie in (0, 1)");
    rejection_factor = prm.get_double("error rejection factor");
    if (!(rejection_factor >= 1.))
      InputFile::reject("Time",
                        "error rejection factor",
                        prm.get("error rejection factor"),
                        "it must be at least 1 (a step within the tolerance "
                        "is never rejected)");
    floor                = get_non_negative(prm,
                             "Time",
                             "error displacement "
                                            "floor");
    const double maximum = get_non_negative(prm, "Time", "maximum time step");
    if (maximum > 0. && maximum < time_step)
      InputFile::reject("Time",
                        "maximum time step",
                        prm.get("maximum time step"),
                        "it must be 0 or at least 'time step' (" +
                          prm.get("time step") + " s), the first step");
    max_dt                = maximum > 0. ? maximum : time_step;
    mass_weighted_coupled = prm.get("coupled error norm") == "mass weighted";
  }


  namespace
  {
    // The error constant |beta - 1/6| of the Zienkiewicz-Xie estimate;
    // beta = 1/6 (third order in the displacement): the bound without the
    // cancellation.
    double
    error_constant(const double beta)
    {
      return std::abs(beta - 1. / 6.) > 1e-3 ? std::abs(beta - 1. / 6.) :
                                               1. / 6.;
    }


    // eta = e / (increment + floor), 0 without an error
    double
    relative_error(const double e, const double increment, const double floor)
    {
      if (e == 0.)
        return 0.;
      const double scale = increment + floor;
      return scale > 0. ? e / scale : std::numeric_limits<double>::infinity();
    }
  } // namespace


  double
  TruncationErrorControl::error(const TruncationErrorNorms &norms,
                                const double                dt,
                                const double                beta) const
  {
    return relative_error(dt * dt * error_constant(beta) *
                            norms.acceleration_change,
                          norms.increment,
                          floor);
  }


  double
  TruncationErrorControl::mass_weighted_error(
    const std::vector<std::pair<TruncationErrorNorms, double>> &fields,
    const double                                                dt) const
  {
    // sums of m e^2, m du^2 and m over the fields
    double e2 = 0., du2 = 0., mass = 0.;
    for (const auto &[norms, beta] : fields)
      {
        const double e =
          dt * dt * error_constant(beta) * norms.acceleration_change;
        e2 += norms.mass * e * e;
        du2 += norms.mass * norms.increment * norms.increment;
        mass += norms.mass;
      }
    if (!(mass > 0.))
      return 0.;
    return relative_error(std::sqrt(e2 / mass), std::sqrt(du2 / mass), floor);
  }


  double
  TruncationErrorControl::step_factor(const double eta) const
  {
    if (!(eta > 0.))
      return growth_limit;
    return std::clamp(safety * std::sqrt(tolerance / eta),
                      shrink_limit,
                      growth_limit);
  }
} // namespace Talus
