#ifndef talus_app_structure_models_solid_model_h
#define talus_app_structure_models_solid_model_h

#include <talus/app/structure_models/model.h>
#include <talus/base/input.h>

#include <deal.II/grid/tria.h>

#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace StructureModels
  {
    /**
     * Mean of displacement component @p c of solid mesh @p mesh over its
     * faces with boundary id @p id, int u_c dA0 / A0 (the work-conjugate
     * of a uniform traction along c) [m]. Instantiated for dim = 2, 3.
     */
    template <int dim>
    double
    face_mean(const Talus::Structure::SolidMeshT<dim> &mesh,
              const dealii::Vector<double>            &u,
              const unsigned int                       id,
              const unsigned int                       c);


    /**
     * Mean of displacement component @p c of solid mesh @p mesh over its
     * cells whose centre lies at x > @p x_min, int u_c dV0 / V0 [m] (the
     * mean a coupled run measures on the material points of a region).
     * Instantiated for dim = 2, 3.
     */
    template <int dim>
    double
    region_mean(const Talus::Structure::SolidMeshT<dim> &mesh,
                const dealii::Vector<double>            &u,
                const double                             x_min,
                const unsigned int                       c);


    // ------------------------------------------------------------------
    /**
     * A continuum solid alone (subsection Solid): generated box or Gmsh
     * file of hexahedra, the supports and the traction of that
     * subsection, gravity. Reports the largest displacement, compared
     * with 'reference largest displacement' if that is set.
     */
    class SolidModel : public Model
    {
    public:
      using Model::Model;

      std::string
      description() const override
      {
        return std::string(p.plane_solid ? "plane-strain " : "") +
               "continuum solid (" + p.solid.law_name() + ", FE_Q(" +
               std::to_string(p.solid.degree) +
               ")) with the supports and loads of subsection Solid";
      }

      bool
      supports_dynamics() const override
      {
        return true;
      }

      std::array<std::string, 3>
      support_parameter() const override
      {
        const auto &g = p.solid_geometry;
        if (g.fixed_boundary_ids.empty() && !g.support_boxes.empty())
          return {{structure_section + "/Solid",
                   "support boxes",
                   std::to_string(g.support_boxes.size()) + " box(es)"}};
        std::string ids;
        for (const unsigned int id : g.fixed_boundary_ids)
          ids += (ids.empty() ? "" : ", ") + std::to_string(id);
        return {{structure_section + "/Solid", "fixed boundary ids", ids}};
      }

      void
      build(Structure &s, const unsigned int level) override
      {
        const std::string ss = structure_section + "/Solid";
        if (p.solid_geometry.traction_boundary_id >= 0)
          add_solid_mesh(s, "solid", level)
            .emplace_back(p.solid_geometry.traction_boundary_id,
                          p.solid_geometry.traction);
        else
          add_solid_mesh(s, "solid", level);
        s.setup_dofs();
        on_solid(s, [&](const auto &mesh) {
          for (const unsigned int id : p.solid_geometry.fixed_boundary_ids)
            if (s.prescribe_solid_boundary(mesh, id) == 0)
              InputFile::reject(ss,
                                "fixed boundary ids",
                                std::to_string(id),
                                "every fixed boundary id must be the id of "
                                "faces on the boundary of the solid (a "
                                "generated box has ids 0 to 5, a plane "
                                "rectangle 0 to 3), and boundary id " +
                                  std::to_string(id) + " has none");
          unsigned int k = 0;
          for (const auto &box : p.solid_geometry.support_boxes)
            {
              ++k;
              if (s.prescribe_solid_box(
                    mesh, box.lower, box.upper, box.components) == 0)
                InputFile::reject(ss,
                                  "support boxes",
                                  "box " + std::to_string(k),
                                  std::string(
                                    "every support box must contain a node of "
                                    "the solid") +
                                    (p.plane_solid ? " (a plane solid lies at "
                                                     "z = 0)" :
                                                     "") +
                                    ", and box " + std::to_string(k) +
                                    " contains none");
            }
        });
        s.gravity = p.gravity;
      }

      std::vector<Result>
      results(const Structure &s, const dealii::Vector<double> &u) override
      {
        double umax = 0.;
        for (unsigned int k = 0; k < s.n_nodes(); ++k)
          umax = std::max(umax, s.node_displacement(u, k).norm());
        if (p.reference_displacement > 0.)
          return {{"largest displacement [m]", umax, p.reference_displacement}};
        return {{"largest displacement [m]", umax, 0., false}};
      }

    protected:
      std::shared_ptr<Talus::Structure::ContinuumSolid<3>>
      solid_component() const
      {
        return std::make_shared<Talus::Structure::ContinuumSolid<3>>(p.solid);
      }

      /**
       * Add the model's solid named @p name: the box of subsection Solid
       * (Triangulation<3,3>), or for the plane models its rectangle in
       * the x-y plane as a plane-strain solid of 'thickness' t. Returns
       * its tractions (to fill before setup_dofs()).
       */
      std::vector<std::pair<unsigned int, dealii::Tensor<1, 3>>> &
      add_solid_mesh(Structure         &s,
                     const std::string &name,
                     const unsigned int level) const
      {
        const auto &g = p.solid_geometry;
        if (p.plane_solid)
          {
            dealii::Triangulation<2> plane;
            g.create_triangulation(plane, level, structure_section + "/Solid");
            auto solid =
              std::make_shared<Talus::Structure::ContinuumSolid<2>>();
            solid->youngs_modulus = p.solid.youngs_modulus;
            solid->poissons_ratio = p.solid.poissons_ratio;
            solid->density        = p.solid.density;
            solid->degree         = p.solid.degree;
            solid->law            = p.solid.law;
            return s.add_plane_solid(name, solid, g.thickness, plane).tractions;
          }
        auto &mesh = s.add_solid(name, solid_component());
        g.create_triangulation(mesh.triangulation,
                               level,
                               structure_section + "/Solid");
        return mesh.tractions;
      }

      /** Call @p f with the model's (last) solid mesh, 3D or plane. */
      template <typename Function>
      static void
      on_solid(const Structure &s, const Function &f)
      {
        if (!s.plane_solid_meshes.empty())
          f(*s.plane_solid_meshes.back());
        else
          f(*s.solid_meshes.back());
      }

      /** Mean of displacement component @p c over the faces of boundary
       * id @p id of the model's solid (the work-conjugate of a uniform
       * traction there) [m]. */
      static double
      solid_face_mean(const Structure              &s,
                      const dealii::Vector<double> &u,
                      const unsigned int            id,
                      const unsigned int            c)
      {
        double mean = 0.;
        on_solid(s,
                 [&](const auto &mesh) { mean = face_mean(mesh, u, id, c); });
        return mean;
      }

      /** Direction of the "vertical" (height, load, gravity): z, or y
       * for a plane solid. */
      unsigned int
      vertical() const
      {
        return p.plane_solid ? 1 : 2;
      }

      /** Cross-section of the generated solid normal to x: width b
       * (y extent, or the thickness t of a plane solid) and height h
       * (z extent, or the y extent of a plane solid) [m]. */
      double
      width() const
      {
        const auto &g = p.solid_geometry;
        return p.plane_solid ? g.thickness :
                               g.upper_corner[1] - g.lower_corner[1];
      }

      double
      height() const
      {
        const auto &g = p.solid_geometry;
        return g.upper_corner[vertical()] - g.lower_corner[vertical()];
      }

      /** Young's modulus and Poisson's ratio of the beam and bar
       * formulas: E, nu, or for plane strain E/(1 - nu^2), nu/(1 - nu). */
      double
      effective_modulus() const
      {
        const double nu = p.solid.poissons_ratio;
        return p.plane_solid ? p.solid.youngs_modulus / (1. - nu * nu) :
                               p.solid.youngs_modulus;
      }

      double
      effective_poisson() const
      {
        const double nu = p.solid.poissons_ratio;
        return p.plane_solid ? nu / (1. - nu) : nu;
      }
    };
  } // namespace StructureModels
} // namespace Talus

#endif
