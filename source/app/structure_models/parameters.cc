// Parameters of the structure application: subsection Structure.

#include <talus/app/simulation.h>
#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/base/input.h>
#include <talus/structure/barrier_builder.h>
#include <talus/structure/continuum_solid.h>
#include <talus/structure/dynamic_solver.h>
#include <talus/structure/mesh_input.h>
#include <talus/structure/plane_string.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_values.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

namespace Talus
{
  namespace StructureModels
  {
    using namespace dealii;


    Parameters
    parse_parameters(ParameterHandler &prm)
    {
      Parameters p;
      prm.enter_subsection(structure_section);
      p.model      = prm.get("model");
      p.model_text = p.model;
      for (const std::string base :
           {"solid", "cantilever", "axial bar", "hanging block"})
        if (p.model == "plane " + base)
          {
            p.plane_solid = true;
            p.model       = base;
          }

      const std::string lm = structure_section + "/Line members";
      prm.enter_subsection("Line members");
      p.line_element = prm.get("element");
      p.E            = get_positive(prm, lm, "Young's modulus");
      p.A            = get_positive(prm, lm, "cross-section area");
      p.prestress    = prm.get_double("prestress");
      p.density      = get_non_negative(prm, lm, "density");
      p.yield_stress = get_non_negative(prm, lm, "yield stress");
      p.hardening    = get_non_negative(prm, lm, "hardening modulus");
      p.elements     = prm.get_integer("elements per member");
      if (p.elements < 1)
        InputFile::reject(lm,
                          "elements per member",
                          prm.get("elements per member"),
                          "a member needs at least one element (two nodes)");
      p.slack_ratio = get_positive(prm, lm, "slack stiffness ratio");
      p.strain_measure =
        Talus::Structure::strain_measure_from_string(prm.get("strain measure"));
      if (p.strain_measure == Talus::Structure::StrainMeasure::engineering &&
          !(p.prestress > -p.E))
        InputFile::reject(lm,
                          "prestress",
                          prm.get("prestress"),
                          "with 'strain measure = engineering' the "
                          "unstretched length L/(1 + prestress/E) must be "
                          "positive: prestress > -E");
      p.friction   = get_non_negative(prm, lm, "friction coefficient");
      p.stick_slip = prm.get("friction law") == "stick-slip";
      if (p.stick_slip && !(p.friction > 0.))
        InputFile::reject(lm,
                          "friction law",
                          "stick-slip",
                          "the stick-slip law needs a 'friction coefficient' "
                          "> 0 (without friction a sliding cable has no "
                          "stick)");
      prm.leave_subsection();

      const std::string ms = structure_section + "/Membrane";
      prm.enter_subsection("Membrane");
      p.membrane_E = get_positive(prm, ms, "Young's modulus");
      // plane stress: nu = 0.5 (an incompressible sheet) is allowed
      p.membrane_nu = prm.get_double("Poisson's ratio");
      if (!(p.membrane_nu > -1. && p.membrane_nu <= 0.5))
        InputFile::reject(ms,
                          "Poisson's ratio",
                          prm.get("Poisson's ratio"),
                          "it must lie in (-1, 0.5] (plane stress: 0.5 is an "
                          "incompressible sheet)");
      p.orthotropic = prm.get_bool("orthotropic");
      if (p.orthotropic)
        {
          p.membrane_E2 = get_positive(prm, ms, "Young's modulus 2");
          p.membrane_G  = get_positive(prm, ms, "shear modulus");
        }
      p.thickness          = get_positive(prm, ms, "thickness");
      p.mode_amplitude     = prm.get_double("initial mode amplitude");
      p.membrane_density   = get_non_negative(prm, ms, "density");
      p.membrane_prestress = get_vector(prm, ms, "prestress");
      p.wrinkling          = prm.get_bool("wrinkling");
      p.initial_deflection = prm.get_double("initial deflection");
      p.shear_strain       = prm.get_double("shear strain");
      {
        const auto e = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("stretch")));
        p.stretch_x = e[0];
        p.stretch_y = e[1];
      }
      p.uniaxial_stress = prm.get_bool("uniaxial stress");
      prm.leave_subsection();

      const std::string bs = structure_section + "/Brake";
      prm.enter_subsection("Brake");
      p.brake_k      = get_positive(prm, bs, "stiffness");
      p.brake_Fa     = get_positive(prm, bs, "activation force");
      p.brake_H      = get_non_negative(prm, bs, "hardening");
      p.brake_smax   = get_non_negative(prm, bs, "stroke limit");
      p.brake_length = get_positive(prm, bs, "length");
      prm.leave_subsection();

      const std::string solid_s = structure_section + "/Solid";
      prm.enter_subsection("Solid");
      p.solid.parse_parameters(prm, solid_s);
      p.solid_geometry.parse_parameters(prm, solid_s);
      p.solid_traction_text = prm.get("traction");
      prm.leave_subsection();
      if ((p.model == "cantilever" || p.model == "hanging block" ||
           p.model == "axial bar") &&
          !p.solid_geometry.mesh_file.empty())
        InputFile::reject(solid_s,
                          "mesh file",
                          p.solid_geometry.mesh_file,
                          "models 'cantilever', 'hanging block' and "
                          "'axial bar' generate their box (leave 'mesh "
                          "file' empty)");

      {
        const std::string ps = structure_section + "/Plane barrier";
        prm.enter_subsection("Plane barrier");
        const auto point = [&](const std::string &entry) {
          const auto v = Utilities::string_to_double(
            Utilities::split_string_list(prm.get(entry)));
          if (v.size() != 2)
            InputFile::reject(ps,
                              entry,
                              prm.get(entry),
                              "it must have two components x, y (a point "
                              "of the 2D problem)");
          return Tensor<1, 3>({v[0], v[1], 0.});
        };
        p.post_base             = point("post base");
        p.post_top              = point("post top");
        p.net_bottom            = point("net bottom");
        p.rope_anchor           = point("rope anchor");
        p.post_EA               = get_positive(prm, ps, "post EA");
        p.post_mass             = get_non_negative(prm, ps, "post mass");
        p.rope_EA               = get_positive(prm, ps, "rope EA");
        p.rope_mass             = get_non_negative(prm, ps, "rope mass");
        p.rope_pretension       = get_non_negative(prm, ps, "rope pretension");
        p.member_strain_measure = Talus::Structure::strain_measure_from_string(
          prm.get("strain measure"));
        if (p.model == "plane barrier")
          {
            const Tensor<1, 3> post = p.post_top - p.post_base,
                               net  = p.post_top - p.net_bottom,
                               rope = p.post_top - p.rope_anchor;
            if (!(post.norm() > 0.) || !(net.norm() > 0.) ||
                !(rope.norm() > 0.))
              InputFile::reject(ps,
                                "post top",
                                prm.get("post top"),
                                "the post, the net and the rope must have a "
                                "length (post top differs from post base, "
                                "net bottom and rope anchor)");
            if (!(p.brake_length < rope.norm()))
              InputFile::reject(structure_section + "/Brake",
                                "length",
                                std::to_string(p.brake_length),
                                "the brake is the last piece of the "
                                "retaining rope: it must be shorter than the "
                                "rope from the post top to the rope anchor (" +
                                  std::to_string(rope.norm()) + " m)");
            // The post head is held by three members: the net has to pull
            // it downstream (away from the rope), or the post and the net
            // are a mechanism.
            const double cross_post_net = post[0] * net[1] - post[1] * net[0];
            if (std::abs(cross_post_net) < 1e-3 * post.norm() * net.norm())
              InputFile::reject(ps,
                                "net bottom",
                                prm.get("net bottom"),
                                "the net must not lie along the post: a "
                                "post hinged at its foot and a net along it "
                                "hold the post head in no direction across "
                                "them. Put the net bottom downstream of the "
                                "post base (the net leaning against the "
                                "retaining rope)");
          }
        prm.leave_subsection();
      }

      const std::string gs = structure_section + "/Geometry";
      prm.enter_subsection("Geometry");
      p.half_span          = get_positive(prm, gs, "half span");
      p.rise               = get_positive(prm, gs, "rise");
      p.span               = get_positive(prm, gs, "span");
      p.unstretched_length = get_positive(prm, gs, "unstretched length");
      p.radius             = get_positive(prm, gs, "radius");
      p.side               = get_positive(prm, gs, "side");
      p.cable_length       = get_positive(prm, gs, "cable length");
      p.spring_EA          = get_non_negative(prm, gs, "spring EA");
      p.string_amplitude   = prm.get_double("string amplitude");
      p.wrap_angle         = prm.get_double("wrap angle");
      p.drum_radius        = get_positive(prm, gs, "drum radius");
      p.spring_length      = get_positive(prm, gs, "spring length");
      p.refinements        = prm.get_integer("refinements");
      p.origin             = get_vector(prm, gs, "origin");
      p.mesh_file          = prm.get("mesh file");
      p.mesh_is_membrane   = prm.get("mesh file type") == "membrane";
      prm.leave_subsection();
      const bool catenary =
        p.model == "catenary" || p.model == "plane catenary";
      if (catenary && !(p.unstretched_length > p.span))
        InputFile::reject(gs,
                          "unstretched length",
                          std::to_string(p.unstretched_length),
                          "the catenary needs a cable longer than the span");
      if (p.model == "mesh file" && p.mesh_file.empty())
        InputFile::reject(gs,
                          "mesh file",
                          "",
                          "model 'mesh file' needs the name of a Gmsh file");

      const std::string ls = structure_section + "/Loads";
      prm.enter_subsection("Loads");
      p.gravity                         = get_vector(prm, ls, "gravity");
      const std::string gravity_text    = prm.get("gravity");
      p.point_load                      = get_vector(prm, ls, "point load");
      const std::string point_load_text = prm.get("point load");
      p.pressure                        = prm.get_double("pressure");
      p.prescribed_displacement = prm.get_double("prescribed displacement");
      p.load_path               = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("load path")));
      prm.leave_subsection();
      if (p.model == "plane catenary" &&
          !(p.gravity[0] == 0. && p.gravity[2] == 0. && p.gravity[1] < 0.))
        InputFile::reject(ls,
                          "gravity",
                          gravity_text,
                          "the plane catenary lies in the x-y plane of a "
                          "2D problem and sags along -y: gravity must be "
                          "0, -g, 0 with g > 0");
      if (catenary && !(p.density > 0. && p.gravity.norm() > 0.))
        InputFile::reject(lm,
                          "density",
                          std::to_string(p.density),
                          "the catenary needs a weight: density > 0 and a "
                          "non-zero 'gravity' in subsection Loads");
      if ((p.model == "sliding ring" || p.model == "capstan") &&
          !(p.point_load.norm() > 0.))
        InputFile::reject(ls,
                          "point load",
                          point_load_text,
                          "the sliding ring needs a non-zero load in the "
                          "x-z plane");

      // Models loaded by 'point load' along one axis c only.
      const auto require_load_along =
        [&](const bool applies, const unsigned int c, const std::string &what) {
          if (applies &&
              !(p.point_load[c] != 0. && p.point_load[(c + 1) % 3] == 0. &&
                p.point_load[(c + 2) % 3] == 0.))
            InputFile::reject(ls, "point load", point_load_text, what);
        };
      // The cantilever: an end load and / or its weight, both along its
      // height (z, or y for the plane cantilever).
      if (p.model == "cantilever")
        {
          const unsigned int c     = p.plane_solid ? 1 : 2;
          const auto         along = [c](const Tensor<1, 3> &v) {
            return v[(c + 1) % 3] == 0. && v[(c + 2) % 3] == 0.;
          };
          const std::string axis = p.plane_solid ? "0, P, 0" : "0, 0, P";
          if (!along(p.point_load) ||
              (p.point_load[c] == 0. && p.gravity[c] == 0.))
            InputFile::reject(ls,
                              "point load",
                              point_load_text,
                              std::string(p.plane_solid ?
                                            "the plane cantilever lies in "
                                            "the x-y plane and needs" :
                                            "the cantilever needs") +
                                " an end load " + axis +
                                " with P != 0 (or P = 0 and a weight, "
                                "'gravity' along the height)");
          if (!along(p.gravity))
            InputFile::reject(ls,
                              "gravity",
                              gravity_text,
                              std::string("the cantilever's weight acts "
                                          "along its height: gravity ") +
                                (p.plane_solid ? "0, g, 0" : "0, 0, g"));
        }
      require_load_along(p.model == "plastic bar",
                         0,
                         "the plastic bar needs an end load F, 0, 0 with "
                         "F != 0");
      require_load_along(p.model == "midspan cable",
                         2,
                         "the midspan cable needs a load 0, 0, -P with "
                         "P > 0");
      if (p.model == "midspan cable" && !(p.point_load[2] < 0.))
        InputFile::reject(ls,
                          "point load",
                          point_load_text,
                          "the midspan cable needs a load 0, 0, -P with "
                          "P > 0");
      // The closed forms of these models are written for the
      // Green-Lagrange law of the line members.
      if (p.strain_measure == Talus::Structure::StrainMeasure::engineering &&
          p.model != "midspan cable" && p.model != "sliding ring" &&
          p.model != "barrier" && p.model != "mesh file" &&
          p.model != "plane string" && p.model != "plane barrier")
        InputFile::reject(lm,
                          "strain measure",
                          "engineering",
                          "the closed form of model '" + p.model_text +
                            "' is written for the Green-Lagrange law (the "
                            "engineering law is verified by the models "
                            "'midspan cable' and 'sliding ring')");
      require_load_along(p.model == "axial bar",
                         0,
                         "the axial bar needs an end load F, 0, 0 with "
                         "F != 0");
      if (p.plane_solid && p.gravity[2] != 0.)
        InputFile::reject(ls,
                          "gravity",
                          gravity_text,
                          "a plane-strain solid lies in the x-y plane of "
                          "a 2D problem: gravity must be g_x, g_y, 0");
      if (p.plane_solid && p.solid_geometry.traction[2] != 0.)
        InputFile::reject(structure_section + "/Solid",
                          "traction",
                          p.solid_traction_text,
                          "a plane-strain solid lies in the x-y plane of "
                          "a 2D problem: its traction must be t_x, t_y, 0");
      if (p.model == "plastic bar" && p.line_element != "truss")
        InputFile::reject(lm,
                          "element",
                          p.line_element,
                          "the plastic bar is made of 'truss' elements "
                          "(a cable has no plasticity)");
      if (p.model == "hanging block")
        {
          if (!p.plane_solid &&
              !(p.gravity[0] == 0. && p.gravity[1] == 0. && p.gravity[2] < 0.))
            InputFile::reject(ls,
                              "gravity",
                              gravity_text,
                              "the hanging block needs gravity 0, 0, -g "
                              "with g > 0");
          if (p.plane_solid &&
              !(p.gravity[0] == 0. && p.gravity[1] < 0. && p.gravity[2] == 0.))
            InputFile::reject(ls,
                              "gravity",
                              gravity_text,
                              "the plane hanging block needs gravity 0, "
                              "-g, 0 with g > 0 (it hangs along -y in the "
                              "x-y plane)");
          if (p.prestress != 0.)
            InputFile::reject(lm,
                              "prestress",
                              std::to_string(p.prestress),
                              "the hanging block's cable has no "
                              "pre-stress (its reference is for 0)");
        }
      p.barrier.parse_parameters(prm, structure_section + "/Barrier");
      prm.enter_subsection("Solver");
      p.arc_length_control = prm.get("control") == "arc length";
      prm.leave_subsection();

      prm.enter_subsection("Dynamics");
      p.dynamic           = prm.get_bool("dynamic");
      p.mass_damping      = prm.get_double("mass damping");
      p.stiffness_damping = prm.get_double("stiffness damping");
      p.bossak_alpha      = prm.get_double("Bossak alpha");
      p.dynamic_time_step = prm.get_double("time step");
      prm.leave_subsection();
      if (p.dynamic && p.model != "square membrane" && p.model != "barrier" &&
          p.model != "vibrating string" && p.model != "solid" &&
          p.model != "axial bar" && p.model != "plane string" &&
          p.model != "plane barrier" && p.model != "cantilever")
        InputFile::reject(structure_section + "/Dynamics",
                          "dynamic",
                          "true",
                          "only models 'square membrane', 'vibrating "
                          "string', 'solid', 'axial bar', 'cantilever', "
                          "'plane string', 'plane barrier' and 'barrier' run "
                          "in time so far");
      if (!p.dynamic && p.model == "vibrating string")
        InputFile::reject(structure_section + "/Dynamics",
                          "dynamic",
                          "false",
                          "model 'vibrating string' needs 'dynamic = true'");

      prm.enter_subsection("Output");
      p.directory = prm.get("output directory");
      p.write_vtu = prm.get_bool("write vtu");
      p.test_mode = prm.get_bool("test mode");
      prm.leave_subsection();

      prm.enter_subsection("Verification");
      p.tolerance = prm.get_double("tolerance");
      p.reference_displacement =
        prm.get_double("reference largest displacement");
      p.tip_region_length =
        get_non_negative(prm,
                         structure_section + "/Verification",
                         "tip region length");
      p.n_levels     = prm.get_integer("number of levels");
      p.first_level  = prm.get_integer("first level");
      p.minimum_rate = prm.get_double("minimum rate");
      prm.leave_subsection();
      prm.leave_subsection();
      return p;
    }


    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection(structure_section);
      prm.declare_entry(
        "model",
        "von Mises truss",
        Patterns::Selection("von Mises truss|catenary|plane catenary|"
                            "circular membrane|"
                            "square membrane|sheared membrane|vibrating string|"
                            "sliding ring|capstan|brake|mesh file|barrier|"
                            "solid|cantilever|hanging block|axial bar|"
                            "plane solid|plane cantilever|plane axial bar|"
                            "plane hanging block|plane string|"
                            "stretched membrane|plastic bar|midspan cable|"
                            "plane barrier"),
        "Structural model built from the subsections below (used with "
        "'set problem = structure'): 'von Mises truss' (two bars, apex "
        "pushed down by 'prescribed displacement'), 'catenary' (cable "
        "under self weight between two supports), 'plane catenary' (the "
        "same as a 2D string: a Triangulation<1,2> in the x-y plane, "
        "gravity 0, -g, 0), 'circular membrane' "
        "(Hencky: clamped disk under pressure), 'square membrane' "
        "(pre-stressed, clamped, small pressure), 'sheared membrane' "
        "(square in simple shear: tension field with wrinkling), "
        "'vibrating string' (pre-stressed cable of two elements, middle node "
        "released: one degree of freedom against the Bossak recurrence), "
        "'sliding ring' (ring "
        "on a frictionless cable under 'point load'), 'capstan' (a sliding "
        "cable with friction around a drum, its free end pulled by "
        "|point load|), 'brake' (brake in "
        "series with a cable, end pulled by 'prescribed displacement'), "
        "'mesh file' (a line or membrane mesh read from 'mesh file', "
        "ends or boundary fixed, gravity and pressure), 'barrier' (the standard barrier of subsection Barrier "
        "with net, posts, support cables, retaining and lateral ropes and "
        "brakes: staged form finding of the pre-stressed state, then "
        "gravity and the field load; checks the global force balance), "
        "'solid' (a continuum solid of subsection Solid with its supports, "
        "traction and gravity), 'cantilever' (the box of subsection Solid "
        "clamped at x_min, end load 'point load' (0, 0, P) as a shear "
        "traction on x_max and / or its weight, 'gravity' (0, 0, g): "
        "Timoshenko's tip deflection), 'hanging block' "
        "(the box hanging under gravity on a vertical cable of 'cable "
        "length' tied to the centre of its top face: cable force and "
        "stretch by hand), 'axial bar' (the box on its symmetry planes "
        "pulled on x_max by 'point load' (F, 0, 0) as a traction: exact "
        "uniaxial stress, or with 'dynamic' the first axial period 4 L/c), "
        "'plane solid', 'plane cantilever', 'plane axial bar', 'plane "
        "hanging block' (the same four as plane-strain solids of a 2D "
        "problem: the rectangle of the x, y coordinates of subsection Solid "
        "as a Triangulation<2,2> in the x-y plane, 'thickness' t out of "
        "plane, u_z = 0; the cantilever is loaded along y by 'point load' "
        "(0, P, 0) against the plane-strain Timoshenko beam, the block "
        "hangs on a 2D string (Triangulation<1,2>) under gravity 0, -g, 0), "
        "'stretched membrane' (square membrane, orthotropic or not, under "
        "the homogeneous biaxial stretch or uniaxial stress of 'stretch'), "
        "'plane barrier' (the 2D analogue of a flexible barrier, per "
        "metre of width, subsection Plane barrier: a net of 'Line members' "
        "from 'net bottom' to the top of a post hinged at 'post base', the "
        "post head held uphill by a retaining rope with a brake of "
        "subsection Brake at its anchor), "
        "'plastic bar' (a straight truss of 'span' along x, fixed at x = 0, "
        "its end loaded by the x component of 'point load' along 'load "
        "path': elasto-plastic with linear hardening, loading, unloading "
        "and residual elongation in closed form), 'plane string' (a "
        "pre-tensioned straight string of a 2D problem: 'span' along x "
        "centred at 'origin', both ends fixed, mesh name 'string'; the "
        "barrier of the coupled 2D cases), 'midspan cable' (a straight "
        "cable of 'span' along x between two anchors, its middle loaded by "
        "'point load' (0, 0, -P), started straight: the two-bar truss in "
        "closed form for either 'strain measure'). "
        "Each model with a closed "
        "form reports and checks it.");

      prm.enter_subsection("Line members");
      prm.declare_entry("element",
                        "truss",
                        Patterns::Selection("truss|cable"),
                        "Element of the bars/cables: 'truss' (tension and "
                        "compression, optional plasticity) or 'cable' "
                        "(tension only, slack in compression).");
      prm.declare_entry("Young's modulus",
                        "2e11",
                        Patterns::Double(),
                        "E of the line members [Pa], > 0.");
      prm.declare_entry("cross-section area",
                        "1e-4",
                        Patterns::Double(),
                        "A of the line members [m^2], > 0.");
      prm.declare_entry("prestress",
                        "0",
                        Patterns::Double(),
                        "Pre-stress sigma_0, the axial stress at the "
                        "reference length L (Green-Lagrange: PK2, added to "
                        "E eps; engineering: unstretched length l0 = L/(1 + "
                        "sigma_0/E)) [Pa].");
      prm.declare_entry("density",
                        "0",
                        Patterns::Double(),
                        "Density [kg/m^3] (weight rho A g per unstretched "
                        "length), >= 0.");
      prm.declare_entry("yield stress",
                        "0",
                        Patterns::Double(),
                        "Truss yield stress (PK2) [Pa]; 0: elastic.");
      prm.declare_entry("hardening modulus",
                        "0",
                        Patterns::Double(),
                        "Linear isotropic hardening H of the truss [Pa].");
      prm.declare_entry("elements per member",
                        "1",
                        Patterns::Integer(),
                        "Elements along each bar or cable [-], >= 1 (the "
                        "catenary: on the coarsest level, even).");
      prm.declare_entry("friction coefficient",
                        "0",
                        Patterns::Double(),
                        "Capstan friction coefficient mu of sliding cables "
                        "at their interior nodes (model 'capstan') [-], >= "
                        "0.");
      prm.declare_entry("friction law",
                        "slide",
                        Patterns::Selection("slide|stick-slip"),
                        "Capstan friction of sliding cables: 'slide' (the "
                        "cable slides towards its last node at every node, "
                        "no history) or 'stick-slip' (a node sticks while "
                        "exp(-mu theta) <= N_k/N_{k-1} <= exp(mu theta) and "
                        "slips at the limit otherwise; history: the material "
                        "length of every segment).");
      prm.declare_entry("slack stiffness ratio",
                        "1e-8",
                        Patterns::Double(),
                        "Stiffness of a slack cable or brake in the Newton "
                        "matrix only (never in the forces), as a fraction "
                        "of EA/L (brake: of k_e) [-], > 0.");
      prm.declare_entry(
        "strain measure",
        "Green-Lagrange",
        Patterns::Selection(Talus::Structure::strain_measure_names),
        "Axial law of the cables, sliding cables and trusses: "
        "'Green-Lagrange' (S = E (l^2 - L^2)/(2 L^2) + sigma_0, N = A S "
        "l/L) or 'engineering' (N = EA (l - l0)/l0, l0 = L/(1 + "
        "sigma_0/E) the unstretched length, dN/dl = EA/l0: steel ropes as "
        "specified by EA) [-]. At 2 % strain the two forces differ by "
        "3 %.");
      prm.leave_subsection();

      prm.enter_subsection("Membrane");
      prm.declare_entry("Young's modulus",
                        "1e9",
                        Patterns::Double(),
                        "E (isotropic) or E1 along material axis 1 [Pa], > "
                        "0.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(),
                        "nu (isotropic) or nu12 [-], in (-1, 0.5].");
      prm.declare_entry("orthotropic",
                        "false",
                        Patterns::Bool(),
                        "Orthotropic plane-stress SVK with E2 and G12 below "
                        "(axis 1: global x projected on the surface).");
      prm.declare_entry("Young's modulus 2",
                        "1e9",
                        Patterns::Double(),
                        "E2 along material axis 2 (orthotropic) [Pa].");
      prm.declare_entry("shear modulus",
                        "4e8",
                        Patterns::Double(),
                        "G12 (orthotropic) [Pa].");
      prm.declare_entry("thickness",
                        "1e-3",
                        Patterns::Double(),
                        "Membrane thickness t [m], > 0.");
      prm.declare_entry("density",
                        "0",
                        Patterns::Double(),
                        "Density [kg/m^3], >= 0.");
      prm.declare_entry("prestress",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "In-plane PK2 pre-stress S11, S22, S12 in the "
                        "material axes [Pa].");
      prm.declare_entry("wrinkling",
                        "false",
                        Patterns::Bool(),
                        "Tension-field law: no compressive principal stress "
                        "(taut / wrinkled / slack).");
      prm.declare_entry("initial mode amplitude",
                        "0",
                        Patterns::Double(),
                        "Dynamic square membrane: initial deflection A "
                        "cos(pi x/a) cos(pi y/a) (the first mode) [m], "
                        "released from rest.");
      prm.declare_entry("shear strain",
                        "1e-4",
                        Patterns::Double(),
                        "Model 'sheared membrane': engineering shear strain "
                        "gamma imposed on the boundary (u_x = gamma (y + "
                        "a/2)) at load factor 1 [-].");
      prm.declare_entry("stretch",
                        "0.01, 0.005",
                        Patterns::List(Patterns::Double(), 2, 2),
                        "Model 'stretched membrane': engineering strains "
                        "lambda_1 - 1, lambda_2 - 1 along x and y imposed on "
                        "the boundary (u_x = e_x x, u_y = e_y y) at load "
                        "factor 1 [-]; with 'uniaxial stress' only e_x is "
                        "used.");
      prm.declare_entry("uniaxial stress",
                        "false",
                        Patterns::Bool(),
                        "Model 'stretched membrane': prescribe u_x = e_x x "
                        "on the edges x = +-a/2 only and hold u_y on the "
                        "line y = 0 (lateral edges free: uniaxial stress) "
                        "instead of the biaxial stretch of the whole "
                        "boundary.");
      prm.declare_entry("initial deflection",
                        "0",
                        Patterns::Double(),
                        "Start of Newton for the circular membrane: a "
                        "paraboloid bulge of this height [m] (a flat "
                        "unstressed membrane has no stiffness normal to "
                        "itself). It does not change the solution.");
      prm.leave_subsection();

      prm.enter_subsection("Brake");
      prm.declare_entry("stiffness",
                        "1e6",
                        Patterns::Double(),
                        "Elastic stiffness k_e [N/m], > 0.");
      prm.declare_entry("activation force",
                        "5e4",
                        Patterns::Double(),
                        "Force F_a at which the brake starts to slip [N], > "
                        "0.");
      prm.declare_entry("hardening",
                        "0",
                        Patterns::Double(),
                        "Hardening H: force rise per metre of stroke [N/m], "
                        ">= 0.");
      prm.declare_entry("stroke limit",
                        "0",
                        Patterns::Double(),
                        "Stroke s_max after which the brake blocks [m]; 0: "
                        "unlimited.");
      prm.declare_entry("length",
                        "1",
                        Patterns::Double(),
                        "Reference length of the brake element [m], > 0.");
      prm.leave_subsection();

      prm.enter_subsection("Plane barrier");
      prm.declare_entry("post base",
                        "0, 0",
                        Patterns::Anything(),
                        "Model 'plane barrier': foot of the post, hinged "
                        "(x, y of the 2D problem) [m].");
      prm.declare_entry("post top",
                        "0, 3",
                        Patterns::Anything(),
                        "Head of the post (x, y) [m]: the net's top and the "
                        "retaining rope end there.");
      prm.declare_entry("net bottom",
                        "0, 0",
                        Patterns::Anything(),
                        "Lower end of the net, fixed (the bottom support "
                        "rope in the ground; x, y) [m]. The net is "
                        "'elements per member' elements of subsection Line "
                        "members from here to the post top.");
      prm.declare_entry("rope anchor",
                        "-6, 0",
                        Patterns::Anything(),
                        "Uphill anchor of the retaining rope (x, y) [m]; the "
                        "brake of subsection Brake (its 'length') is the "
                        "last piece of the rope before the anchor.");
      prm.declare_entry("post EA",
                        "3.3e8",
                        Patterns::Double(),
                        "Axial stiffness of the posts per metre of barrier "
                        "width [N/m], > 0 (a truss hinged at both ends; "
                        "e.g. an HEB 200, E A = 1.6e9 N, every 5 m).");
      prm.declare_entry("post mass",
                        "12",
                        Patterns::Double(),
                        "Mass of the posts per metre of post length and "
                        "metre of barrier width [kg/m^2], >= 0 (61 kg/m "
                        "every 5 m).");
      prm.declare_entry("rope EA",
                        "1.1e7",
                        Patterns::Double(),
                        "Axial stiffness of the retaining ropes per metre of "
                        "barrier width [N/m], > 0 (two ropes of 22 mm, E A "
                        "= 2.8e7 N each, every 5 m).");
      prm.declare_entry("rope mass",
                        "0.8",
                        Patterns::Double(),
                        "Mass of the retaining ropes per metre of rope and "
                        "metre of barrier width [kg/m^2], >= 0.");
      prm.declare_entry("rope pretension",
                        "0",
                        Patterns::Double(),
                        "Pre-stress force of the retaining ropes, per metre "
                        "of barrier width [N/m], >= 0 (below the brake's "
                        "activation force); the equilibrium before the "
                        "impact follows from it and the net's prestress.");
      prm.declare_entry(
        "strain measure",
        "Green-Lagrange",
        Patterns::Selection(Talus::Structure::strain_measure_names),
        "Axial law of the post and the retaining rope [-]: 'Green-Lagrange' "
        "(N = EA (l^2 - L^2)/(2 L^2) l/L) or 'engineering' (N = EA (l - "
        "l0)/l0, the law barrier engineers specify steel ropes and posts "
        "by). The net follows 'strain measure' of subsection Line "
        "members.");
      prm.leave_subsection();

      prm.enter_subsection("Geometry");
      prm.declare_entry("half span",
                        "1",
                        Patterns::Double(),
                        "Half the distance between the supports b (von "
                        "Mises truss, sliding ring) [m], > 0.");
      prm.declare_entry("rise",
                        "0.1",
                        Patterns::Double(),
                        "Height h of the truss apex above the supports [m], "
                        "> 0.");
      prm.declare_entry("wrap angle",
                        "180",
                        Patterns::Double(1, 720),
                        "Capstan: angle the cable is wrapped around the drum "
                        "[degrees], 1 to 720 (more than 360: helix in the "
                        "plane is not modelled, keep <= 360).");
      prm.declare_entry("drum radius",
                        "0.5",
                        Patterns::Double(),
                        "Capstan: radius of the drum (fixed nodes on a "
                        "circle in the x-z plane) [m], > 0.");
      prm.declare_entry("string amplitude",
                        "1e-3",
                        Patterns::Double(),
                        "Model 'vibrating string': initial deflection of "
                        "the middle node, released from rest [m].");
      prm.declare_entry("spring EA",
                        "0",
                        Patterns::Double(),
                        "von Mises truss: if > 0, a vertical Truss spring of "
                        "this axial stiffness E A [N] stands on the apex and "
                        "carries the load at its top (snap-back under load "
                        "control when EA/L_s < EA h^2/L0^3).");
      prm.declare_entry("spring length",
                        "1",
                        Patterns::Double(),
                        "Length L_s of that spring [m], > 0.");
      prm.declare_entry("origin",
                        "0, 0, 0",
                        Patterns::Anything(),
                        "Centre of model 'plane string' (x, y, z; z = 0 for "
                        "a 2D problem) [m].");
      prm.declare_entry("span",
                        "10",
                        Patterns::Double(),
                        "Distance between the catenary supports l [m], > 0.");
      prm.declare_entry("unstretched length",
                        "12",
                        Patterns::Double(),
                        "Stress-free length of the catenary or ring cable "
                        "[m], > 0.");
      prm.declare_entry("radius",
                        "1",
                        Patterns::Double(),
                        "Radius a of the circular membrane [m], > 0.");
      prm.declare_entry("side",
                        "1",
                        Patterns::Double(),
                        "Side a of the square membrane [m], > 0.");
      prm.declare_entry("cable length",
                        "5",
                        Patterns::Double(),
                        "Length of the cable behind the brake [m], > 0.");
      prm.declare_entry("refinements",
                        "3",
                        Patterns::Integer(0, 10),
                        "Global refinements of the membrane meshes (level 0 "
                        "of a convergence study) [-].");
      prm.declare_entry("mesh file type",
                        "lines",
                        Patterns::Selection("lines|membrane"),
                        "What the file of model 'mesh file' holds: 'lines' "
                        "(a cable or truss, element of subsection Line "
                        "members) or 'membrane' (quadrilaterals, material of "
                        "subsection Membrane).");
      prm.declare_entry("mesh file",
                        "",
                        Patterns::Anything(),
                        "Gmsh (.msh) file of a line mesh for model 'mesh "
                        "file'.");
      prm.leave_subsection();

      prm.enter_subsection("Loads");
      prm.declare_entry("gravity",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Gravity acceleration [m/s^2], scaled by the load "
                        "factor.");
      prm.declare_entry("point load",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Load at the model's load point (the ring) [N].");
      prm.declare_entry("pressure",
                        "0",
                        Patterns::Double(),
                        "Follower pressure on the membranes, along the "
                        "normal t1 x t2 of the current surface [Pa].");
      prm.declare_entry("prescribed displacement",
                        "0",
                        Patterns::Double(),
                        "Displacement of the controlled node at load factor "
                        "1 (truss apex down, brake cable end along x) [m].");
      prm.declare_entry("load path",
                        "",
                        Patterns::List(Patterns::Double()),
                        "Load factors to visit in order (e.g. '1, 0.5, 1.5' "
                        "to load, unload, reload), each leg in 'load steps' "
                        "increments; empty: 0 to 1 [-].");
      prm.leave_subsection();

      prm.enter_subsection("Solid");
      Talus::Structure::ContinuumSolid<3>::declare_parameters(prm);
      Talus::Structure::SolidGeometry::declare_parameters(prm);
      prm.leave_subsection();

      Talus::Structure::BarrierBuilder::declare_parameters(prm);
      Talus::Structure::StaticSolver::declare_parameters(prm);
      Talus::Structure::DynamicSolver::declare_parameters(prm);

      prm.enter_subsection("Output");
      prm.declare_entry("output directory",
                        "output-structure",
                        Patterns::Anything(),
                        "Directory of the VTU files and of "
                        "load_steps.csv.");
      prm.declare_entry("write vtu",
                        "false",
                        Patterns::Bool(),
                        "Write one VTU file per mesh and load step (and a "
                        ".pvd per mesh).");
      prm.declare_entry("test mode",
                        "false",
                        Patterns::Bool(),
                        "Deterministic terminal output: no step lines.");
      prm.leave_subsection();

      prm.enter_subsection("Verification");
      prm.declare_entry("tolerance",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the run fails (exit code 3) when a checked "
                        "quantity misses its closed form by more than this "
                        "relative error on the finest level [-].");
      prm.declare_entry("reference largest displacement",
                        "0",
                        Patterns::Double(0),
                        "Model 'mesh file': if > 0, the largest nodal "
                        "displacement is compared with this value; model "
                        "'midspan cable': the sag [m].");
      prm.declare_entry("tip region length",
                        "0",
                        Patterns::Double(0),
                        "Model 'cantilever' with 'dynamic = true': the CSV "
                        "column end_region_u_y is the mean vertical "
                        "displacement of the cells within this distance of "
                        "the free end, int u dV0 / V0 over x >= L - a (the "
                        "mean an MPM run measures on the material points "
                        "of that region); 0: the last column of cells [m].");
      prm.declare_entry("number of levels",
                        "1",
                        Patterns::Integer(1, 8),
                        "Number of meshes, each refined once more (membranes: "
                        "one global refinement, catenary: twice the "
                        "elements) [-].");
      prm.declare_entry("first level",
                        "0",
                        Patterns::Integer(0, 8),
                        "Refinement level of the first run [-].");
      prm.declare_entry("minimum rate",
                        "0",
                        Patterns::Double(0),
                        "If > 0: the study fails when the rate of a checked "
                        "error between the last two levels is below this "
                        "[-].");
      prm.leave_subsection();
      prm.leave_subsection();
    }
  } // namespace StructureModels
} // namespace Talus
