#ifndef talus_mpm_material_points_h
#define talus_mpm_material_points_h

#include <talus/mpm/background_grid.h>

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <deal.II/numerics/data_component_interpretation.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    /**
     * Layout of the properties every material point carries in the
     * Particles::ParticleHandler. Fixed block first, then the history
     * variables of the constitutive model.
     *
     * | property             | size    | unit   |
     * |----------------------|---------|--------|
     * | mass                 | 1       | kg (per unit thickness in 2D) |
     * | initial volume V0    | 1       | m^dim  |
     * | velocity             | dim     | m/s    |
     * | acceleration         | dim     | m/s^2  |
     * | deformation gradient | dim*dim | -      |
     * | Cauchy stress        | 6 (xx yy zz xy yz xz) | Pa |
     * | initial position X   | dim     | m      |
     * | affine velocity C    | dim*dim | 1/s    |
     * | history              | n       | model dependent |
     * | contact gap          | dim * n_slots | m |
     * | contact offset       | n_slots | m |
     *
     * In 2D (plane strain) the out-of-plane stress zz is kept because it
     * enters plasticity; the in-plane deformation gradient has F_zz = 1.
     *
     * The affine velocity C (row-major, C_ij = d v_i / d x_j) is the grid
     * velocity gradient at the point after the step; only the APIC velocity
     * update uses it (Jiang et al. 2015: the point's velocity field is
     * v_p + C (x - x_p)). With FLIP it stays zero.
     *
     * The contact gap holds, per boundary b (n_slots = the number of
     * boundaries, MaterialPoints::set_contact_slots()), the elastic tangential
     * relative displacement of the point's contact point against boundary
     * b (the stick spring of a boundary with 'contact side = material
     * points', see MPMSolver); zero while the point does not touch it.
     * The contact offset is the depth by which the point's extent
     * overlapped boundary b at the start (a lattice of points in a curved
     * or inclined body pokes out of it by up to half a point spacing): its
     * contact gap is measured from that depth on, so that a body placed on
     * a boundary starts touching it instead of being thrown off.
     */
    template <int dim>
    struct MaterialPointProperties
    {
      static constexpr unsigned int mass             = 0;
      static constexpr unsigned int initial_volume   = 1;
      static constexpr unsigned int velocity         = 2;
      static constexpr unsigned int acceleration     = velocity + dim;
      static constexpr unsigned int deformation      = acceleration + dim;
      static constexpr unsigned int stress           = deformation + dim * dim;
      static constexpr unsigned int initial_position = stress + 6;
      static constexpr unsigned int affine_velocity  = initial_position + dim;
      static constexpr unsigned int history = affine_velocity + dim * dim;

      /**
       * Number of properties for a model with @p n_history variables and
       * contact data for @p n_slots boundaries.
       */
      static constexpr unsigned int
      n_properties(const unsigned int n_history, const unsigned int n_slots)
      {
        return history + n_history + (dim + 1) * n_slots;
      }

      /** First component of the contact gap against boundary @p b. */
      static constexpr unsigned int
      contact_gap(const unsigned int n_history, const unsigned int b)
      {
        return history + n_history + dim * b;
      }

      /** The body index: after the contact data (several bodies only). */
      static constexpr unsigned int
      body(const unsigned int n_history, const unsigned int n_slots)
      {
        return n_properties(n_history, n_slots);
      }

      /** Contact offset against boundary @p b of @p n_slots. */
      static constexpr unsigned int
      contact_offset(const unsigned int n_history,
                     const unsigned int n_slots,
                     const unsigned int b)
      {
        return history + n_history + dim * n_slots + b;
      }

      /**
       * Store the Cauchy stress @p sigma [Pa] in a point's properties in
       * the order xx yy zz xy yz xz (symmetric part of the upper triangle).
       */
      static void
      store_stress(const dealii::ArrayView<double> &props,
                   const dealii::Tensor<2, 3>      &sigma)
      {
        props[stress + 0] = sigma[0][0];
        props[stress + 1] = sigma[1][1];
        props[stress + 2] = sigma[2][2];
        props[stress + 3] = sigma[0][1];
        props[stress + 4] = sigma[1][2];
        props[stress + 5] = sigma[0][2];
      }

      /**
       * Names for output, one per property (history as history_i; "body"
       * last if @p with_body).
       */
      static std::vector<std::string>
      names(const unsigned int n_history,
            const unsigned int n_slots,
            const bool         with_body = false);

      /** Output interpretation (vectors for velocity, ...). */
      static std::vector<
        dealii::DataComponentInterpretation::DataComponentInterpretation>
      interpretation(const unsigned int n_history,
                     const unsigned int n_slots,
                     const bool         with_body = false);
    };


    /**
     * The material points of the soil: a Particles::ParticleHandler on the
     * background grid whose particles carry mass, volume, velocity,
     * acceleration, deformation gradient, stress and the history of the
     * constitutive model (MaterialPointProperties).
     *
     * Bodies are generated from geometry, with n^dim points per background
     * cell placed at the centres of an n^dim subdivision of the cell (never
     * on vertices or faces):
     *  - `box` (2D and 3D): the points of the background cells that lie
     *    inside the box;
     *  - `polygon` (2D): the points inside a closed polygon;
     *  - `gmsh` (2D and 3D): the cells of a Gmsh mesh of the body, each
     *    with n^dim points at the centres of its subcells (volume = JxW).
     *
     * Several bodies: subsection "Body" is body 1 and sets 'number of
     * bodies' N (1 to max_bodies); "Body 2" ... "Body N" describe the
     * others with the same parameters. Each body names its material
     * subsection ("Material", "Material 2", ...). The points of all bodies
     * share one background grid and one grid velocity field (they stick
     * where they meet, as in standard MPM). Box and polygon bodies must
     * not overlap (a point of a later body inside an earlier box or
     * polygon body is an input error); Gmsh bodies are not checked.
     *
     * Points that leave the grid are removed: the lost mass is recorded by
     * the `particle_lost` signal and reported (or turned into an error).
     */
    template <int dim>
    class MaterialPoints
    {
    public:
      using Properties = MaterialPointProperties<dim>;

      explicit MaterialPoints(const BackgroundGrid<dim> &grid);

      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Largest number of bodies ("Body", "Body 2", ...). */
      static constexpr unsigned int max_bodies = 4;

      /** "Body" for @p index 0, "Body 2" for 1, ... */
      static std::string
      body_subsection(const unsigned int index);

      /**
       * The material subsection index of each body (0: "Material"), with
       * 'number of bodies' and the material names checked.
       */
      static std::vector<unsigned int>
      body_materials(dealii::ParameterHandler &prm);

      /** Parse subsections "Body" (and "Body 2" ... with several). */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * 'points per cell per direction' of subsection "Body" (uGIMP's
       * particle size); throws ExcInvalidInput if the bodies differ in it.
       */
      unsigned int
      points_per_cell_direction() const;

      /**
       * Generate the bodies: positions, masses (density * volume),
       * velocities from the initial-velocity function, F = I, zero stress,
       * history from @p initialize_history. Throws ExcInvalidInput for an
       * empty body or a body outside the grid. All bodies get @p density.
       */
      void
      generate(const double       density,
               const unsigned int n_history,
               const std::function<void(const dealii::ArrayView<double> &)>
                 &initialize_history);

      /**
       * Generate the bodies, each with the density of its material
       * (@p density[m] for material subsection m), @p n_history history
       * variables per point (the largest of the materials) and the
       * history of its material (@p initialize_history(m, history)).
       */
      void
      generate(const std::vector<double> &density,
               const unsigned int         n_history,
               const std::function<void(const unsigned int,
                                        const dealii::ArrayView<double> &)>
                 &initialize_history);

      /** Number of bodies. */
      unsigned int
      n_bodies() const
      {
        return bodies.size();
      }

      /** Index of the material subsection of body @p b (0: "Material"). */
      unsigned int
      body_material(const unsigned int b) const
      {
        return bodies[b].material;
      }

      /** Whether the points carry their body (several bodies). */
      bool
      has_body_property() const
      {
        return bodies.size() > 1;
      }

      /** Index of the body property (has_body_property()). */
      unsigned int
      body_index() const
      {
        return MaterialPointProperties<dim>::body(history_size, contact_slots);
      }

      /** Body of a point with properties @p props (0 with one body). */
      template <class View>
      unsigned int
      body_of(const View &props) const
      {
        return has_body_property() ?
                 static_cast<unsigned int>(props[body_index()] + 0.5) :
                 0;
      }

      /** Material subsection index of a point with properties @p props. */
      template <class View>
      unsigned int
      material_of(const View &props) const
      {
        return bodies[body_of(props)].material;
      }

      /** Number of properties per point. */
      unsigned int
      n_properties() const
      {
        return MaterialPointProperties<dim>::n_properties(history_size,
                                                          contact_slots) +
               (has_body_property() ? 1 : 0);
      }

      dealii::Particles::ParticleHandler<dim> &
      particle_handler();

      const dealii::Particles::ParticleHandler<dim> &
      particle_handler() const;

      /** Total number of material points (all ranks). */
      dealii::types::particle_index
      n_global_points() const;

      /** Mass lost through the grid boundary since the last call (global). */
      double
      take_lost_mass();

      /** Number of points lost since the last call (global). */
      unsigned int
      take_lost_count();

      /**
       * Number of points lost since the last take_lost_count() (global,
       * collective), without resetting the count: whether a trial commit
       * lost points (EnergyJumpMonitor::is_jump()).
       */
      unsigned int
      count_lost() const;

      /**
       * Bounding box of the positions (outside the grid) of the points lost
       * since the last call (global); empty when none was lost. Called with
       * take_lost_count() so that a report can say where points left.
       */
      std::pair<dealii::Point<dim>, dealii::Point<dim>>
      take_lost_region();

      /** Keep a copy of all points (state of the last accepted step). */
      void
      save_state();

      /** Restore the copy made by save_state(). */
      void
      restore_state();

      /** Number of history variables per point. */
      unsigned int
      n_history() const;

      /**
       * Reserve contact data (gap and offset, MaterialPointProperties) for
       * @p n boundaries (one slot per boundary of BoundaryParticles; there
       * is no fixed limit). Call before generate().
       */
      void
      set_contact_slots(const unsigned int n)
      {
        contact_slots = n;
      }

      /** Number of boundaries with contact data per point. */
      unsigned int
      n_contact_slots() const
      {
        return contact_slots;
      }

      /** Index of the first component of the contact gap of boundary b. */
      unsigned int
      contact_gap_index(const unsigned int b) const
      {
        return MaterialPointProperties<dim>::contact_gap(history_size, b);
      }

      /** Index of the contact offset of boundary b. */
      unsigned int
      contact_offset_index(const unsigned int b) const
      {
        return MaterialPointProperties<dim>::contact_offset(history_size,
                                                            contact_slots,
                                                            b);
      }

    private:
      /** The geometry of one body (subsection "Body", "Body 2", ...). */
      struct Body
      {
        std::string                     subsection;
        std::string                     geometry;
        dealii::Point<dim>              box_lower;
        dealii::Point<dim>              box_upper;
        std::vector<dealii::Point<dim>> polygon;
        std::string                     mesh_file;
        unsigned int                    points_per_direction = 2;
        /** Clip the points' sub-cells to a box or polygon body. */
        bool clip_to_body = false;
        std::unique_ptr<dealii::Functions::ParsedFunction<dim>>
                     initial_velocity;
        unsigned int material = 0;

        /**
         * Whether @p p lies inside a box or polygon body, more than
         * @p tolerance from its boundary (box) (false for Gmsh bodies).
         */
        bool
        contains(const dealii::Point<dim> &p, const double tolerance) const;
      };

      static void
      declare_body(dealii::ParameterHandler &prm, const unsigned int index);

      void
      parse_body(dealii::ParameterHandler &prm, Body &body) const;

      void
      generate_from_background_cells(
        const Body                                            &body,
        const std::function<bool(const dealii::Point<dim> &)> &inside,
        std::vector<dealii::Point<dim>>                       &points,
        std::vector<double>                                   &volumes,
        std::vector<typename dealii::Triangulation<dim>::active_cell_iterator>
                                        &cells,
        std::vector<dealii::Point<dim>> &reference_points) const;

      void
      generate_from_gmsh(const Body                      &body,
                         std::vector<dealii::Point<dim>> &points,
                         std::vector<double>             &volumes) const;

      const BackgroundGrid<dim> &grid;

      dealii::Particles::ParticleHandler<dim> handler;
      dealii::Particles::ParticleHandler<dim> backup;

      std::vector<Body> bodies;
      unsigned int      history_size;
      unsigned int      contact_slots = 0;

      double       lost_mass;
      unsigned int lost_count;
      /** Bounds of the positions of the points lost since the last call. */
      dealii::Point<dim> lost_lower;
      dealii::Point<dim> lost_upper;
    };
  } // namespace MPM
} // namespace Talus

#endif
