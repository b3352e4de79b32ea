#ifndef talus_mpm_background_grid_h
#define talus_mpm_background_grid_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/distributed/tria.h>

#include <map>
#include <memory>
#include <set>
#include <string>

namespace Talus
{
  namespace MPM
  {
    /**
     * The fixed background grid of the Material Point Method: a
     * parallel::distributed::Triangulation (a subdivided box or a Gmsh
     * mesh), the vector-valued FE_Q(1)^dim space of the grid displacement
     * increment and the conforming boundary conditions on its faces.
     *
     * The grid never moves: each step solves for the displacement
     * increment of its nodes and is reset afterwards (founding paper §3).
     * Boundary ids of a box: 0/1 at x = min/max, 2/3 at y = min/max,
     * 4/5 at z = min/max (GridGenerator::subdivided_hyper_rectangle with
     * colorize = true); a Gmsh mesh keeps its physical tags.
     */
    template <int dim>
    class BackgroundGrid
    {
    public:
      explicit BackgroundGrid(const MPI_Comm communicator);

      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse subsection "Background grid" and create the mesh. */
      void
      parse_parameters_and_create(dealii::ParameterHandler &prm);

      /**
       * The bounding box of every rank's locally owned cells (one box per
       * rank, all ranks; collective), the guide of
       * Particles::ParticleHandler::insert_global_particles(). (deal.II
       * 9.4's GridTools::compute_mesh_predicate_bounding_box() with merged
       * boxes crashes on some unrefined 3D grids, e.g. 20 x 20 x 10 cells.)
       */
      std::vector<std::vector<dealii::BoundingBox<dim>>>
      global_bounding_boxes() const;

      /** Distribute the degrees of freedom (after creation/refinement). */
      void
      setup_dofs();

      /**
       * Multi-velocity-field contact between bodies (subsection Body
       * contact): the grid carries @p n velocity fields, one per body, on
       * the element FE_Q(1)^(dim n) (components b dim ... b dim + dim - 1
       * are the displacement increment of body b). Call before
       * parse_parameters_and_create(); 1 (the default) is the one field of
       * standard MPM on FE_Q(1)^dim.
       */
      void
      set_velocity_fields(const unsigned int n);

      /** Number of velocity fields on the grid (1 or the number of bodies). */
      unsigned int
      n_velocity_fields() const
      {
        return n_fields;
      }

      /**
       * The element the dof handler is distributed with: fe with one
       * velocity field, FE_Q(1)^(dim n) with n fields. Cell dofs of
       * dof_handler are ordered by this element; fe describes the dim
       * components of one field (the solver's per-body cell caches).
       */
      const dealii::FESystem<dim> &
      system_fe() const
      {
        return multi_field_fe ? *multi_field_fe : fe;
      }

      /**
       * Component mask of all fields' components d in @p directions (size
       * dim n_velocity_fields()).
       */
      dealii::ComponentMask
      component_mask(const std::vector<bool> &directions) const;

      MPI_Comm                                          mpi_communicator;
      dealii::parallel::distributed::Triangulation<dim> triangulation;
      /** FE_Q(1)^dim: one velocity field (see system_fe()). */
      dealii::FESystem<dim>   fe;
      dealii::DoFHandler<dim> dof_handler;
      dealii::MappingQ1<dim>  mapping;

      dealii::IndexSet locally_owned_dofs;
      dealii::IndexSet locally_relevant_dofs;

      /** True for an axis-aligned box grid: shape gradients are computed
       * directly from the cell extent. */
      bool is_cartesian;

      /** Cell extent per direction on a box grid [m], of the cells of
       * level cell_extent_level (the finest level of a refined grid). */
      dealii::Tensor<1, dim> cell_extent;

      /** The refinement level whose cells have the extent cell_extent. */
      int cell_extent_level = 0;

      /** Smallest cell diameter [m]. */
      double minimal_cell_diameter;

      /** Bounding box of the whole grid. */
      dealii::Point<dim> lower_corner, upper_corner;

      /** Boundary ids where all displacement components are zero. */
      std::set<dealii::types::boundary_id> fixed_boundaries;

      /**
       * Whether every grid node inside the box [fixed_region_lower,
       * fixed_region_upper] is fixed ('fixed region lower corner', 'fixed
       * region upper corner'), in addition to the fixed boundaries: e.g.
       * the root face of a clamped beam inside the grid.
       */
      bool fixed_region_given = false;

      /** Corners of the box of fixed nodes [m] (if fixed_region_given). */
      dealii::Point<dim> fixed_region_lower, fixed_region_upper;

      /** Boundary ids where the normal displacement is zero (the boundary
       * must be axis aligned). */
      std::set<dealii::types::boundary_id> slip_boundaries;

      /**
       * Axis-aligned boundaries with Coulomb friction: boundary id ->
       * friction coefficient mu [-] (contact with separation, stick/slip;
       * see MPMSolver).
       */
      std::map<dealii::types::boundary_id, double> friction_boundaries;

      /**
       * How nodes leave the friction boundaries: false ('pressure'), every
       * node with mass starts a step in contact and is released when the
       * boundary would pull; true ('velocity'), a node whose projected
       * velocity leaves the boundary faster than gravity brings it back
       * within the step starts free.
       */
      bool friction_separation_by_velocity = true;

      /**
       * First guess of the friction nodes' states ('friction state guess'):
       * true ('previous step'), a node that ended the previous step stuck
       * starts stuck if friction can stop its projected tangential velocity
       * within the step; false ('velocity'), a node with a tangential
       * projected velocity starts slipping.
       */
      bool friction_guess_from_previous_step = false;

      /**
       * Smallest ballistic lift-off height v_n^2 / (2 g_n), as a fraction
       * of the cell size, for which a separating node starts free (with
       * friction_separation_by_velocity) [-].
       */
      double separation_lift_height = 0.05;

    private:
      unsigned int                           n_fields = 1;
      std::unique_ptr<dealii::FESystem<dim>> multi_field_fe;
      std::string                            type;
      std::string                            mesh_file;
      std::vector<unsigned int>              subdivisions;
    };

    /**
     * Parse the entries "lower corner" and "upper corner" of the current
     * subsection @p subsection into an axis-aligned box, or reject them
     * (wrong number of coordinates, upper not above lower).
     */
    template <int dim>
    std::pair<dealii::Point<dim>, dealii::Point<dim>>
    parse_box(const dealii::ParameterHandler &prm,
              const std::string              &subsection);

    /** Parse "a, b[, c]" into a point with dim coordinates, or reject. */
    template <int dim>
    dealii::Point<dim>
    parse_point(const dealii::ParameterHandler &prm,
                const std::string              &subsection,
                const std::string              &entry);
  } // namespace MPM
} // namespace Talus

#endif
