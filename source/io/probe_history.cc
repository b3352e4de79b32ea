#include <talus/base/input.h>
#include <talus/io/probe_history.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace Talus
{
  namespace IO
  {
    template <int dim>
    ProbeHistory<dim>::ProbeHistory(const MPI_Comm communicator)
      : communicator(communicator)
      , is_root(dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
    {}


    template <int dim>
    void
    ProbeHistory<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection(section);
      prm.declare_entry("lower corner",
                        "",
                        Patterns::List(Patterns::Double(), 0, 3),
                        "Box of the probe: the material points whose initial "
                        "position lies in [lower corner, upper corner] "
                        "(dim components each; empty: no probe) [m]. Their "
                        "mass-weighted mean displacement is written after "
                        "every step to probe_history.csv in the output "
                        "directory.");
      prm.declare_entry("upper corner",
                        "",
                        Patterns::List(Patterns::Double(), 0, 3),
                        "Opposite corner of the probe's box [m].");
      prm.declare_entry("component",
                        "1",
                        Patterns::Integer(0, 2),
                        "Displacement component (0: x, 1: y, 2: z) compared "
                        "with the reference history and whose peak is "
                        "reported [-].");
      prm.declare_entry(
        "reference file",
        "",
        Patterns::Anything(),
        "CSV file of the reference history: lines starting with '#' are "
        "comments, the first other line is a header, then 'time, u' per "
        "line (time [s] increasing, u [m] the probe component); it must "
        "cover the run. Empty: no comparison. The relative L2-in-time "
        "error (int (u - u_ref)^2 dt / int u_ref^2 dt)^(1/2) and the "
        "relative error of the peak are printed at the end.");
      prm.declare_entry("tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails (exit code 3) when the "
                        "relative L2-in-time error against the reference "
                        "exceeds this [-].");
      prm.declare_entry("peak tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails when the relative error of "
                        "the peak (the extreme value of the component over "
                        "the run) against the reference's exceeds this "
                        "[-].");
      prm.leave_subsection();
    }


    template <int dim>
    void
    ProbeHistory<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection(section);
      const auto corner = [&](const std::string &entry) {
        const std::string text = prm.get(entry);
        const auto        v    = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(text));
        if (!v.empty() && v.size() != dim)
          InputFile::reject(section,
                            entry,
                            text,
                            "empty or " + std::to_string(dim) +
                              " components are expected");
        dealii::Point<dim> x;
        for (unsigned int d = 0; d < v.size(); ++d)
          x[d] = v[d];
        return std::make_pair(!v.empty(), x);
      };
      const auto lo = corner("lower corner");
      const auto hi = corner("upper corner");
      if (lo.first != hi.first)
        InputFile::reject(section,
                          lo.first ? "upper corner" : "lower corner",
                          "",
                          "both corners of the probe's box are needed");
      active = lo.first;
      lower  = lo.second;
      upper  = hi.second;
      for (unsigned int d = 0; active && d < dim; ++d)
        if (!(upper[d] >= lower[d]))
          InputFile::reject(section,
                            "upper corner",
                            prm.get("upper corner"),
                            "it must not be below 'lower corner' in any "
                            "coordinate");
      component = prm.get_integer("component");
      if (component >= dim)
        InputFile::reject(section,
                          "component",
                          prm.get("component"),
                          "a " + std::to_string(dim) +
                            "D problem has the components 0 to " +
                            std::to_string(dim - 1));
      tolerance      = prm.get_double("tolerance");
      peak_tolerance = prm.get_double("peak tolerance");
      reference_file = prm.get("reference file");
      reference.clear();
      if (!reference_file.empty())
        {
          if (!active)
            InputFile::reject(section,
                              "reference file",
                              reference_file,
                              "empty unless the probe's box is given");
          std::ifstream in(reference_file);
          if (!in)
            InputFile::reject(section,
                              "reference file",
                              reference_file,
                              "the file cannot be read");
          std::string line;
          bool        header = true;
          while (std::getline(in, line))
            {
              if (line.empty() || line[0] == '#')
                continue;
              if (header)
                {
                  header = false;
                  continue;
                }
              const auto f = dealii::Utilities::split_string_list(line, ',');
              double     t = 0., u = 0.;
              try
                {
                  if (f.size() < 2)
                    throw std::invalid_argument(line);
                  t = std::stod(f[0]);
                  u = std::stod(f[1]);
                }
              catch (const std::exception &)
                {
                  InputFile::reject(section,
                                    "reference file",
                                    reference_file,
                                    "every data line must be 'time, u' (not "
                                    "<" +
                                      line + ">)");
                }
              if (!reference.empty() && !(t > reference.back().first))
                InputFile::reject(section,
                                  "reference file",
                                  reference_file,
                                  "the times must increase (line <" + line +
                                    ">)");
              reference.emplace_back(t, u);
            }
          if (reference.size() < 2)
            InputFile::reject(section,
                              "reference file",
                              reference_file,
                              "it needs at least two data lines");
        }
      else if (tolerance > 0. || peak_tolerance > 0.)
        InputFile::reject(section,
                          "reference file",
                          "",
                          "a reference file is needed for the tolerances");
      prm.leave_subsection();
    }


    template <int dim>
    void
    ProbeHistory<dim>::open(const std::string &directory)
    {
      if (!active || !is_root)
        return;
      file.open(directory + "/probe_history.csv");
      if (!file)
        throw ExcInvalidInput("Cannot write <" + directory +
                              "/probe_history.csv>: check 'output directory' "
                              "in subsection <Output>.");
      file << "time";
      for (unsigned int d = 0; d < dim; ++d)
        file << ",u_"
             << "xyz"[d];
      file << '\n' << std::setprecision(12);
    }


    template <int dim>
    void
    ProbeHistory<dim>::record(const double                    t,
                              const MPM::MaterialPoints<dim> &points)
    {
      if (!active)
        return;
      using Properties = MPM::MaterialPointProperties<dim>;
      dealii::Tensor<1, dim> mu;
      double                 m = 0., n = 0.;
      for (const auto &p : points.particle_handler())
        {
          const auto props = p.get_properties();
          bool       in    = true;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double X = props[Properties::initial_position + d];
              in             = in && X >= lower[d] && X <= upper[d];
            }
          if (!in)
            continue;
          const double mass = props[Properties::mass];
          m += mass;
          n += 1.;
          for (unsigned int d = 0; d < dim; ++d)
            mu[d] += mass * (p.get_location()[d] -
                             props[Properties::initial_position + d]);
        }
      m        = dealii::Utilities::MPI::sum(m, communicator);
      n        = dealii::Utilities::MPI::sum(n, communicator);
      mu       = dealii::Utilities::MPI::sum(mu, communicator);
      n_points = static_cast<unsigned int>(n);
      const dealii::Tensor<1, dim> u = m > 0. ? mu / m : mu;
      times.push_back(t);
      values.push_back(u);
      if (is_root && file)
        {
          file << t;
          for (unsigned int d = 0; d < dim; ++d)
            file << ',' << u[d];
          file << '\n';
          file.flush();
        }
    }


    template <int dim>
    bool
    ProbeHistory<dim>::finalize(std::ostream &out)
    {
      if (!active || times.empty())
        return true;
      const unsigned int c = component;
      // extreme value: the largest magnitude
      std::size_t k_peak = 0;
      for (std::size_t k = 0; k < times.size(); ++k)
        if (std::abs(values[k][c]) > std::abs(values[k_peak][c]))
          k_peak = k;
      std::ostringstream o;
      o << std::setprecision(4);
      o << "  probe history (" << n_points << " points, component "
        << "xyz"[c] << "): peak " << values[k_peak][c]
        << " m at t = " << times[k_peak] << " s\n";
      if (reference.empty())
        {
          if (is_root)
            out << o.str();
          return true;
        }
      const auto u_ref = [&](const double t) {
        if (t <= reference.front().first)
          return reference.front().second;
        if (t >= reference.back().first)
          return reference.back().second;
        const auto it =
          std::upper_bound(reference.begin(),
                           reference.end(),
                           t,
                           [](const double                     x,
                              const std::pair<double, double> &r) {
                             return x < r.first;
                           });
        const auto &b = *it;
        const auto &a = *(it - 1);
        return a.second +
               (b.second - a.second) * (t - a.first) / (b.first - a.first);
      };
      const double t_end   = times.back();
      bool         covered = t_end <= reference.back().first * (1. + 1e-12) &&
                     times.front() >= reference.front().first - 1e-12;
      double e2 = 0., r2 = 0.;
      for (std::size_t k = 1; k < times.size(); ++k)
        {
          const double dt = times[k] - times[k - 1];
          const double d0 = values[k - 1][c] - u_ref(times[k - 1]);
          const double d1 = values[k][c] - u_ref(times[k]);
          e2 += 0.5 * dt * (d0 * d0 + d1 * d1);
          r2 +=
            0.5 * dt *
            (std::pow(u_ref(times[k - 1]), 2) + std::pow(u_ref(times[k]), 2));
        }
      const double error = r2 > 0. ? std::sqrt(e2 / r2) : std::sqrt(e2);
      // the reference's peak over the run's time span
      double ref_peak = 0., ref_peak_time = 0.;
      for (const auto &[t, u] : reference)
        if (t <= t_end * (1. + 1e-12) && std::abs(u) > std::abs(ref_peak))
          {
            ref_peak      = u;
            ref_peak_time = t;
          }
      const double peak_error = std::abs(values[k_peak][c] - ref_peak) /
                                std::max(std::abs(ref_peak), 1e-300);
      o << "  probe reference: peak " << ref_peak
        << " m at t = " << ref_peak_time << " s; relative peak error "
        << std::scientific << std::setprecision(3) << peak_error
        << ", relative L2-in-time error " << error << std::defaultfloat << '\n';
      bool passed = true;
      if (!covered)
        {
          o << "  check probe history: the reference file covers ["
            << reference.front().first << ", " << reference.back().first
            << "] s, not the run's [" << times.front() << ", " << t_end
            << "] s  FAILED\n";
          passed = false;
        }
      const auto check =
        [&](const std::string &what, const double value, const double limit) {
          if (limit <= 0.)
            return;
          const bool ok = value <= limit;
          o << "  check " << what << ": " << std::setprecision(3)
            << std::scientific << value << (ok ? " <= " : " > ") << limit
            << std::defaultfloat << (ok ? "  ok" : "  FAILED") << '\n';
          passed = passed && ok;
        };
      check("probe L2-in-time error", error, tolerance);
      check("probe peak error", peak_error, peak_tolerance);
      if (is_root)
        out << o.str();
      return passed;
    }


    template class ProbeHistory<2>;
    template class ProbeHistory<3>;
  } // namespace IO
} // namespace Talus
