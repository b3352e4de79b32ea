#include <talus/base/input.h>
#include <talus/io/deposit_profile.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Talus
{
  namespace IO
  {
    namespace
    {
      const std::string section = "Deposit profile";

      unsigned int
      axis_index(const std::string &name)
      {
        return name == "x" ? 0 : (name == "y" ? 1 : 2);
      }

      const char *
      axis_name(const unsigned int axis)
      {
        return axis == 0 ? "x" : (axis == 1 ? "y" : "z");
      }

      std::string
      trim(const std::string &s)
      {
        const auto begin = s.find_first_not_of(" \t\r");
        if (begin == std::string::npos)
          return "";
        const auto end = s.find_last_not_of(" \t\r");
        return s.substr(begin, end - begin + 1);
      }

      /** Deterministic rounding for the terminal (6 significant digits). */
      std::string
      round(const double x)
      {
        std::ostringstream o;
        o << std::setprecision(6) << (std::abs(x) < 1e-10 ? 0. : x);
        return o.str();
      }

      /**
       * Read a CSV file of 'x, h' pairs [m] (h >= 0; '#' comments, an
       * optional 'x,h' header) named by @p parameter; rejects an
       * unreadable, malformed or empty file naming the parameter.
       */
      std::vector<std::pair<double, double>>
      read_pairs(const std::string &file, const std::string &parameter)
      {
        std::vector<std::pair<double, double>> pairs;

        std::ifstream in(file);
        if (!in)
          InputFile::reject(section,
                            parameter,
                            file,
                            "this file cannot be opened for reading");
        std::string  line;
        unsigned int line_n      = 0;
        bool         seen_header = false;
        while (std::getline(in, line))
          {
            ++line_n;
            const auto hash = line.find('#');
            if (hash != std::string::npos)
              line.erase(hash);
            line = trim(line);
            if (line.empty())
              continue;
            const auto comma = line.find(',');
            if (!seen_header && pairs.empty() && comma != std::string::npos &&
                trim(line.substr(0, comma)) == "x" &&
                trim(line.substr(comma + 1)) == "h")
              {
                seen_header = true;
                continue;
              }
            double x = 0., h = 0.;
            if (comma == std::string::npos ||
                !parse_double(line.substr(0, comma), x) ||
                !parse_double(line.substr(comma + 1), h))
              InputFile::reject(section,
                                parameter,
                                file,
                                "line " + std::to_string(line_n) +
                                  " of that file is not an 'x, h' pair of "
                                  "two numbers: <" +
                                  line + ">");
            if (h < 0.)
              InputFile::reject(section,
                                parameter,
                                file,
                                "line " + std::to_string(line_n) +
                                  " of that file has a negative height <" +
                                  line + ">");
            pairs.emplace_back(x, h);
          }
        if (pairs.empty())
          InputFile::reject(section,
                            parameter,
                            file,
                            "that file holds no 'x, h' pair");
        return pairs;
      }


      /** Broadcast a vector of doubles from rank 0. */
      void
      broadcast(std::vector<double> &data, const MPI_Comm communicator)
      {
        unsigned long n = data.size();
        MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, communicator);
        data.resize(n);
        if (n > 0)
          MPI_Bcast(data.data(), n, MPI_DOUBLE, 0, communicator);
      }
    } // namespace


    template <int dim>
    DepositProfile<dim>::DepositProfile(const MPI_Comm communicator)
      : communicator(communicator)
      , is_root(dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
    {}


    template <int dim>
    void
    DepositProfile<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection(section);
      prm.declare_entry(
        "measure deposit",
        "false",
        Patterns::Bool(),
        "Measure the deposit of a granular collapse from the material "
        "points: runout, maximum height and free surface h(x) (definitions "
        "in doc/verification.md), written to deposit_profile.csv and "
        "deposit_summary.csv in the output directory and printed at the end "
        "of the run, and compared with the references below.");
      prm.declare_entry("horizontal axis",
                        "x",
                        Patterns::Selection("x|y|z"),
                        "Coordinate axis along which the material spreads "
                        "and the runout is measured [-].");
      prm.declare_entry("vertical axis",
                        dim == 2 ? "y" : "z",
                        Patterns::Selection("x|y|z"),
                        "Coordinate axis of the heights [-]; default y in 2D, "
                        "z in 3D. Must differ from the horizontal axis. With "
                        "tilted gravity choose the axes of the tilted floor.");
      prm.declare_entry("flow direction",
                        "positive",
                        Patterns::Selection("positive|negative"),
                        "Direction of spreading along the horizontal axis, "
                        "away from the wall [-]: 'positive' (increasing "
                        "coordinate) or 'negative'.");
      prm.declare_entry("wall position",
                        "0",
                        Patterns::Double(),
                        "Horizontal coordinate of the wall (origin of the "
                        "runout and of the stations) [m].");
      prm.declare_entry("base level",
                        "0",
                        Patterns::Double(),
                        "Vertical coordinate of the floor (origin of the "
                        "heights) [m].");
      prm.declare_entry("point size",
                        "0",
                        Patterns::Double(),
                        "Edge d_p of the square (cube) a material point "
                        "stands for [m], >= 0; the top of the material lies "
                        "d_p/2 above the highest point and the front d_p/2 "
                        "ahead of the front point. 0: each point's own "
                        "V0^(1/dim) from its initial volume V0 (the point "
                        "spacing of a generated box body).");
      prm.declare_entry("runout mass fraction",
                        "0.001",
                        Patterns::Double(),
                        "At most this fraction of the total mass may lie "
                        "beyond the measured front [-], 0 <= f < 1: the "
                        "front is the first point, counted from the far "
                        "end, at which the mass summed from the far end "
                        "exceeds f times the total mass.");
      prm.declare_entry("ignored outermost points",
                        "1",
                        Patterns::Integer(0),
                        "The front is never one of this many outermost "
                        "points [-], >= 0, whatever their mass: stray points "
                        "ahead of the deposit do not count.");
      prm.declare_entry("bin width",
                        "0.01",
                        Patterns::Double(),
                        "Width of the horizontal bin around a station in "
                        "which the highest point is searched [m], > 0; also "
                        "the spacing of the stations of deposit_profile.csv. "
                        "Take at least one point spacing.");
      prm.declare_entry("stations",
                        "",
                        Patterns::List(Patterns::Double()),
                        "Distances from the wall at which h(x) is printed "
                        "(besides those of the reference profile) [m].");
      prm.declare_entry("time series interval",
                        "0",
                        Patterns::Integer(0),
                        "If > 0: append runout, maximum height and h at the "
                        "stations to deposit_time_series.csv every this "
                        "many steps [-].");
      prm.declare_entry("initial height",
                        "0",
                        Patterns::Double(),
                        "Height H0 of the initial column [m], >= 0; 0: "
                        "measured from the initial points (maximum height at "
                        "t = 0). Scales the height tolerance and gives the "
                        "aspect ratio a = H0/L0.");
      prm.declare_entry("initial length",
                        "0",
                        Patterns::Double(),
                        "Length L0 of the initial column from the wall [m], "
                        ">= 0; 0: measured from the initial points (runout "
                        "at t = 0).");
      prm.declare_entry("reference profile file",
                        "",
                        Patterns::Anything(),
                        "CSV file of a reference free surface, one 'x, h' "
                        "pair [m] per line (x from the wall, h above the "
                        "base; '#' starts a comment, an 'x,h' header line "
                        "is allowed); relative paths are relative to the "
                        "working directory. Empty: none. h is compared at "
                        "every x of the file.");
      prm.declare_entry("reference runout",
                        "0",
                        Patterns::Double(),
                        "Reference runout L (distance of the front from "
                        "the wall) [m], >= 0; 0: not compared.");
      prm.declare_entry("runout tolerance",
                        "0.1",
                        Patterns::Double(),
                        "Allowed relative error |L - L_ref|/L_ref of the "
                        "runout [-], >= 0.");
      prm.declare_entry("height tolerance",
                        "0.1",
                        Patterns::Double(),
                        "Allowed error |h - h_ref| of the free surface at "
                        "each reference station, as a fraction of H0 [-], "
                        ">= 0.");
      prm.declare_entry(
        "reference failure line file",
        "",
        Patterns::Anything(),
        "CSV file of a reference failure line, 'x, h' pairs [m] along it "
        "(x from the wall, h above the base; same format as the reference "
        "profile file), e.g. data/bui2008_failure_line.csv. Empty: the "
        "failure line is neither measured nor compared. Otherwise it is "
        "measured in bands of initial height of one bin width over the "
        "height range of the file: the largest initial distance from the "
        "wall (plus d_p/2) of the points that did not move (see 'failure "
        "line displacement'), written to failure_line.csv and compared "
        "with the file's points, each in the band nearest to its height "
        "(between the points the file's straight segments are an "
        "interpolation, written to the CSV for plotting only).");
      prm.declare_entry("failure line displacement",
                        "0.002",
                        Patterns::Double(),
                        "A point whose displacement from its initial "
                        "position is below this did not move (it lies "
                        "behind the failure line) [m], > 0. Take it above "
                        "the elastic settlement of the column and below "
                        "the displacements of the sliding mass.");
      prm.declare_entry("failure line tolerance",
                        "0.1",
                        Patterns::Double(),
                        "Allowed error |s_f - s_ref| of the failure line at "
                        "each band, as a fraction of L0 [-], >= 0.");
      prm.declare_entry(
        "compare with Lube law",
        "false",
        Patterns::Bool(),
        "Compare with the 2D laws of Lube et al. 2005 (Phys Rev E "
        "72:041301) for a = H0/L0: (L - L0)/L0 = 1.2 a (a < 1.8) or "
        "1.9 a^(2/3) (a > 2.8), no law in between (refused); H/L0 = a "
        "(a < 1.15) or a^(2/5).");
      prm.declare_entry("Lube tolerance",
                        "0.15",
                        Patterns::Double(),
                        "Allowed relative error against the Lube et al. "
                        "laws [-], >= 0.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    DepositProfile<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection(section);
      active     = prm.get_bool("measure deposit");
      horizontal = axis_index(prm.get("horizontal axis"));
      vertical   = axis_index(prm.get("vertical axis"));
      if (horizontal >= dim)
        InputFile::reject(section,
                          "horizontal axis",
                          prm.get("horizontal axis"),
                          "a " + std::to_string(dim) +
                            "D problem only has the axes x, y" +
                            (dim == 3 ? ", z" : ""));
      if (vertical >= dim)
        InputFile::reject(section,
                          "vertical axis",
                          prm.get("vertical axis"),
                          "a " + std::to_string(dim) +
                            "D problem only has the axes x, y" +
                            (dim == 3 ? ", z" : ""));
      if (vertical == horizontal)
        InputFile::reject(section,
                          "vertical axis",
                          prm.get("vertical axis"),
                          "it must differ from the horizontal axis");
      direction      = prm.get("flow direction") == "positive" ? 1. : -1.;
      wall_position  = prm.get_double("wall position");
      base_level     = prm.get_double("base level");
      point_size     = get_non_negative(prm, section, "point size");
      mass_fraction  = get_non_negative(prm, section, "runout mass fraction");
      ignored_points = prm.get_integer("ignored outermost points");
      if (mass_fraction >= 1.)
        InputFile::reject(section,
                          "runout mass fraction",
                          prm.get("runout mass fraction"),
                          "it must be smaller than 1");
      bin_width       = get_positive(prm, section, "bin width");
      listed_stations = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(prm.get("stations")));
      series_interval   = prm.get_integer("time series interval");
      given_H0          = get_non_negative(prm, section, "initial height");
      given_L0          = get_non_negative(prm, section, "initial length");
      reference_runout  = get_non_negative(prm, section, "reference runout");
      runout_tolerance  = get_non_negative(prm, section, "runout tolerance");
      height_tolerance  = get_non_negative(prm, section, "height tolerance");
      compare_lube      = prm.get_bool("compare with Lube law");
      lube_tolerance    = get_non_negative(prm, section, "Lube tolerance");
      reference_file    = trim(prm.get("reference profile file"));
      failure_line_file = trim(prm.get("reference failure line file"));
      failure_displacement =
        get_positive(prm, section, "failure line displacement");
      failure_line_tolerance =
        get_non_negative(prm, section, "failure line tolerance");
      prm.leave_subsection();

      reference_profile.clear();
      reference_failure_line.clear();
      if (!active)
        return;
      if (!reference_file.empty())
        reference_profile =
          read_pairs(reference_file, "reference profile file");
      if (!failure_line_file.empty())
        {
          for (const auto &p :
               read_pairs(failure_line_file, "reference failure line file"))
            reference_failure_line.emplace_back(p.second, p.first);
          std::sort(reference_failure_line.begin(),
                    reference_failure_line.end());
          if (reference_failure_line.size() < 2 ||
              reference_failure_line.back().first -
                  reference_failure_line.front().first <
                bin_width)
            InputFile::reject(
              section,
              "reference failure line file",
              failure_line_file,
              "a failure line needs at least two 'x, h' pairs spanning a "
              "height range of at least one 'bin width'");
        }
    }


    template <int dim>
    std::vector<double>
    DepositProfile<dim>::stations() const
    {
      std::vector<double> result;
      for (const auto &p : reference_profile)
        result.push_back(p.first);
      result.insert(result.end(),
                    listed_stations.begin(),
                    listed_stations.end());
      return result;
    }


    template <int dim>
    std::vector<double>
    DepositProfile<dim>::failure_line_heights() const
    {
      std::vector<double> result;
      if (reference_failure_line.empty())
        return result;
      const double       low  = reference_failure_line.front().first;
      const double       high = reference_failure_line.back().first;
      const unsigned int n =
        static_cast<unsigned int>(std::floor((high - low) / bin_width + 1e-9));
      for (unsigned int k = 0; k < n; ++k)
        result.push_back(low + (k + 0.5) * bin_width);
      return result;
    }


    template <int dim>
    double
    DepositProfile<dim>::reference_failure_position(const double v) const
    {
      const auto &line = reference_failure_line;
      for (std::size_t i = 1; i < line.size(); ++i)
        if (v <= line[i].first || i + 1 == line.size())
          {
            const double dv = line[i].first - line[i - 1].first;
            if (dv <= 0.)
              return line[i].second;
            const double t = (v - line[i - 1].first) / dv;
            return (1. - t) * line[i - 1].second + t * line[i].second;
          }
      return line.front().second;
    }


    template <int dim>
    double
    DepositProfile<dim>::lube_runout(const double a)
    {
      if (a < 1.8)
        return 1.2 * a;
      if (a > 2.8)
        return 1.9 * std::pow(a, 2. / 3.);
      return std::numeric_limits<double>::quiet_NaN();
    }


    template <int dim>
    double
    DepositProfile<dim>::lube_height(const double a)
    {
      return a < 1.15 ? a : std::pow(a, 0.4);
    }


    template <int dim>
    typename DepositProfile<dim>::Measurement
    DepositProfile<dim>::measure(const MPM::MaterialPoints<dim> &points,
                                 const bool with_failure_line) const
    {
      // Local (s, v + d/2, m, d, s0, v0, |x - X0|) of every point (s0, v0:
      // the initial position), gathered on rank 0.
      constexpr unsigned int n_data = 7;
      std::vector<double>    local;
      for (const auto &p : points.particle_handler())
        {
          const auto   props = p.get_properties();
          const double d =
            point_size > 0. ?
              point_size :
              std::pow(props[Properties::initial_volume], 1. / dim);
          const auto        &x = p.get_location();
          dealii::Point<dim> X0;
          for (unsigned int c = 0; c < dim; ++c)
            X0[c] = props[Properties::initial_position + c];
          local.push_back(direction * (x[horizontal] - wall_position));
          local.push_back(x[vertical] - base_level + 0.5 * d);
          local.push_back(props[Properties::mass]);
          local.push_back(d);
          local.push_back(direction * (X0[horizontal] - wall_position));
          local.push_back(X0[vertical] - base_level);
          local.push_back(x.distance(X0));
        }
      const auto gathered =
        dealii::Utilities::MPI::gather(communicator, local, 0);

      const auto station_list = stations();
      const auto failure_heights =
        with_failure_line ? failure_line_heights() : std::vector<double>();
      std::vector<double> packed;
      if (is_root)
        {
          std::vector<std::array<double, n_data>> all;
          for (const auto &g : gathered)
            for (std::size_t i = 0; i + n_data - 1 < g.size(); i += n_data)
              {
                std::array<double, n_data> q;
                std::copy(g.begin() + i, g.begin() + i + n_data, q.begin());
                all.push_back(q);
              }
          // Largest s first; ties broken by the other entries, so the
          // order (and every sum) is independent of the partition.
          std::sort(all.begin(), all.end(), [](const auto &a, const auto &b) {
            return a > b;
          });
          Measurement m;
          double      total = 0.;
          for (const auto &q : all)
            total += q[2];
          m.mass = total;
          if (!all.empty())
            {
              double       beyond = 0.;
              std::size_t  front  = all.size() - 1;
              const double limit  = mass_fraction * total;
              for (std::size_t i = 0; i < all.size(); ++i)
                {
                  beyond += all[i][2];
                  if (beyond > limit && i >= ignored_points)
                    {
                      front = i;
                      break;
                    }
                }
              m.runout     = all[front][0] + 0.5 * all[front][3];
              m.max_height = -1e300;
              for (const auto &q : all)
                m.max_height = std::max(m.max_height, q[1]);
            }
          const auto height_in_bin = [&](const double x) {
            double h = 0.;
            for (const auto &q : all)
              if (std::abs(q[0] - x) <= 0.5 * bin_width * (1. + 1e-12))
                h = std::max(h, q[1]);
            return h;
          };
          for (const double x : station_list)
            m.station_heights.push_back(height_in_bin(x));
          // Regular stations every bin width up to one bin beyond the front.
          const unsigned int n = static_cast<unsigned int>(std::ceil(
                                   std::max(m.runout, 0.) / bin_width)) +
                                 2;
          std::vector<double> h(n, 0.);
          for (const auto &q : all)
            {
              const long first = static_cast<long>(
                std::ceil((q[0] - 0.5 * bin_width) / bin_width - 1e-12));
              const long last = static_cast<long>(
                std::floor((q[0] + 0.5 * bin_width) / bin_width + 1e-12));
              for (long k = std::max(first, 0L);
                   k <= std::min(last, static_cast<long>(n) - 1);
                   ++k)
                h[k] = std::max(h[k], q[1]);
            }
          packed = {m.runout, m.max_height, m.mass};
          packed.insert(packed.end(),
                        m.station_heights.begin(),
                        m.station_heights.end());
          // Failure line: per band of initial height, the largest initial
          // s0 + d/2 of the points that did not move.
          for (const double v : failure_heights)
            {
              double s_f = 0.;
              for (const auto &q : all)
                if (std::abs(q[5] - v) <= 0.5 * bin_width * (1. + 1e-12) &&
                    q[6] < failure_displacement)
                  s_f = std::max(s_f, q[4] + 0.5 * q[3]);
              packed.push_back(s_f);
            }
          for (unsigned int k = 0; k < n; ++k)
            {
              packed.push_back(k * bin_width);
              packed.push_back(h[k]);
            }
        }
      broadcast(packed, communicator);
      Measurement m;
      m.runout     = packed[0];
      m.max_height = packed[1];
      m.mass       = packed[2];
      m.station_heights.assign(packed.begin() + 3,
                               packed.begin() + 3 + station_list.size());
      const std::size_t first_failure = 3 + station_list.size();
      for (std::size_t k = 0; k < failure_heights.size(); ++k)
        m.failure_line.emplace_back(failure_heights[k],
                                    packed[first_failure + k]);
      for (std::size_t i = first_failure + failure_heights.size();
           i + 1 < packed.size();
           i += 2)
        m.profile.emplace_back(packed[i], packed[i + 1]);
      return m;
    }


    template <int dim>
    void
    DepositProfile<dim>::initialize(const MPM::MaterialPoints<dim> &points,
                                    const std::string &output_directory)
    {
      if (!active)
        return;
      directory     = output_directory;
      const auto m0 = measure(points);
      H0            = given_H0 > 0. ? given_H0 : m0.max_height;
      L0            = given_L0 > 0. ? given_L0 : m0.runout;
      if (compare_lube)
        {
          std::ostringstream what;
          what << "the Lube et al. 2005 laws need H0 > 0 and L0 > 0 (here H0 "
                  "= "
               << H0 << " m, L0 = " << L0 << " m; set 'initial height' and "
               << "'initial length' or check 'wall position', 'base level' "
                  "and the axes)";
          if (!(H0 > 0. && L0 > 0.))
            InputFile::reject(section,
                              "compare with Lube law",
                              "true",
                              what.str());
          const double a = H0 / L0;
          if (a >= 1.8 && a <= 2.8)
            {
              std::ostringstream msg;
              msg << "the aspect ratio a = H0/L0 = " << a << " (H0 = " << H0
                  << " m, L0 = " << L0
                  << " m) lies in [1.8, 2.8], between the two fits of Lube "
                     "et al. 2005 for the runout (1.2 a for a < 1.8, "
                     "1.9 a^(2/3) for a > 2.8): there is no law to compare "
                     "with there";
              InputFile::reject(section,
                                "compare with Lube law",
                                "true",
                                msg.str());
            }
        }
      if (series_interval > 0)
        {
          int ok = 1;
          if (is_root)
            {
              series.open(directory + "/deposit_time_series.csv");
              ok = series ? 1 : 0;
            }
          ok = dealii::Utilities::MPI::min(ok, communicator);
          if (!ok)
            throw ExcInvalidInput("Cannot write <" + directory +
                                  "/deposit_time_series.csv>: check 'output "
                                  "directory' in subsection <Output>.");
          if (is_root)
            {
              series << "step,time,runout,max_height";
              for (const double x : stations())
                series << ",h_" << x;
              series << '\n' << std::setprecision(12);
            }
          step(0, 0., points);
        }
    }


    template <int dim>
    void
    DepositProfile<dim>::step(const unsigned int              step,
                              const double                    time,
                              const MPM::MaterialPoints<dim> &points)
    {
      if (!active || series_interval == 0 || step % series_interval != 0)
        return;
      const auto m = measure(points);
      if (!is_root)
        return;
      series << step << ',' << time << ',' << m.runout << ',' << m.max_height;
      for (const double h : m.station_heights)
        series << ',' << h;
      series << '\n';
      series.flush();
    }


    template <int dim>
    bool
    DepositProfile<dim>::finalize(const MPM::MaterialPoints<dim> &points,
                                  std::ostream                   &out,
                                  const bool                      test_mode)
    {
      if (!active)
        return true;
      const auto         m            = measure(points, true);
      const auto         station_list = stations();
      const double       a            = L0 > 0. ? H0 / L0 : 0.;
      const double       dL           = L0 > 0. ? (m.runout - L0) / L0 : 0.;
      const double       Hn           = L0 > 0. ? m.max_height / L0 : 0.;
      std::ostringstream o;
      bool               passed = true;

      // Files (rank 0).
      int files_ok = 1;
      if (is_root)
        {
          std::ofstream profile(directory + "/deposit_profile.csv");
          profile << "# free surface h(x) of the deposit: x from the wall, "
                     "h above the base [m], bin width "
                  << bin_width << " m\nx,h\n"
                  << std::setprecision(12);
          for (const auto &p : m.profile)
            profile << p.first << ',' << p.second << '\n';
          std::ofstream summary(directory + "/deposit_summary.csv");
          summary << std::setprecision(12)
                  << "L0,H0,a,runout,max_height,runout_normalised,"
                     "height_normalised,lube_runout,lube_height,mass\n"
                  << L0 << ',' << H0 << ',' << a << ',' << m.runout << ','
                  << m.max_height << ',' << dL << ',' << Hn << ','
                  << lube_runout(a) << ',' << lube_height(a) << ',' << m.mass
                  << '\n';
          files_ok = (profile && summary) ? 1 : 0;
          if (!m.failure_line.empty())
            {
              std::ofstream failure(directory + "/failure_line.csv");
              failure << "# failure line: per band of initial height v "
                         "(width "
                      << bin_width
                      << " m), the largest initial distance from the wall "
                         "s_f of the points displaced less than "
                      << failure_displacement
                      << " m, and the reference s_ref [m]\nv,s_f,s_ref\n"
                      << std::setprecision(12);
              for (const auto &f : m.failure_line)
                failure << f.first << ',' << f.second << ','
                        << reference_failure_position(f.first) << '\n';
              files_ok = (files_ok && failure) ? 1 : 0;
            }
        }
      files_ok = dealii::Utilities::MPI::min(files_ok, communicator);
      if (!files_ok)
        throw ExcInvalidInput("Cannot write the deposit profile files in <" +
                              directory +
                              ">: check 'output directory' in subsection "
                              "<Output>.");

      o << "Deposit profile (horizontal axis " << axis_name(horizontal)
        << (direction > 0 ? " (+)" : " (-)") << ", vertical axis "
        << axis_name(vertical) << ", wall at " << round(wall_position)
        << " m, base at " << round(base_level) << " m)\n"
        << "  initial length L0 = " << round(L0)
        << " m, initial height H0 = " << round(H0)
        << " m, aspect ratio a = H0/L0 = " << round(a) << '\n'
        << "  runout L = " << round(m.runout)
        << " m, (L - L0)/L0 = " << round(dL) << '\n'
        << "  maximum height H = " << round(m.max_height)
        << " m, H/L0 = " << round(Hn) << '\n'
        << "  profile: " << (test_mode ? std::string("") : directory + "/")
        << "deposit_profile.csv (" << m.profile.size()
        << " stations, bin width " << round(bin_width) << " m)\n";

      const bool has_reference = !reference_profile.empty() ||
                                 reference_runout > 0. || compare_lube ||
                                 !m.failure_line.empty();
      if (!station_list.empty() || has_reference)
        o << "  " << std::left << std::setw(26) << "quantity" << std::setw(13)
          << "measured" << std::setw(13) << "reference" << std::setw(13)
          << "error" << std::setw(13) << "tolerance"
          << "result\n";
      const auto row = [&](const std::string &what,
                           const double       value,
                           const bool         with_reference,
                           const double       reference,
                           const double       error,
                           const double       tolerance) {
        o << "  " << std::left << std::setw(26) << what;
        if (!with_reference)
          o << round(value);
        else
          {
            o << std::setw(13) << round(value);
            const bool ok = error <= tolerance;
            passed        = passed && ok;
            o << std::setw(13) << round(reference) << std::setw(13)
              << round(error) << std::setw(13) << round(tolerance)
              << (ok ? "ok" : "FAILED");
          }
        o << '\n';
      };
      last_comparison            = Comparison();
      last_comparison.runout     = m.runout;
      last_comparison.max_height = m.max_height;
      if (reference_runout > 0.)
        last_comparison.runout_error =
          (m.runout - reference_runout) / reference_runout;
      if (!reference_profile.empty())
        {
          double largest = 0., sum = 0.;
          for (unsigned int i = 0; i < reference_profile.size(); ++i)
            {
              const double e =
                m.station_heights[i] - reference_profile[i].second;
              largest = std::max(largest, std::abs(e));
              sum += e * e;
            }
          last_comparison.max_height_error = largest;
          last_comparison.rms_height_error =
            std::sqrt(sum / reference_profile.size());
        }
      if (reference_runout > 0.)
        row("runout L [m]",
            m.runout,
            true,
            reference_runout,
            std::abs(m.runout - reference_runout) / reference_runout,
            runout_tolerance);
      for (unsigned int i = 0; i < station_list.size(); ++i)
        {
          const bool   with_reference = i < reference_profile.size();
          const double h_ref =
            with_reference ? reference_profile[i].second : 0.;
          row("h(" + round(station_list[i]) + ") [m]",
              m.station_heights[i],
              with_reference,
              h_ref,
              std::abs(m.station_heights[i] - h_ref),
              height_tolerance * H0);
        }
      // The failure line is compared where the reference gives a point
      // (in the band nearest to its height); between them the reference's
      // straight segments are an interpolation, not data, and are only
      // written to failure_line.csv.
      if (!m.failure_line.empty())
        for (const auto &r : reference_failure_line)
          {
            const auto nearest =
              std::min_element(m.failure_line.begin(),
                               m.failure_line.end(),
                               [&](const auto &f1, const auto &f2) {
                                 return std::abs(f1.first - r.first) <
                                        std::abs(f2.first - r.first);
                               });
            row("failure s_f(" + round(nearest->first) + ") [m]",
                nearest->second,
                true,
                r.second,
                std::abs(nearest->second - r.second),
                failure_line_tolerance * L0);
          }
      if (compare_lube)
        {
          const double pL = lube_runout(a);
          const double pH = lube_height(a);
          row("Lube (L - L0)/L0 [-]",
              dL,
              true,
              pL,
              std::abs(dL - pL) / pL,
              lube_tolerance);
          row("Lube H/L0 [-]",
              Hn,
              true,
              pH,
              std::abs(Hn - pH) / pH,
              lube_tolerance);
        }
      if (has_reference)
        {
          o << "  (errors: runout and Lube relative, h absolute in m with "
               "tolerance 'height tolerance' x H0";
          if (!m.failure_line.empty())
            o << ", s_f absolute in m with tolerance 'failure line "
                 "tolerance' x L0; s_f(v): largest initial distance from the "
                 "wall of the points displaced less than "
              << round(failure_displacement) << " m with initial height v";
          o << ")\n";
        }
      if (is_root)
        out << o.str() << std::flush;
      last_comparison.passed = passed;
      return passed;
    }


    template class DepositProfile<2>;
    template class DepositProfile<3>;
  } // namespace IO
} // namespace Talus
