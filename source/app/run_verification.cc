// The checks of subsection "Verification" of an MPM run (RunVerification).

#include <talus/app/run_verification.h>
#include <talus/base/input.h>
#include <talus/base/parsed_functions.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace Talus
{
  template <int dim>
  RunVerification<dim>::RunVerification(const MPI_Comm communicator)
    : communicator(communicator)
    , exact_displacement(dim)
    , exact_stress(dim == 2 ? 3 : 6)
  {}


  template <int dim>
  void
  RunVerification<dim>::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.enter_subsection("Verification");
    {
      prm.declare_entry("compare with exact solution",
                        "false",
                        Patterns::Bool(),
                        "Measure the material points against the exact "
                        "displacement (and stress) below at the report "
                        "times and print the errors.");
      prm.declare_entry("report times",
                        "",
                        Patterns::List(Patterns::Double(0)),
                        "Times at which the errors are measured [s] (the "
                        "end time is always included).");
      prm.enter_subsection("Exact displacement");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();
      prm.declare_entry("displacement error tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails (exit code 3) when the "
                        "displacement error at any report time exceeds "
                        "this value [m].");
      prm.declare_entry("relative displacement error tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails (exit code 3) when the "
                        "displacement error at any report time exceeds "
                        "this fraction of the exact displacement (the same "
                        "norm of u_ex; for 'compare center of mass' of "
                        "|u_ex(X_c)|; where u_ex = 0 the absolute error is "
                        "checked) [-].");
      prm.declare_entry("stress error tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the relative stress "
                        "error max|s - s_ex| / max|s_ex| exceeds this [-].");
      prm.declare_entry(
        "stress error norm",
        "max",
        Patterns::Selection("max|RMS"),
        "Which stress error 'stress error tolerance' checks: 'max', the "
        "largest deviation of any point, max|s - s_ex| / max|s_ex|; "
        "'RMS', the volume-weighted root mean square over the points, "
        "sqrt(sum_p V_p |s - s_ex|^2 / sum_p V_p) / max|s_ex| (|.|: the "
        "Euclidean norm of the components xx, yy, (zz,) xy, (yz, xz)). "
        "With 'RMS' both are printed.");
      prm.declare_entry("reference period",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the period of the oscillation is measured "
                        "from the zero crossings of the total momentum in x "
                        "and compared with this value [s].");
      prm.declare_entry("period tolerance",
                        "0.005",
                        Patterns::Double(0),
                        "Allowed relative error of the measured period [-].");
      prm.declare_entry("energy drift tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the total energy "
                        "(kinetic + strain + gravitational) drifts by more "
                        "than this fraction of its initial value [-].");
      prm.declare_entry("maximum final speed",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the largest speed of a "
                        "material point at the end exceeds this value "
                        "[m/s] (e.g. a body that must come to or stay at "
                        "rest).");
      prm.declare_entry(
        "final speed measure",
        "point velocity",
        Patterns::Selection("point velocity|grid velocity"),
        "Which speed 'maximum final speed' checks: 'point velocity', the "
        "velocity the material points carry (FLIP: it also holds particle "
        "velocity modes the grid does not see, which move nothing and are "
        "never damped); 'grid velocity', the grid velocity interpolated at "
        "the points, sum_I N_I(x_p) v_I, the velocity that moves them. "
        "Both are printed [-].");
      prm.declare_entry(
        "final speed window",
        "0",
        Patterns::Double(0),
        "If > 0: 'maximum final speed' bounds the largest speed of every "
        "step of the last this many seconds of the run, not only the end "
        "state: a body that must stay at rest, not just be slow at one "
        "instant [s].");
      prm.declare_entry("maximum penetration",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the largest "
                        "penetration of the material into a boundary of "
                        "subsection <Boundary particles> during the run "
                        "exceeds this value [m].");
      prm.declare_entry(
        "expected reaction",
        "0",
        Patterns::Double(0),
        "If > 0: the magnitude of the summed reaction of all boundaries of "
        "subsection <Boundary particles> at the end of the run is compared "
        "with this value [N], e.g. the weight m g of a body at rest "
        "(equilibrium); 0: off.");
      prm.declare_entry("reaction tolerance",
                        "1e-6",
                        Patterns::Double(0),
                        "Allowed relative error of the summed reaction "
                        "against 'expected reaction' [-].");
      prm.declare_entry("energy balance tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the energy balance "
                        "B = kinetic + strain + gravitational + plastic "
                        "dissipation + friction dissipation + reset "
                        "dissipation + transfer dissipation (the kinetic "
                        "energy a PIC blend or XPIC removes relative "
                        "to FLIP; APIC's loss is not booked) changes "
                        "during "
                        "the run by more than this fraction of the "
                        "largest released gravitational energy "
                        "max|G(t) - G(0)| plus the initial kinetic energy "
                        "[-].");
      prm.declare_entry(
        "stress comparison axis",
        "",
        Patterns::List(Patterns::Double(), 0, 3),
        "If given (dim components): compare only the normal stress along "
        "this axis a, a.s.a against a.s_ex.a (e.g. the axial stress of a "
        "column along its axis), for both 'stress error norm's and "
        "relative to max|a.s_ex.a|. Empty: every component [-].");
      prm.declare_entry(
        "impulse normal",
        "",
        Patterns::List(Patterns::Double(), 0, 3),
        "If given (dim components): the unit normal n, pointing into the "
        "body, of the boundary whose impulse on the body is checked against "
        "Coulomb's law. The boundary impulse over the run is J = p(T) - "
        "p(0) - m g T (change of the total momentum minus the impulse of "
        "gravity; every boundary together); J_n = J.n, J_t = |J - J_n n|. "
        "Empty: no check [-].");
      prm.declare_entry("impulse ratio",
                        "0",
                        Patterns::Double(0),
                        "The expected ratio J_t / J_n of the boundary "
                        "impulse along 'impulse normal': the friction "
                        "coefficient mu for a body that slides during the "
                        "whole contact (Coulomb) [-].");
      prm.declare_entry("impulse ratio tolerance",
                        "0.01",
                        Patterns::Double(0),
                        "Allowed relative error of the measured impulse "
                        "ratio J_t / J_n (absolute error when 'impulse "
                        "ratio' is 0, a frictionless boundary) [-].");
      prm.declare_entry("compare center of mass",
                        "false",
                        Patterns::Bool(),
                        "Measure the displacement error of the center of "
                        "mass only, abs(sum m u / sum m - u_exact(X_c)) "
                        "with X_c the initial center of mass [-] (for "
                        "bodies that roll or deform, whose points do not "
                        "follow one rigid translation).");
      prm.declare_entry("compare stress",
                        "false",
                        Patterns::Bool(),
                        "Also measure the Cauchy stress against 'Exact "
                        "stress'.");
      prm.enter_subsection("Exact stress");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim == 2 ? 3 : 6);
      prm.leave_subsection();
    }
    prm.leave_subsection();
    prm.enter_subsection("Convergence study");
    {
      prm.declare_entry("number of levels",
                        "1",
                        Patterns::Integer(1, 8),
                        "Run the problem on this many grids, each refined "
                        "once more (cells halved in every direction), and "
                        "print a convergence table of the errors with "
                        "their measured rates [-], 1 to 8. Needs 'compare "
                        "with exact solution' (errors against the exact "
                        "solution) or 'measure deposit' (the deposit "
                        "against its references, subsection <Deposit "
                        "profile>). Each level writes its files into "
                        "<output directory>/level-N.");
      prm.declare_entry("first level",
                        "0",
                        Patterns::Integer(0, 8),
                        "Refinement level of the first run [-].");
      prm.declare_entry("minimum rate",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the study fails (exit code 3) when the "
                        "rate measured between the last two levels is "
                        "below this value for any report time [-].");
      prm.declare_entry("refine time step",
                        "true",
                        Patterns::Bool(),
                        "Halve the time step with every refinement.");
      prm.declare_entry(
        "refine bin width",
        "true",
        Patterns::Bool(),
        "Halve the deposit's 'bin width' (subsection <Deposit profile>) "
        "with every refinement, so that it stays the same multiple of the "
        "point spacing (false: the same bins on every grid) [-].");
      prm.declare_entry(
        "require shrinking deposit error",
        "false",
        Patterns::Bool(),
        "With 'measure deposit' (subsection <Deposit profile>) and a "
        "'reference runout': the study fails (exit code 3) unless the "
        "runout error |L - L_ref|/L_ref decreases at every refinement "
        "[-].");
      prm.declare_entry(
        "exempt coarse levels",
        "0",
        Patterns::Integer(0, 7),
        "Number of the study's coarsest levels whose deposit may miss the "
        "references of subsection <Deposit profile> (reported in the "
        "table, not a failure); every finer level must meet them [-]. "
        "Smaller than 'number of levels'.");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  RunVerification<dim>::parse_parameters(
    dealii::ParameterHandler                 &prm,
    const Boundaries::BoundaryParticles<dim> &boundaries,
    const double                              end_time)
  {
    prm.enter_subsection("Verification");
    compare = prm.get_bool("compare with exact solution");
    times   = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("report times")));
    prm.enter_subsection("Exact displacement");
    parse_function(prm, exact_displacement, "Verification/Exact displacement");
    prm.leave_subsection();
    compare_stress = prm.get_bool("compare stress");
    compare_center = prm.get_bool("compare center of mass");
    u_tolerance    = prm.get_double("displacement error tolerance");
    u_relative_tolerance =
      prm.get_double("relative displacement error tolerance");
    s_tolerance = prm.get_double("stress error tolerance");
    stress_rms  = prm.get("stress error norm") == "RMS";
    // An optional direction of the subsection Verification: empty, or dim
    // components of a non-zero vector (returned normalised).
    const auto read_direction = [&](const std::string &entry) {
      const std::string         text = prm.get(entry);
      const std::vector<double> list = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(text));
      if (!list.empty() && list.size() != dim)
        InputFile::reject("Verification",
                          entry,
                          text,
                          "an empty value or " + std::to_string(dim) +
                            " components (one per space dimension) is "
                            "expected");
      dealii::Tensor<1, dim> v;
      for (unsigned int d = 0; d < list.size(); ++d)
        v[d] = list[d];
      if (!list.empty() && v.norm() == 0.)
        InputFile::reject("Verification",
                          entry,
                          text,
                          "a non-zero vector is expected");
      return std::make_pair(
        !list.empty(), list.empty() ? v : dealii::Tensor<1, dim>(v / v.norm()));
    };
    const auto axis_entry = read_direction("stress comparison axis");
    axial_stress          = axis_entry.first;
    stress_axis           = axis_entry.second;
    reference_period      = prm.get_double("reference period");
    period_tolerance      = prm.get_double("period tolerance");
    drift_tolerance       = prm.get_double("energy drift tolerance");
    speed_limit           = prm.get_double("maximum final speed");
    speed_window          = prm.get_double("final speed window");
    if (speed_window > 0. && speed_limit <= 0.)
      InputFile::reject("Verification",
                        "final speed window",
                        prm.get("final speed window"),
                        "0 unless 'maximum final speed' is set (the window "
                        "is where that limit applies)");
    balance_tolerance  = prm.get_double("energy balance tolerance");
    penetration_limit  = prm.get_double("maximum penetration");
    expected_reaction  = prm.get_double("expected reaction");
    reaction_tolerance = prm.get_double("reaction tolerance");
    if (expected_reaction > 0. && boundaries.empty())
      InputFile::reject("Verification",
                        "expected reaction",
                        prm.get("expected reaction"),
                        "0 unless subsection <Boundary particles> describes "
                        "a boundary (the reaction is theirs)");
    speed_of_grid           = prm.get("final speed measure") == "grid velocity";
    const auto normal_entry = read_direction("impulse normal");
    impulse_check           = normal_entry.first;
    impulse_normal          = normal_entry.second;
    impulse_ratio           = prm.get_double("impulse ratio");
    impulse_ratio_tolerance = prm.get_double("impulse ratio tolerance");
    prm.enter_subsection("Exact stress");
    parse_function(prm, exact_stress, "Verification/Exact stress");
    prm.leave_subsection();
    prm.leave_subsection();
    times.push_back(end_time);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(),
                            times.end(),
                            [](const double a, const double b) {
                              return std::abs(a - b) <=
                                     1e-12 * std::max(1., std::abs(b));
                            }),
                times.end());
  }


  template <int dim>
  void
  RunVerification<dim>::start(const MPM::Diagnostics<dim> &initial)
  {
    window_speed = window_speed_time = 0.;
    max_drift = max_balance_change = max_released = max_penetration = 0.;
    last_momentum = initial.momentum[0];
    crossings.clear();
    measured.clear();
    next_report = 0;
  }


  template <int dim>
  double
  RunVerification<dim>::max_point_speed(
    const MPM::MaterialPoints<dim> &points) const
  {
    using Properties = MPM::MaterialPointProperties<dim>;
    double v         = 0.;
    for (const auto &p : points.particle_handler())
      {
        double v2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          v2 += dealii::Utilities::fixed_power<2>(
            p.get_properties()[Properties::velocity + d]);
        v = std::max(v, std::sqrt(v2));
      }
    return dealii::Utilities::MPI::max(v, communicator);
  }


  template <int dim>
  void
  RunVerification<dim>::record_step(const MPM::Diagnostics<dim>    &initial,
                                    const MPM::Diagnostics<dim>    &d,
                                    const MPM::MaterialPoints<dim> &points,
                                    const double                    time,
                                    const double                    dt,
                                    const double                    end_time)
  {
    if (speed_window > 0. && time >= end_time - speed_window * (1. + 1e-9))
      {
        const double v =
          speed_of_grid ? d.max_grid_speed : max_point_speed(points);
        if (v >= window_speed)
          {
            window_speed      = v;
            window_speed_time = time;
          }
      }
    const double e0 = initial.kinetic_energy + initial.strain_energy +
                      initial.gravitational_energy;
    const double e =
      d.kinetic_energy + d.strain_energy + d.gravitational_energy;
    max_drift =
      std::max(max_drift, std::abs(e - e0) / std::max(std::abs(e0), 1e-300));
    max_balance_change =
      std::max(max_balance_change,
               std::abs(d.energy_balance() - initial.energy_balance()));
    for (const auto &b : d.boundaries)
      max_penetration = std::max(max_penetration, b.penetration);
    max_released =
      std::max(max_released,
               std::abs(d.gravitational_energy - initial.gravitational_energy));
    const double p = d.momentum[0];
    if (p * last_momentum < 0.)
      crossings.push_back(time - dt * p / (p - last_momentum));
    last_momentum = p;
  }


  template <int dim>
  void
  RunVerification<dim>::measure_due(const double                    time,
                                    const double                    dt,
                                    const MPM::MaterialPoints<dim> &points)
  {
    while (compare && next_report < times.size() &&
           time >= times[next_report] - 0.5 * dt)
      {
        measured.push_back(measure(time, points));
        // Name the error by the requested time, so that the columns of
        // a convergence study line up even if a step was halved.
        measured.back().time = times[next_report];
        ++next_report;
      }
  }


  template <int dim>
  VerificationErrors
  RunVerification<dim>::measure(const double                    t,
                                const MPM::MaterialPoints<dim> &points)
  {
    using Properties = MPM::MaterialPointProperties<dim>;
    VerificationErrors e;
    e.time = t;
    exact_displacement.set_time(t);
    exact_stress.set_time(t);
    double sum_u = 0., sum_v = 0., max_ds = 0., max_s = 0., sum_m = 0.,
           sum_ds = 0., sum_ex = 0.;
    dealii::Tensor<1, dim> sum_mu, sum_mX;
    for (const auto &p : points.particle_handler())
      {
        const auto         props = p.get_properties();
        dealii::Point<dim> X;
        for (unsigned int d = 0; d < dim; ++d)
          X[d] = props[Properties::initial_position + d];
        const double V0 = props[Properties::initial_volume];
        const double m  = props[Properties::mass];
        sum_m += m;
        for (unsigned int d = 0; d < dim; ++d)
          {
            sum_mu[d] += m * (p.get_location()[d] - X[d]);
            sum_mX[d] += m * X[d];
          }
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double u    = p.get_location()[d] - X[d];
            const double u_ex = exact_displacement.value(X, d);
            sum_u += V0 * std::pow(u - u_ex, 2);
            sum_ex += V0 * u_ex * u_ex;
          }
        sum_v += V0;
        if (compare_stress)
          {
            // 2D: xx yy xy; 3D: xx yy zz xy yz xz
            const std::vector<unsigned int> map =
              dim == 2 ? std::vector<unsigned int>{0, 1, 3} :
                         std::vector<unsigned int>{0, 1, 2, 3, 4, 5};
            if (axial_stress)
              {
                // a.s.a from the components (symmetric tensor)
                const std::vector<std::pair<unsigned int, unsigned int>> ij =
                  dim == 2 ?
                    std::vector<std::pair<unsigned int, unsigned int>>{{0, 0},
                                                                       {1, 1},
                                                                       {0, 1}} :
                    std::vector<std::pair<unsigned int, unsigned int>>{
                      {0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
                double s_h = 0., s_ex = 0.;
                for (unsigned int c = 0; c < map.size(); ++c)
                  {
                    const double w = (ij[c].first == ij[c].second ? 1. : 2.) *
                                     stress_axis[ij[c].first] *
                                     stress_axis[ij[c].second];
                    s_h += w * props[Properties::stress + map[c]];
                    s_ex += w * exact_stress.value(X, c);
                  }
                const double ds = s_h - s_ex;
                max_ds          = std::max(max_ds, std::abs(ds));
                sum_ds += V0 * ds * ds;
                max_s = std::max(max_s, std::abs(s_ex));
              }
            else
              for (unsigned int c = 0; c < map.size(); ++c)
                {
                  const double s_ex = exact_stress.value(X, c);
                  const double ds   = props[Properties::stress + map[c]] - s_ex;
                  max_ds            = std::max(max_ds, std::abs(ds));
                  sum_ds += V0 * ds * ds;
                  max_s = std::max(max_s, std::abs(s_ex));
                }
            if (std::getenv("TALUS_DEBUG_STRESS"))
              {
                // (the point stresses of the comparison, for
                // contrib/boundaries/column_ghost_study.py)
                std::ostringstream line;
                line << std::setprecision(10) << "DBGSTRESS " << X << ' '
                     << p.get_location();
                for (unsigned int c = 0; c < map.size(); ++c)
                  line << ' ' << props[Properties::stress + map[c]] << ' '
                       << exact_stress.value(X, c);
                line << ' ' << V0 << '\n';
                std::cout << line.str();
              }
          }
      }
    sum_u                = dealii::Utilities::MPI::sum(sum_u, communicator);
    sum_v                = dealii::Utilities::MPI::sum(sum_v, communicator);
    max_ds               = dealii::Utilities::MPI::max(max_ds, communicator);
    max_s                = dealii::Utilities::MPI::max(max_s, communicator);
    sum_ds               = dealii::Utilities::MPI::sum(sum_ds, communicator);
    sum_ex               = dealii::Utilities::MPI::sum(sum_ex, communicator);
    e.displacement_error = std::sqrt(sum_u / sum_v);
    e.exact_displacement = std::sqrt(sum_ex / sum_v);
    if (compare_center)
      {
        sum_m  = dealii::Utilities::MPI::sum(sum_m, communicator);
        sum_mu = dealii::Utilities::MPI::sum(sum_mu, communicator);
        sum_mX = dealii::Utilities::MPI::sum(sum_mX, communicator);
        const dealii::Point<dim> X_c(sum_mX / sum_m);
        dealii::Tensor<1, dim>   du = sum_mu / sum_m;
        dealii::Tensor<1, dim>   u_ex;
        for (unsigned int d = 0; d < dim; ++d)
          u_ex[d] = exact_displacement.value(X_c, d);
        du -= u_ex;
        e.displacement_error = du.norm();
        e.exact_displacement = u_ex.norm();
      }
    e.stress_error     = max_s > 0. ? max_ds / max_s : max_ds;
    e.stress_rms_error = std::sqrt(sum_ds / sum_v) / (max_s > 0. ? max_s : 1.);
    return e;
  }


  template <int dim>
  bool
  RunVerification<dim>::report(
    dealii::ConditionalOStream               &pcout,
    const MPM::Diagnostics<dim>              &initial,
    const MPM::Diagnostics<dim>              &final_state,
    const Boundaries::BoundaryParticles<dim> &boundaries,
    const MPM::MaterialPoints<dim>           &points,
    const dealii::Tensor<1, dim>             &gravity,
    const double                              time) const
  {
    if (compare)
      for (const auto &e : measured)
        {
          pcout << "  error at t = " << std::setprecision(6) << e.time
                << ": displacement " << std::setprecision(4) << std::scientific
                << e.displacement_error;
          if (compare_stress)
            pcout << (axial_stress ? ", axial stress" : ", stress")
                  << " (relative, max) " << e.stress_error;
          if (compare_stress && stress_rms)
            pcout << ", (relative, RMS) " << e.stress_rms_error;
          pcout << std::defaultfloat << '\n';
        }
    // Checks against the references given in the file.
    bool       passed = true;
    const auto check =
      [&](const std::string &what, const double value, const double tolerance) {
        const bool ok = value <= tolerance;
        pcout << "  check " << what << ": " << std::setprecision(3)
              << std::scientific << value << (ok ? " <= " : " > ") << tolerance
              << std::defaultfloat << (ok ? "  ok" : "  FAILED") << '\n';
        passed = passed && ok;
      };
    if (compare)
      for (const auto &e : measured)
        {
          if (u_tolerance > 0.)
            check("displacement error", e.displacement_error, u_tolerance);
          if (u_relative_tolerance > 0.)
            check("relative displacement error",
                  e.exact_displacement > 0. ?
                    e.displacement_error / e.exact_displacement :
                    e.displacement_error,
                  u_relative_tolerance);
          if (compare_stress && s_tolerance > 0.)
            check(std::string(axial_stress ? "axial " : "") +
                    (stress_rms ? "stress error (RMS)" : "stress error"),
                  stress_rms ? e.stress_rms_error : e.stress_error,
                  s_tolerance);
        }
    if (drift_tolerance > 0.)
      check("energy drift", max_drift, drift_tolerance);
    if (balance_tolerance > 0.)
      {
        const double scale = max_released + initial.kinetic_energy;
        pcout << "  energy balance: largest change " << std::setprecision(4)
              << max_balance_change << " J, released gravitational energy "
              << max_released << " J, plastic dissipation "
              << final_state.plastic_dissipation << " J, friction dissipation "
              << final_state.friction_dissipation << " J, reset dissipation "
              << final_state.reset_dissipation << " J, transfer dissipation "
              << final_state.transfer_dissipation
              << " J, integrator dissipation "
              << final_state.integrator_dissipation << " J, spring energy "
              << final_state.spring_energy() << " J\n";
        check("energy balance",
              max_balance_change / std::max(scale, 1e-300),
              balance_tolerance);
      }
    if (!boundaries.empty())
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &r = final_state.boundaries[b];
          pcout << "  boundary " << boundaries.boundary(b).name << ": reaction";
          for (unsigned int d = 0; d < dim; ++d)
            pcout << ' ' << std::setprecision(6)
                  << (std::abs(r.force[d]) < 1e-8 ? 0. : r.force[d]);
          pcout << " N, normal " << r.normal_force << " N, tangential "
                << (r.tangential_force < 1e-8 ? 0. : r.tangential_force)
                << " N, " << r.active << " particles in contact\n";
        }
    if (expected_reaction > 0.)
      {
        dealii::Tensor<1, dim> total;
        for (const auto &r : final_state.boundaries)
          total += r.force;
        pcout << "  summed reaction: " << std::setprecision(10) << total.norm()
              << " N (expected " << expected_reaction << " N)\n";
        check("relative reaction error",
              std::abs(total.norm() - expected_reaction) / expected_reaction,
              reaction_tolerance);
      }
    if (penetration_limit > 0.)
      check("penetration", max_penetration, penetration_limit);
    if (impulse_check)
      {
        // Impulse of the boundaries: momentum change minus gravity's.
        const dealii::Tensor<1, dim> J = final_state.momentum -
                                         initial.momentum -
                                         (final_state.mass * time) * gravity;
        const double J_n = J * impulse_normal;
        const double J_t = (J - J_n * impulse_normal).norm();
        pcout << "  boundary impulse: normal " << std::setprecision(6) << J_n
              << " N s, tangential " << J_t << " N s, ratio "
              << J_t / std::max(std::abs(J_n), 1e-300) << " (expected "
              << impulse_ratio << ")\n";
        check(impulse_ratio > 0. ? "relative impulse ratio error" :
                                   "impulse ratio error",
              J_n > 0. ? std::abs(J_t / J_n - impulse_ratio) /
                           (impulse_ratio > 0. ? impulse_ratio : 1.) :
                         std::numeric_limits<double>::infinity(),
              impulse_ratio_tolerance);
      }
    if (speed_limit > 0.)
      {
        const double v_end = max_point_speed(points);
        pcout << "  final speed: point velocity " << std::setprecision(6)
              << v_end << " m/s, grid velocity " << final_state.max_grid_speed
              << " m/s; kinetic energy of the grid velocity "
              << final_state.grid_kinetic_energy << " J\n";
        if (speed_window > 0.)
          {
            pcout << "  largest " << (speed_of_grid ? "grid" : "point")
                  << " speed over the last " << speed_window
                  << " s: " << std::setprecision(6) << window_speed
                  << " m/s at t = " << window_speed_time << " s\n";
            check(speed_of_grid ? "speed in the final window (grid velocity)" :
                                  "speed in the final window",
                  window_speed,
                  speed_limit);
          }
        else
          check(speed_of_grid ? "final speed (grid velocity)" : "final speed",
                speed_of_grid ? final_state.max_grid_speed : v_end,
                speed_limit);
      }
    if (reference_period > 0.)
      {
        if (crossings.size() < 2)
          {
            pcout << "  check period: fewer than two zero crossings of the "
                     "momentum  FAILED\n";
            passed = false;
          }
        else
          {
            const double period = 2. * (crossings.back() - crossings.front()) /
                                  (crossings.size() - 1);
            pcout << "  period: " << std::setprecision(6) << period
                  << " s (reference " << reference_period << " s)\n";
            check("relative period error",
                  std::abs(period - reference_period) / reference_period,
                  period_tolerance);
          }
      }
    return passed;
  }


  template class RunVerification<2>;
  template class RunVerification<3>;
} // namespace Talus
