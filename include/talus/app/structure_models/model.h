#ifndef talus_app_structure_models_model_h
#define talus_app_structure_models_model_h

#include <talus/structure/barrier_builder.h>
#include <talus/structure/continuum_solid.h>
#include <talus/structure/line_elements.h>
#include <talus/structure/membrane.h>
#include <talus/structure/sliding_cable.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>
#include <talus/structure/structure_problem.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/vector.h>

#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Talus
{
  /**
   * The verification models of the structure application (`set problem =
   * structure`, subsection `Structure`): each is a builder of meshes,
   * supports and loads of a Talus::Structure::Structure with its own
   * closed-form reference (doc/verification.md). One model per file in
   * source/app/structure_models/; create_model() (factory.h) picks the one
   * the file asks for.
   */
  namespace StructureModels
  {
    using Structure     = Talus::Structure::Structure;
    using StructurePart = Talus::Structure::StructurePart;

    /** Name of the parameter subsection of the structure application. */
    inline const std::string structure_section = "Structure";

    /** Find x in [a, b] with f(x) = 0 by bisection (f(a) f(b) <= 0). */
    double
    bisect(const std::function<double(double)> &f, double a, double b);

    /** Entry @p entry of @p subsection (entered) as a vector x, y, z. */
    dealii::Tensor<1, 3>
    get_vector(dealii::ParameterHandler &prm,
               const std::string        &subsection,
               const std::string        &entry);


    /** Everything read from subsection Structure. */
    struct Parameters
    {
      std::string model;
      /** The model as written in the file ('plane cantilever'); model
       * holds the name without 'plane ' for the plane-strain solids. */
      std::string model_text;
      /** A 'plane' solid model: Triangulation<2,2> in the x-y plane. */
      bool        plane_solid = false;
      std::string solid_traction_text; ///< as written, for messages
      // Line members.
      std::string  line_element;
      double       E = 0., A = 0., prestress = 0., density = 0.;
      double       yield_stress = 0., hardening = 0.;
      unsigned int elements    = 1;
      double       slack_ratio = 1e-8;
      /** Axial law of cables, sliding cables and trusses. */
      Talus::Structure::StrainMeasure strain_measure =
        Talus::Structure::StrainMeasure::green_lagrange;
      // Membrane.
      double membrane_E = 0., membrane_nu = 0., membrane_E2 = 0.,
             membrane_G = 0., thickness = 0., membrane_density = 0.;
      bool                 orthotropic = false, wrinkling = false;
      dealii::Tensor<1, 3> membrane_prestress;
      double               initial_deflection = 0.;
      // Brake.
      double brake_k = 0., brake_Fa = 0., brake_H = 0., brake_smax = 0.,
             brake_length = 0.;
      // Geometry.
      double half_span = 0., rise = 0., span = 0., unstretched_length = 0.,
             radius = 0., side = 0., cable_length = 0.;
      /** Centre of the models placed in space ('plane string') [m]. */
      dealii::Tensor<1, 3> origin;
      unsigned int         refinements = 0;
      std::string          mesh_file;
      // Loads.
      dealii::Tensor<1, 3> gravity, point_load;
      double               pressure = 0., prescribed_displacement = 0.;
      std::vector<double>  load_path;
      // Output and verification.
      std::string directory;
      bool        write_vtu = false, test_mode = false;
      double      tolerance = 0., reference_displacement = 0.;
      /** Model 'cantilever' in time: length of the end region whose mean
       * deflection is monitored (0: the last column of cells) [m]. */
      double tip_region_length = 0.;
      bool   dynamic           = false;
      double bossak_alpha = 0., dynamic_time_step = 0., string_amplitude = 0.;
      bool   mesh_is_membrane = false;
      double mass_damping = 0., stiffness_damping = 0.;
      bool   arc_length_control = false;
      double shear_strain       = 0.;
      /** Model 'stretched membrane': engineering strains along x, y. */
      double stretch_x = 0., stretch_y = 0.;
      bool   uniaxial_stress = false;
      double friction = 0., wrap_angle = 180., drum_radius = 0.5;
      bool   stick_slip = false;
      double spring_EA = 0., spring_length = 1.;
      Talus::Structure::BarrierBuilder barrier;
      /** Model 'plane barrier' (subsection Plane barrier): points in the
       * plane of the 2D problem (z = 0) [m], axial stiffnesses [N] and
       * masses [kg/m] per metre of barrier width. */
      dealii::Tensor<1, 3> post_base, post_top, net_bottom, rope_anchor;
      double post_EA = 0., post_mass = 0., rope_EA = 0., rope_mass = 0.,
             rope_pretension = 0.;
      /** Axial law of the post and the retaining rope ('strain measure' of
       * subsection Plane barrier; the net follows Line members). */
      Talus::Structure::StrainMeasure member_strain_measure =
        Talus::Structure::StrainMeasure::green_lagrange;
      // Continuum solid.
      Talus::Structure::ContinuumSolid<3> solid;
      Talus::Structure::SolidGeometry     solid_geometry;
      double                              mode_amplitude = 0.;
      unsigned int                        n_levels = 1, first_level = 0;
      double                              minimum_rate = 0.;
    };


    /** A computed quantity and its closed-form value. */
    struct Result
    {
      std::string name;
      double      computed  = 0.;
      double      reference = 0.;
      bool        checked   = true; ///< counts for the tolerance
      /** The computed value is itself a relative error (reference 0). */
      bool is_error = false;
      /** Tolerance of this result; 0: the file's 'tolerance'. */
      double tolerance = 0.;
      double
      error() const
      {
        if (is_error)
          return std::abs(computed);
        return std::abs(computed - reference) /
               std::max(std::abs(reference), 1e-300);
      }
    };


    /**
     * A structural model built from the parameters, with its closed-form
     * reference. build() creates the meshes, supports and loads of the
     * given refinement level.
     */
    class Model : public Talus::Structure::StructureBuilder
    {
    public:
      explicit Model(const Parameters &p)
        : p(p)
      {}
      virtual ~Model() = default;

      void
      build(Structure &s, const unsigned int level) override = 0;

      /** Start of Newton (e.g. a bulge for a flat, unstressed membrane). */
      void
      initial_guess(const Structure &, dealii::Vector<double> &) const override
      {}

      /** Extra load factors to visit (inserted into the load path). */
      virtual std::vector<double>
      extra_load_factors() const
      {
        return {};
      }

      /** Values written to the CSV (and checked) after every step. */
      virtual std::vector<std::pair<std::string, double>>
      monitor(const Structure &, const dealii::Vector<double> &, double)
      {
        return {};
      }

      /**
       * What a barrier engineer reads off a coupled run, written by
       * IO::StructureTimeSeries into structure.csv after every step besides
       * the per-mesh columns: e.g. the impact force per field, the post
       * forces and rotations, the force at every anchor, the net's
       * deflection and residual height. @p u: committed displacement,
       * @p interface_forces: the material's nodal forces on the structure
       * [N] (per global DoF). The names must not change between calls.
       */
      virtual std::vector<std::pair<std::string, double>>
      impact_columns(const Structure &,
                     const dealii::Vector<double> &,
                     const dealii::Vector<double> &) const
      {
        return {};
      }

      /** Results compared with the closed form at the end. */
      virtual std::vector<Result>
      results(const Structure &s, const dealii::Vector<double> &u) = 0;

      /**
       * The parameter that decides how the model is held (subsection,
       * entry, value), named when a part of the structure is connected
       * to no support.
       */
      virtual std::array<std::string, 3>
      support_parameter() const
      {
        return {{structure_section, "model", p.model_text}};
      }

      /** Solve the pre-stress equilibrium (lambda = 0) first. */
      virtual bool
      prestress_step() const
      {
        return p.prestress != 0. || p.membrane_prestress.norm() != 0.;
      }

      virtual std::string
      description() const = 0;

      /** The model can run with 'dynamic = true'. */
      virtual bool
      supports_dynamics() const
      {
        return false;
      }

      /** After a dynamic run: solve the static equilibrium from its end
       * state (dynamic relaxation: damped motion to rest, then Newton). */
      virtual bool
      relax_to_equilibrium() const
      {
        return false;
      }

      /**
       * Called once before the load steps (after the pre-stress step):
       * e.g. staged form finding. Returns false if it failed.
       */
      virtual void
      before_load_steps(Structure &, Talus::Structure::StaticSolver &)
      {}

      /** Set by the time loop before monitor(): time [s], total
       * energy (kinetic + strain + load potential) and kinetic energy
       * [J]. */
      double time = 0., total_energy = 0., kinetic_energy = 0.;

      /** With 'dynamic = true': find the pre-stressed equilibrium
       * (load factor 0 and before_load_steps()) before the motion. */
      virtual bool
      form_finding_before_dynamics() const
      {
        return false;
      }

    protected:
      const Parameters &p;

      /** The line parameters every line element shares. */
      template <typename Element>
      std::shared_ptr<Element>
      line_parameters() const
      {
        auto e                   = std::make_shared<Element>();
        e->youngs_modulus        = p.E;
        e->area                  = p.A;
        e->prestress             = p.prestress;
        e->density               = p.density;
        e->slack_stiffness_ratio = p.slack_ratio;
        e->strain_measure        = p.strain_measure;
        return e;
      }

      std::shared_ptr<Talus::Structure::LineElement>
      line_element() const
      {
        if (p.line_element == "cable")
          return line_parameters<Talus::Structure::Cable>();
        auto t          = line_parameters<Talus::Structure::Truss>();
        t->yield_stress = p.yield_stress;
        t->hardening    = p.hardening;
        return t;
      }

      /** A brake of subsection Brake. */
      std::shared_ptr<Talus::Structure::Brake>
      brake_element() const
      {
        auto brake              = std::make_shared<Talus::Structure::Brake>();
        brake->stiffness        = p.brake_k;
        brake->activation_force = p.brake_Fa;
        brake->hardening        = p.brake_H;
        brake->stroke_limit     = p.brake_smax;
        brake->slack_stiffness_ratio = p.slack_ratio;
        return brake;
      }

      /** A sliding cable with the line parameters of the file. */
      std::shared_ptr<Talus::Structure::SlidingCable>
      sliding_cable() const
      {
        return line_parameters<Talus::Structure::SlidingCable>();
      }

      std::shared_ptr<Talus::Structure::Membrane>
      membrane() const
      {
        auto m                = std::make_shared<Talus::Structure::Membrane>();
        m->material.thickness = p.thickness;
        m->material.set_isotropic(p.membrane_E, p.membrane_nu);
        if (p.orthotropic)
          {
            m->material.youngs_modulus_2 = p.membrane_E2;
            m->material.shear_modulus    = p.membrane_G;
          }
        m->material.prestress = p.membrane_prestress;
        m->material.wrinkling = p.wrinkling;
        m->density            = p.membrane_density;
        m->pressure           = p.pressure;
        return m;
      }

      unsigned int
      node_at(const Structure &s, const dealii::Point<3> &x) const
      {
        const unsigned int n = s.find_node(x, 1e-9 * (1. + x.norm()));
        AssertThrow(n != dealii::numbers::invalid_unsigned_int,
                    dealii::ExcMessage("internal: no node at a model point"));
        return n;
      }
    };


    /** A straight line mesh from a to b with n cells (in space, or in
     * the plane of a 2D problem). */
    template <int spacedim>
    void
    make_line(dealii::Triangulation<1, spacedim> &tria,
              const dealii::Point<spacedim>      &a,
              const dealii::Point<spacedim>      &b,
              const unsigned int                  n);

    /** A line mesh through the points @p x in this order. */
    void
    make_polyline(dealii::Triangulation<1, 3>         &tria,
                  const std::vector<dealii::Point<3>> &x);

    /** A disk or square membrane mesh (flattened from a 2D mesh). */
    void
    make_flat_mesh(dealii::Triangulation<2, 3> &tria,
                   const bool                   disk,
                   const double                 size,
                   const unsigned int           refinements);

    /**
     * Columns of the CSV common to all models: the stored elastic energy,
     * the largest axial force of every line mesh (the tension of a sliding
     * cable), and for brakes the largest stroke and the dissipated energy.
     */
    std::vector<std::pair<std::string, double>>
    structure_columns(const Structure &s);

    /** Read subsection Structure (declared by declare_parameters()). */
    Parameters
    parse_parameters(dealii::ParameterHandler &prm);

    /** Declare subsection Structure and everything in it. */
    void
    declare_parameters(dealii::ParameterHandler &prm);
  } // namespace StructureModels
} // namespace Talus

#endif
