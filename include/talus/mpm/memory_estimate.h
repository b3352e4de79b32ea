#ifndef talus_mpm_memory_estimate_h
#define talus_mpm_memory_estimate_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>

namespace Talus
{
  namespace MPM
  {
    /**
     * The memory an MPM run will take on each MPI rank, estimated from the
     * parameters alone before the background grid and the material points
     * are allocated, and the check that it fits (subsection `Memory`).
     *
     * Counts (all ranks together, in double precision, so that no product
     * of subdivisions overflows): the coarse cells C0 of the grid (the
     * product of `Background grid/subdivisions`, or the cells of a Gmsh
     * grid once read), the active cells C = C0 2^(dim L) after L global
     * refinements (convergence study), the degrees of freedom N = dim x
     * (vertices of the refined box) and the material points P = (volume
     * of the body inside the grid) / (cell volume) x n^dim for a box or
     * polygon body, n = `Body/points per cell per direction`.
     *
     * Bytes on one of R ranks:
     *
     *   M = M_0 + m_coarse C0 + f_R (m_dof N + m_material phi N
     *                                + m_point P) / R,
     *
     * M_0 the program with its shared libraries, m_coarse the extra of the
     * coarse mesh that parallel::distributed::Triangulation and the
     * DoFHandler keep on every rank (each coarse cell is a p4est tree),
     * m_dof a DoF with its share of the cells, the vectors and the tangent
     * of the whole grid made at setup, m_material a DoF of the cells with
     * material (phi: the share of the grid's volume the body fills; 1 for
     * a Gmsh body) with the tangent of a step and its AMG hierarchy,
     * m_point a material point with its properties, its saved copy and
     * the solver's cached shape functions, f_R = 1 on one rank and 1.25 on
     * several (ghosts, communication, uneven peaks). The factors are fitted
     * to the peak resident memory of real runs (doc/testing.md, "Memory
     * estimate"). Not counted: the fill-in of a direct linear solver, the
     * boundary particles, the contact data per point, the points of a
     * Gmsh body and the cells cut by the body's surface beyond its volume.
     */
    template <int dim>
    class MemoryEstimate
    {
    public:
      /** Declare subsection `Memory` (the limit per rank). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Estimate an MPM run of @p prm on @p communicator (collective: the
       * number of ranks on this machine is counted) with the grid refined
       * @p refinement times and @p n_history internal variables per point.
       * @p n_gmsh_grid_cells, @p n_gmsh_grid_vertices and
       * @p gmsh_grid_volume describe a grid read from a Gmsh file (ignored
       * for a box grid, which is estimated from its parameters alone). Reads
       * subsections `Background grid`, `Body` and `Memory`; nothing is
       * allocated.
       */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const MPI_Comm            communicator,
                       const unsigned int        refinement,
                       const unsigned int        n_history,
                       const double              n_gmsh_grid_cells    = 0.,
                       const double              n_gmsh_grid_vertices = 0.,
                       const double              gmsh_grid_volume     = 0.);

      /**
       * Reject the input (InputFile::reject) if the estimate exceeds the
       * limit, naming the parameter that contributes most: `Background
       * grid/subdivisions` (`mesh file` for a Gmsh grid) or `Body/points
       * per cell per direction`, with the estimate, the limit and how much
       * would fit. Also rejects counts beyond deal.II's index types.
       */
      void
      check(dealii::ParameterHandler &prm) const;

      /** Estimated bytes on one rank. */
      double
      bytes_per_rank() const;

      /** The limit of one rank [bytes]. */
      double
      limit_per_rank() const
      {
        return limit;
      }

      /** One line for the start-up log: the estimate, counts and limit. */
      std::string
      summary() const;

      /**
       * MemAvailable of /proc/meminfo [bytes] (the memory the kernel can
       * give to new allocations without swapping), or the physical memory
       * from sysconf if there is no /proc/meminfo; 0 if neither is known.
       */
      static double
      available_memory();

      /** Bytes of the program and its libraries, M_0. */
      static double
      bytes_base();

      /** Bytes per coarse cell on every rank, m_coarse. */
      static double
      bytes_per_coarse_cell();

      /**
       * Bytes per DoF, shared by the ranks, m_dof: the DoF with the vectors
       * and the tangent of the whole grid made at setup, and its cell's
       * share of the triangulation and the DoF handler (a Q1^dim grid has
       * about dim DoFs per cell).
       */
      static double
      bytes_per_dof();

      /**
       * Bytes per DoF of a cell with material, m_material: the tangent of
       * a step (built on the cells with material only) and its AMG
       * hierarchy.
       */
      static double
      bytes_per_dof_with_material();

      /** Bytes per material point with @p n_history internal variables. */
      static double
      bytes_per_point(const unsigned int n_history);

      /** Counts of the whole run (all ranks). */
      double coarse_cells = 0.;
      double cells        = 0.;
      double dofs         = 0.;
      double points       = 0.;

    private:
      /** Factor on the shared part with several ranks, f_R. */
      double
      parallel_overhead() const;

      /** Bytes of the grid and of the points on one rank. */
      double
      grid_bytes_per_rank() const;

      double
      point_bytes_per_rank() const;

      unsigned int refinement       = 0;
      unsigned int n_history        = 0;
      unsigned int n_ranks          = 1;
      unsigned int n_ranks_here     = 1;
      double       limit            = 0.;
      bool         limit_of_machine = true;
      bool         gmsh_grid        = false;
      bool         gmsh_body        = false;
      double       points_per_cell  = 1.;
      /** Share of the grid's volume that the body fills, phi. */
      double material_fraction = 1.;
    };
  } // namespace MPM
} // namespace Talus

#endif
