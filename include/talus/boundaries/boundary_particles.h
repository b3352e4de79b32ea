#ifndef talus_boundaries_boundary_particles_h
#define talus_boundaries_boundary_particles_h

#include <talus/mpm/background_grid.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>

#include <deal.II/particles/particle_handler.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  /**
   * Boundaries that do not follow the background grid (terrain, walls and,
   * later, the protective net), imposed weakly on boundary particles.
   */
  namespace Boundaries
  {
    /** How a boundary constrains the material (per boundary). */
    enum class Condition
    {
      fixed,   ///< u = u_bar (all components)
      slip,    ///< (u - u_bar) . n = 0, tangential motion free
      contact, ///< (u - u_bar) . n >= 0, released on separation
      friction ///< contact with Coulomb friction, stick or slip
    };

    /**
     * Layout of the properties of one boundary particle in the
     * Particles::ParticleHandler of BoundaryParticles.
     */
    template <int dim>
    struct BoundaryParticleProperties
    {
      /** Index of the boundary the particle belongs to. */
      static constexpr unsigned int boundary = 0;
      /** Surface measure the particle represents [m in 2D, m^2 in 3D]. */
      static constexpr unsigned int weight = 1;
      /** Unit normal, pointing from the boundary into the material. */
      static constexpr unsigned int normal = 2;
      /** Position of the particle in the undisplaced boundary [m]. */
      static constexpr unsigned int reference_position = normal + dim;
      /**
       * Accumulated relative displacement of the material against the
       * boundary carried by the penalty spring [m] (its normal part is the
       * penetration when negative).
       */
      static constexpr unsigned int gap = reference_position + dim;
      /** Force the material exerts on the boundary at this particle [N]. */
      static constexpr unsigned int reaction = gap + dim;
      /** 0 inactive (no material in the cell or separated), 1 stick or
       * bonded, 2 slip. */
      static constexpr unsigned int state = reaction + dim;
      /**
       * Lagrange multiplier of an 'augmented Lagrangian' boundary: the
       * force of the boundary on the material at this particle at the end
       * of the last step [N] (zero for 'penalty').
       */
      static constexpr unsigned int multiplier   = state + 1;
      static constexpr unsigned int n_properties = multiplier + dim;
    };

    /** Data of one boundary as read from the parameter file. */
    template <int dim>
    struct BoundaryDescription
    {
      std::string name;
      /** Index k of its subsection `Boundary k+1`. */
      unsigned int slot = 0;
      std::string  geometry;
      Condition    condition = Condition::fixed;
      std::string  method    = "penalty";
      /**
       * Impose the condition with Lagrange multipliers iterated by Uzawa
       * updates on top of the penalty spring (method = augmented
       * Lagrangian): the constraint then holds to a tolerance that does
       * not depend on the penalty value.
       */
      bool augmented = false;
      /**
       * Impose the condition by Nitsche's method (method = Nitsche): the
       * penalty spring plus the material's traction at the boundary and,
       * with weight nitsche_theta, the symmetry term.
       */
      /**
       * Impose the condition with Lagrange multipliers that are unknowns of
       * the Newton iteration (method = Lagrange multiplier): the
       * Alart-Curnier mixed form, r_u = f_int - f_ext - N^T f(lambda, u),
       * (lambda - f(lambda, u)) / k = 0 with the projected trial force
       * f = P(lambda - k g); each linear system is the saddle-point system
       * in (du, dlambda), solved through its Schur complement. The
       * constraint holds to the Newton tolerance whatever k.
       */
      bool lagrange_multiplier = false;
      /**
       * Contact on the material side (contact side = material points): the
       * contact condition is checked at the lowest point of every material
       * point's extent against the boundary's surface (given by its
       * nearest boundary particle), with a geometric gap, instead of at the
       * boundary particles on an accumulated gap (see MPM::MPMSolver).
       */
      bool material_point_contact = false;
      /**
       * Material-point contact: whether the contact point x_c = x_p - r n
       * moves with the material point (r = r_0 from the point's initial
       * volume, the increment that of x_p: the gap a step starts from is
       * the one the last step ended with), or with the increment
       * interpolated at x_c and r from the current volume (the gap is
       * measured again from the point's position at every step).
       */
      bool contact_point_with_point = false;
      /** 'contact point motion = default' (the choice then follows the
       * boundary: at rest, moving, an end-of-step coupling interface). */
      bool contact_point_motion_default = true;
      /**
       * Normal dashpot of material-point contact relative to the spring,
       * eta: the force on a pressed point is k (-g_n - eta s (g_n -
       * g_n,old)) with s = min(1, penetration / (0.01 h)) (a Kelvin-Voigt
       * contact; 0: the elastic penalty spring alone).
       */
      double       contact_damping      = 0.;
      bool         nitsche              = false;
      double       nitsche_theta        = -1.;
      double       friction_coefficient = 0.;
      double       penalty_factor       = 100.;
      double       penalty_parameter    = 0.; ///< [Pa/m], 0: automatic
      unsigned int particles_per_cell   = 2;
      /**
       * Constrain the gap per particle, or its weighted mean per cell
       * (one constraint per background cell and boundary: the penalty
       * limit of cell-wise constant Lagrange multipliers).
       */
      bool                            cellwise = false;
      std::vector<dealii::Point<dim>> vertices;
      dealii::Point<dim>              center;
      double                          radius = 0.;
      dealii::Point<dim>              lower_corner, upper_corner;
      bool                            material_inside = true;
      bool                            flip_normals    = false;
      std::string                     mesh_file;
      /**
       * Surface handed over by the program (geometry = external), e.g.
       * the coupled structure's mesh: a flattened copy of its active cells
       * (BoundaryParticles::set_surface()).
       */
      std::shared_ptr<const dealii::Triangulation<dim - 1, dim>>
                                                              external_surface;
      std::unique_ptr<dealii::Functions::ParsedFunction<dim>> displacement;
      /**
       * Displacement set from outside (the coupling), u(X, t) [m]; when
       * set it replaces the parsed function.
       */
      std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &,
                                           const double)>
           external_displacement;
      bool moving = false;
      /**
       * A coupling interface whose unilateral contact force acts with its
       * end value over the step, as that of boundaries at rest with
       * 'contact force in time = end of step' (MPM::ContactTimeIntegration;
       * set by the coupling: 'interface force in time' in subsection
       * Coupling). Default: the trapezoidal rule of moving boundaries.
       */
      bool end_of_step_force = false;
      /** Penalty parameter used (automatic or given) [Pa/m]. */
      double beta = 0.;
    };

    /** Resultants of one boundary at the end of a step. */
    template <int dim>
    struct BoundaryResultant
    {
      dealii::Tensor<1, dim> force;                 ///< sum of reactions [N]
      double                 normal_force     = 0.; ///< sum of R . n [N]
      double                 tangential_force = 0.; ///< |sum R_t| [N]
      double                 penetration      = 0.; ///< max of -g . n [m]
      unsigned int           active           = 0;  ///< particles in contact
      /**
       * Elastic energy stored in the penalty springs of the pressed
       * particles and points, sum of beta w |g|^2 / 2 over them [J] (part of
       * the energy of the system: a penalty contact is a stiff spring).
       */
      double spring_energy = 0.;

      /** Read or write with a boost archive (checkpoints). */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int /*version*/)
      {
        ar &force &normal_force &tangential_force &penetration &active;
        ar                                                     &spring_energy;
      }
    };

    /**
     * The particles of one boundary as every rank sees them after
     * BoundaryParticles::gather_surface(): current positions x, unit normals
     * n into the material, reference positions X and particle ids.
     */
    template <int dim>
    struct GatheredSurface
    {
      std::vector<dealii::Point<dim>>            x;
      std::vector<dealii::Tensor<1, dim>>        n;
      std::vector<dealii::Point<dim>>            X;
      std::vector<dealii::types::particle_index> id;
    };

    /**
     * The boundary particles: a second Particles::ParticleHandler on the
     * background grid whose particles carry the geometry and the data of
     * boundaries that do not follow the grid (after Chandra et al. 2021,
     * "Nonconforming Dirichlet boundary conditions in implicit material
     * point method by means of penalty augmentation", Acta Geotech. 16, and
     * Singer et al., the founding paper, section 3).
     *
     * Every boundary is first described as a codimension-one
     * Triangulation<dim-1, dim> (a line or polyline, a circle, a
     * rectangle, the surface of a box, or a surface mesh read from a file),
     * refined until its cells are no larger than the smallest background
     * cell; the particles are the Gauss points of that mesh
     * (particles per cell per direction), weighted with their surface
     * measure JxW and carrying the unit normal that points into the
     * material (as deal.II step-70 makes particles from an immersed mesh).
     * A boundary may move with a prescribed displacement u_bar(X, t)
     * (muparser); the particle then sits at X + u_bar(X, t) during the
     * step that starts at t, and the gap grows with the relative
     * increment du - du_bar.
     *
     * The conditions are imposed by MPM::MPMSolver (see there and
     * doc/theory.md): the penalty term adds to the residual the force
     * f = -beta w g of a spring on the accumulated gap g (the relative
     * displacement of the material against the boundary since the
     * particle came into contact), restricted to the normal for slip and
     * contact, with a Coulomb return for friction. With method =
     * augmented Lagrangian a multiplier lambda (a force per particle) is
     * added, f = lambda - beta w g, and updated after each converged Newton
     * solve, lambda <- f (Uzawa), until the gap is below a tolerance
     * (Simo and Laursen 1992, Comput. Struct. 42; the same active-set and
     * Coulomb logic acts on the trial force).
     */
    template <int dim>
    class BoundaryParticles
    {
    public:
      /**
       * Number of boundary subsections (`Boundary 1`, `Boundary 2`, ...)
       * declared when the parameter file does not ask for more (and
       * documented by --print-parameters). There is no upper limit: see
       * n_boundaries_in_file().
       */
      static constexpr unsigned int default_boundary_slots = 4;

      /**
       * The largest N of a line `subsection Boundary N` in the parameter
       * file @p filename, and at least default_boundary_slots: the number
       * of boundary subsections to declare for it.
       */
      static unsigned int
      n_boundaries_in_file(const std::string &filename);

      explicit BoundaryParticles(const MPM::BackgroundGrid<dim> &grid);

      static void
      declare_parameters(dealii::ParameterHandler &prm,
                         const unsigned int n_slots = default_boundary_slots);

      /** Parse subsection "Boundary particles". */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Make the particles of every boundary and insert them into the
       * grid; @p p_wave_modulus [Pa] scales the automatic penalty
       * beta = factor * M / h.
       */
      void
      generate(const double p_wave_modulus);

      /** Whether any boundary is described. */
      bool
      empty() const
      {
        return boundaries.empty();
      }

      unsigned int
      n_boundaries() const
      {
        return boundaries.size();
      }

      const BoundaryDescription<dim> &
      boundary(const unsigned int b) const
      {
        return boundaries[b];
      }

      /** Whether any boundary uses the augmented Lagrangian method. */
      bool
      any_augmented() const
      {
        for (const auto &b : boundaries)
          if (b.augmented)
            return true;
        return false;
      }

      /** Whether any boundary uses the monolithic Lagrange multipliers. */
      bool
      any_lagrange_multiplier() const
      {
        for (const auto &b : boundaries)
          if (b.lagrange_multiplier)
            return true;
        return false;
      }

      /**
       * Largest gap an augmented Lagrangian boundary may keep at the end of
       * a step [m] ('multiplier tolerance' times the smallest cell size).
       */
      double
      multiplier_tolerance() const
      {
        return gap_tolerance;
      }

      /** Most multiplier (Uzawa) updates in one step. */
      unsigned int
      max_multiplier_updates() const
      {
        return max_updates;
      }

      /** Prescribed displacement of boundary @p b at @p X and time @p t. */
      dealii::Tensor<1, dim>
      prescribed_displacement(const unsigned int        b,
                              const dealii::Point<dim> &X,
                              const double              t) const;

      /**
       * Let boundary @p b move with the displacement @p u(X, t) [m] given
       * from outside, e.g. by a partitioned coupling that sets the
       * structure's displacement before every coupling iteration of a
       * step. It replaces the parsed 'Displacement' function. The MPM
       * solver reads it in MPMSolver::prepare_step() (at the start and the
       * end time of the step), so a coupling iteration is: set the
       * function, prepare_step(), solve_step(); the converged iteration is
       * committed with commit_step(), which moves the particles to
       * X + u(X, t_{n+1}). u must be continuous in time and give the
       * committed position at the start of the step.
       */
      void
      set_displacement(
        const unsigned int                                         b,
        const std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &,
                                                   const double)> &u);

      /**
       * Give boundary @p b (geometry = external in the parameter file) its
       * surface: a codimension-one mesh of the program, e.g. the coupled
       * structure's membrane (a serial or parallel::shared
       * Triangulation<dim-1, dim>, possibly refined). Its active cells are
       * copied into a coarse mesh (GridGenerator::flatten_triangulation),
       * which generate() checks for consistent normals like a read 'mesh',
       * refines to the grid's cell size and fills with particles at its
       * Gauss points (as deal.II step-70 does for an immersed solid). The
       * normals follow deal.II's orientation of the cells and must point
       * into the material ('flip normals' reverses them). Call it before
       * generate(); the displacement of the surface then comes from
       * set_displacement().
       */
      void
      set_surface(const unsigned int                         b,
                  const dealii::Triangulation<dim - 1, dim> &surface);

      /**
       * Let the contact force of the moving boundary @p b act with its end
       * value over the step (BoundaryDescription::end_of_step_force). Call
       * it before the MPM solver is set up; the solver checks that the
       * boundary's condition and method allow it. With 'contact point
       * motion = default' the contact point then moves with the material
       * point: the end-of-step force books the change of the springs'
       * energy from the gap the step starts from, which must be the one
       * the last step ended with.
       */
      void
      set_end_of_step_force(const unsigned int b);

      /**
       * Move the particles of moving boundaries to X + u_bar(X, t) and sort
       * them into cells (particles that leave the grid are counted).
       */
      void
      move_to(const double t);

      dealii::Particles::ParticleHandler<dim> &
      particle_handler()
      {
        return handler;
      }

      const dealii::Particles::ParticleHandler<dim> &
      particle_handler() const
      {
        return handler;
      }

      /**
       * Sum the reactions per boundary (all ranks): those of the boundary
       * particles and those recorded by record_point_contact().
       */
      std::vector<BoundaryResultant<dim>>
      resultants() const;

      /**
       * Forget the reactions of material-point contact (contact side =
       * material points) recorded for the last step on this rank.
       */
      void
      clear_point_contact();

      /**
       * Record the force @p reaction [N] that one material point in contact
       * exerts on boundary @p b, the boundary's normal @p normal there and
       * the point's penetration [m] and the energy of its penalty spring
       * [J] (this rank; resultants() sums).
       */
      void
      record_point_contact(const unsigned int            b,
                           const dealii::Tensor<1, dim> &reaction,
                           const dealii::Tensor<1, dim> &normal,
                           const double                  penetration,
                           const double                  spring_energy = 0.);

      /** Boundary particles that left the grid so far (this rank). */
      unsigned int
      n_lost() const
      {
        return lost;
      }

      /**
       * The number of boundary particles of every boundary that left the
       * background grid since the last call, summed over all ranks
       * (collective). A moving boundary that carries its particles out of the
       * grid loses them for good: that part of the boundary no longer acts.
       */
      std::vector<unsigned int>
      take_lost_per_boundary();

      /**
       * The particles of boundary @p b from all ranks (collective): its
       * surface as a point cloud, e.g. for the nearest particle to a
       * material point.
       */
      GatheredSurface<dim>
      gather_surface(const unsigned int b) const;

      /** The name of boundary @p b (as in the parameter file). */
      const std::string &
      name(const unsigned int b) const
      {
        return boundaries[b].name;
      }

      /**
       * Keep a copy of the particles (positions, gaps, reactions, states,
       * multipliers) and of the loss counters: the state of the last
       * committed step.
       */
      void
      save_state();

      /** Go back to the copy of the last save_state(). */
      void
      restore_state();

    private:
      /** The codimension-one mesh of boundary @p b (refined). */
      void
      make_surface(const BoundaryDescription<dim>      &b,
                   const unsigned int                   index,
                   dealii::Triangulation<dim - 1, dim> &surface) const;

      /** @p x moved off the faces of a Cartesian grid along @p n. */
      dealii::Point<dim>
      off_faces(const dealii::Point<dim>     &x,
                const dealii::Tensor<1, dim> &n) const;

      /** Orient the normal of boundary @p b at @p x into the material. */
      dealii::Tensor<1, dim>
      orient(const BoundaryDescription<dim> &b,
             const dealii::Point<dim>       &x,
             const dealii::Tensor<1, dim>   &n) const;

      const MPM::BackgroundGrid<dim>         &grid;
      dealii::Particles::ParticleHandler<dim> handler;
      /** The copy of save_state(). */
      dealii::Particles::ParticleHandler<dim> backup;
      unsigned int                            backup_lost = 0;
      std::vector<unsigned int>               backup_lost_per_boundary;
      bool                                    saved = false;
      std::vector<BoundaryDescription<dim>>   boundaries;
      unsigned int                            lost                   = 0;
      double                                  relative_gap_tolerance = 1e-5;
      double                                  gap_tolerance          = 0.;
      unsigned int                            max_updates            = 20;
      /** Lost since the last take_lost_per_boundary(), per boundary. */
      std::vector<unsigned int> lost_per_boundary;
      /** Material-point contact of the last step on this rank, per boundary. */
      std::vector<BoundaryResultant<dim>> point_contact;
      std::vector<dealii::Tensor<1, dim>> point_contact_tangential;
    };
  } // namespace Boundaries
} // namespace Talus

#endif
