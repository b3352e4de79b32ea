#include <talus/base/input.h>
#include <talus/mpm/material_points.h>
#include <talus/mpm/memory_estimate.h>

#include <deal.II/base/types.h>
#include <deal.II/base/utilities.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    namespace
    {
      constexpr double gibibyte = 1024. * 1024. * 1024.;

      /** Comma-separated numbers; empty if any is not a number. */
      std::vector<double>
      numbers(const std::string &text, const char separator = ',')
      {
        std::vector<double> result;
        for (const auto &s :
             dealii::Utilities::split_string_list(text, separator))
          {
            double v;
            if (!parse_double(s, v))
              return {};
            result.push_back(v);
          }
        return result;
      }


      std::string
      gib(const double bytes)
      {
        std::ostringstream s;
        s << std::setprecision(3) << bytes / gibibyte << " GiB";
        return s.str();
      }


      std::string
      count(const double n)
      {
        std::ostringstream s;
        s << std::setprecision(3) << n;
        return s.str();
      }
    } // namespace


    // The factors: peak resident memory (/usr/bin/time -v, "Maximum
    // resident set size") of talus runs of 2 steps with the default solver
    // (CG + AMG) of a linear elastic body in a box grid; the runs and the
    // estimate of each are tabulated in doc/testing.md ("Memory
    // estimate"). A 2 x 2 grid: 186 MB (M0). A body filling the grid gives
    // m_dof + m_material per DoF (2D 2040-2095 B, 3D 5440-6150 B; the
    // larger grid the larger), one filling 1/4 (2D) or 1/8 (3D) of it the
    // split; the points per cell 1, 4, 9 (2D) and 1, 8 (3D) at a fixed grid
    // m_point (2D 394-502 B, 3D 1487 B); a grid on one level against the
    // same grid refined from a coarse one m_coarse (2D 361 B on 1 rank,
    // 502 B on 2; 3D 1209 B on 1 rank).
    template <int dim>
    double
    MemoryEstimate<dim>::bytes_base()
    {
      return 186e6;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::bytes_per_coarse_cell()
    {
      return dim == 2 ? 500. : 1200.;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::bytes_per_dof()
    {
      return dim == 2 ? 850. : 1400.;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::bytes_per_dof_with_material()
    {
      return dim == 2 ? 1250. : 4800.;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::bytes_per_point(const unsigned int n_history)
    {
      // Each internal variable is one double in the property pool, in the
      // saved copy of the step and in the properties at generation.
      return (dim == 2 ? 500. : 1500.) + 3. * sizeof(double) * n_history;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::parallel_overhead() const
    {
      // With 2 ranks the shared part of a rank peaked at 1.22 times half
      // the part of one rank, in 2D and 3D (ghost cells, the communication
      // structures of the matrix and the AMG, uneven peaks).
      return n_ranks > 1 ? 1.25 : 1.;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::available_memory()
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key, unit;
      double        kilobytes = 0.;
      while (meminfo >> key >> kilobytes >> unit)
        if (key == "MemAvailable:")
          return kilobytes * 1024.;
      const long pages     = sysconf(_SC_AVPHYS_PAGES);
      const long page_size = sysconf(_SC_PAGESIZE);
      if (pages > 0 && page_size > 0)
        return static_cast<double>(pages) * static_cast<double>(page_size);
      return 0.;
    }


    template <int dim>
    void
    MemoryEstimate<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Memory");
      prm.declare_entry(
        "limit per rank",
        "0",
        dealii::Patterns::Double(0.),
        "Memory one MPI rank may use [GiB]; 0: the memory available on this "
        "machine (MemAvailable of /proc/meminfo) shared by the ranks running "
        "on it. Before the background grid and the material points are "
        "allocated, their memory is estimated from the parameters (cells, "
        "degrees of freedom with the tangent matrix, material points; "
        "doc/testing.md, 'Memory estimate'), and a run whose estimate "
        "exceeds the limit stops with the estimate and the parameter that "
        "causes it.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    MemoryEstimate<dim>::parse_parameters(
      dealii::ParameterHandler &prm,
      const MPI_Comm            communicator,
      const unsigned int        refinement_level,
      const unsigned int        n_history_variables,
      const double              n_gmsh_grid_cells,
      const double              n_gmsh_grid_vertices,
      const double              gmsh_grid_volume)
    {
      refinement = refinement_level;
      n_history  = n_history_variables;

      // Ranks in all and on this machine (they share its memory).
      n_ranks             = 1;
      n_ranks_here        = 1;
      int mpi_initialized = 0;
      MPI_Initialized(&mpi_initialized);
      if (mpi_initialized != 0)
        {
          int n = 1;
          MPI_Comm_size(communicator, &n);
          n_ranks = n;
          MPI_Comm node;
          MPI_Comm_split_type(
            communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
          MPI_Comm_size(node, &n);
          n_ranks_here = n;
          MPI_Comm_free(&node);
        }

      prm.enter_subsection("Memory");
      const double limit_gib = prm.get_double("limit per rank");
      prm.leave_subsection();
      limit_of_machine = !(limit_gib > 0.);
      limit            = limit_of_machine ? available_memory() / n_ranks_here :
                                            limit_gib * gibibyte;

      // The grid: coarse cells, refined cells and Q1 vertices.
      const double refine = std::pow(2., static_cast<double>(refinement));
      prm.enter_subsection("Background grid");
      gmsh_grid                              = prm.get("type") != "box";
      const std::vector<double> lower        = numbers(prm.get("lower corner"));
      const std::vector<double> upper        = numbers(prm.get("upper corner"));
      const std::vector<double> subdivisions = numbers(prm.get("subdivisions"));
      prm.leave_subsection();
      double grid_volume = 0.;
      coarse_cells = cells = dofs = 0.;
      if (gmsh_grid)
        {
          coarse_cells = n_gmsh_grid_cells;
          grid_volume  = gmsh_grid_volume;
          cells        = coarse_cells * std::pow(refine, dim);
          // every refinement adds a vertex per new cell inside and a
          // surface's worth on the boundary (exact for a box)
          dofs = dim * (cells + (n_gmsh_grid_vertices - coarse_cells) *
                                  std::pow(refine, dim - 1));
        }
      else if (lower.size() == dim && upper.size() == dim &&
               subdivisions.size() == dim)
        {
          // (corners the grid rejects itself give no estimate)
          coarse_cells    = 1.;
          double vertices = 1.;
          grid_volume     = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            {
              coarse_cells *= subdivisions[d];
              vertices *= subdivisions[d] * refine + 1.;
              grid_volume *= std::abs(upper[d] - lower[d]);
            }
          cells = coarse_cells * std::pow(refine, dim);
          dofs  = dim * vertices;
        }

      // The points: each body's share of the grid times its n^dim.
      prm.enter_subsection("Body");
      const long n_bodies =
        std::max(1L,
                 std::min(prm.get_integer("number of bodies"),
                          static_cast<long>(MaterialPoints<dim>::max_bodies)));
      prm.leave_subsection();
      gmsh_body              = false;
      double all_body_volume = 0.;
      double body_points     = 0.; // sum of body volume * points per cell
      points_per_cell        = 1.;
      for (long b = 0; b < n_bodies; ++b)
        {
          prm.enter_subsection(MaterialPoints<dim>::body_subsection(b));
          const std::string geometry = prm.get("geometry");
          const double      body_points_per_cell =
            std::pow(static_cast<double>(
                       prm.get_integer("points per cell per direction")),
                     dim);
          points_per_cell    = std::max(points_per_cell, body_points_per_cell);
          gmsh_body          = gmsh_body || geometry == "gmsh";
          double body_volume = 0.;
          if (geometry == "box")
            {
              const std::vector<double> body_lower =
                numbers(prm.get("lower corner"));
              const std::vector<double> body_upper =
                numbers(prm.get("upper corner"));
              if (body_lower.size() == dim && body_upper.size() == dim)
                {
                  body_volume = 1.;
                  for (unsigned int d = 0; d < dim && !gmsh_grid; ++d)
                    {
                      // only the part inside a box grid holds points
                      const double lo =
                        std::max(std::min(body_lower[d], body_upper[d]),
                                 std::min(lower[d], upper[d]));
                      const double hi =
                        std::min(std::max(body_lower[d], body_upper[d]),
                                 std::max(lower[d], upper[d]));
                      body_volume *= std::max(hi - lo, 0.);
                    }
                  for (unsigned int d = 0; d < dim && gmsh_grid; ++d)
                    body_volume *= std::abs(body_upper[d] - body_lower[d]);
                }
            }
          else if (geometry == "polygon" && dim == 2)
            {
              // shoelace area of the vertices 'x, y; x, y; ...'
              std::vector<std::vector<double>> v;
              for (const auto &pair :
                   dealii::Utilities::split_string_list(prm.get("vertices"),
                                                        ';'))
                v.push_back(numbers(pair));
              double twice_area = 0.;
              bool   valid      = v.size() >= 3;
              for (std::size_t i = 0; valid && i < v.size(); ++i)
                {
                  const auto &a = v[i];
                  const auto &b = v[(i + 1) % v.size()];
                  valid         = a.size() == 2 && b.size() == 2;
                  if (valid)
                    twice_area += a[0] * b[1] - b[0] * a[1];
                }
              if (valid)
                body_volume = std::abs(twice_area) / 2.;
            }
          prm.leave_subsection();
          all_body_volume += body_volume;
          body_points += grid_volume > 0. && cells > 0. ?
                           std::min(body_volume, grid_volume) / grid_volume *
                             cells * body_points_per_cell :
                           0.;
        }
      // (a Gmsh body is not estimated)
      // The share of the cells with material: the tangent and the AMG are
      // built on them only (a Gmsh body or one of unknown volume: all).
      material_fraction =
        grid_volume > 0. && all_body_volume > 0. && !gmsh_body ?
          std::min(all_body_volume / grid_volume, 1.) :
          1.;
      points = body_points;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::grid_bytes_per_rank() const
    {
      return bytes_per_coarse_cell() * coarse_cells +
             parallel_overhead() *
               (bytes_per_dof() * dofs +
                bytes_per_dof_with_material() * dofs * material_fraction) /
               n_ranks;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::point_bytes_per_rank() const
    {
      return parallel_overhead() * bytes_per_point(n_history) * points /
             n_ranks;
    }


    template <int dim>
    double
    MemoryEstimate<dim>::bytes_per_rank() const
    {
      return bytes_base() + grid_bytes_per_rank() + point_bytes_per_rank();
    }


    template <int dim>
    std::string
    MemoryEstimate<dim>::summary() const
    {
      std::ostringstream s;
      s << "memory estimate: " << gib(bytes_per_rank()) << " per rank ("
        << count(cells) << " cells, " << count(dofs) << " DoFs, "
        << count(points) << " material points";
      if (gmsh_body)
        s << " (a Gmsh body's are not counted)";
      s << "), limit " << gib(limit) << " per rank";
      if (limit_of_machine)
        s << " (available memory / " << n_ranks_here << " rank(s))";
      return s.str();
    }


    template <int dim>
    void
    MemoryEstimate<dim>::check(dealii::ParameterHandler &prm) const
    {
      const std::string grid_entry = gmsh_grid ? "mesh file" : "subdivisions";
      const auto        value      = [&](const std::string &subsection,
                             const std::string &entry) {
        prm.enter_subsection(subsection);
        const std::string v = prm.get(entry);
        prm.leave_subsection();
        return v;
      };

      const double total = bytes_per_rank();
      if (limit > 0. && total > limit)
        {
          const double       grid  = grid_bytes_per_rank();
          const double       point = point_bytes_per_rank();
          const double       spare = limit - bytes_base();
          std::ostringstream allowed;
          allowed << "the run would need about " << gib(total)
                  << " of memory on each of its " << n_ranks << " MPI rank(s) ("
                  << count(cells) << " cells and " << count(dofs)
                  << " degrees of freedom: " << gib(grid) << ", "
                  << count(points) << " material points: " << gib(point);
          if (refinement > 0)
            allowed << ", on refinement level " << refinement
                    << " of subsection <Convergence study>";
          allowed << "), more than the limit of " << gib(limit) << " per rank";
          if (limit_of_machine)
            allowed << " (the " << gib(limit * n_ranks_here)
                    << " available on this machine, MemAvailable of "
                       "/proc/meminfo, shared by its "
                    << n_ranks_here
                    << " rank(s); subsection <Memory>, 'limit per rank' sets "
                       "another)";
          else
            allowed << " (subsection <Memory>, 'limit per rank')";

          if (grid >= point)
            {
              // Points grow with the cells at a fixed body: scale both.
              allowed << "; at most about "
                      << count(spare > 0. ? cells * spare / (grid + point) : 0.)
                      << " cells fit (fewer cells, more ranks or a larger "
                         "limit)";
              InputFile::reject("Background grid",
                                grid_entry,
                                value("Background grid", grid_entry),
                                allowed.str());
            }
          // The largest number of points per cell per direction that fits.
          const double n_now = std::round(std::pow(points_per_cell, 1. / dim));
          unsigned int n_fit = 0;
          for (unsigned int n = 1; n < n_now; ++n)
            if (grid + point * std::pow(n / n_now, dim) <= spare)
              n_fit = n;
          if (n_fit > 0)
            allowed << "; at most " << n_fit
                    << " point(s) per cell per direction fit (or a smaller "
                       "body, more ranks or a larger limit)";
          else
            allowed << "; not even 1 point per cell per direction fits (a "
                       "coarser grid, a smaller body, more ranks or a larger "
                       "limit)";
          InputFile::reject("Body",
                            "points per cell per direction",
                            value("Body", "points per cell per direction"),
                            allowed.str());
        }

      // Counts beyond what deal.II can index, on a machine large enough to
      // hold them: p4est numbers its trees (the coarse cells) with a 32-bit
      // int, and the DoFs are types::global_dof_index.
      const double max_trees =
        static_cast<double>(std::numeric_limits<int>::max());
      const double max_dofs = static_cast<double>(
        std::numeric_limits<dealii::types::global_dof_index>::max());
      if (coarse_cells > max_trees)
        InputFile::reject("Background grid",
                          grid_entry,
                          value("Background grid", grid_entry),
                          "the grid would have " + count(coarse_cells) +
                            " coarse cells, more than the " + count(max_trees) +
                            " that parallel::distributed::Triangulation "
                            "(p4est) can number");
      if (dofs > max_dofs)
        InputFile::reject("Background grid",
                          grid_entry,
                          value("Background grid", grid_entry),
                          "the grid would have " + count(dofs) +
                            " degrees of freedom, more than the " +
                            count(max_dofs) +
                            " that deal.II's index type can number");
    }


    template class MemoryEstimate<2>;
    template class MemoryEstimate<3>;
  } // namespace MPM
} // namespace Talus
