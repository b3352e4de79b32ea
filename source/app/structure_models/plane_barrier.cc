// Structure model: the 2D analogue of a flexible barrier (a longitudinal
// section, per metre of barrier width), the barrier of the 2D flagship
// input prm/flexible_barrier_2d.prm (set problem = coupled).

#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/structure/plane_string.h>
#include <talus/structure/structure.h>

#include <deal.II/grid/tria.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace StructureModels
  {
    namespace
    {
      using namespace dealii;

      /**
       * A flexible barrier in a longitudinal section of a 2D problem, every
       * quantity per metre of barrier width: the net (cables of subsection
       * Line members, 'elements per member' of them) from 'net bottom'
       * (fixed: the bottom support rope in the ground) to the head of the
       * post; the post a truss from 'post base' (hinged) to 'post top'
       * ('post EA', 'post mass'); the retaining rope from the post head
       * uphill to 'rope anchor', a cable ('rope EA', 'rope mass', 'rope
       * pretension') in series with the brake of subsection Brake
       * (activation force, hardening, stroke limit, 'length') at the
       * anchor. Post and rope take the axial law of the subsection's
       * 'strain measure', the net that of Line members. Meshes "net", "post",
       * "rope" and "brake", each a Triangulation<1,2> in the plane
       * (PlaneString), joined where their vertices coincide
       * (Structure::setup_dofs()). The coupling's 'structure mesh' is "net".
       *
       * It reduces the three-field barrier of the founding paper (section
       * 5; BarrierBuilder in 3D) to its load path in the flow direction:
       * net -> post head -> retaining rope and brake -> anchor, and net ->
       * bottom rope. What the section cannot carry: the lateral spread of
       * the load to the edge cables and the posts' bending.
       */
      class PlaneBarrier : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "flexible barrier in a longitudinal section of a 2D "
                 "problem (net, post, retaining rope with brake)";
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const Point<2> bottom = point(p.net_bottom),
                         base = point(p.post_base), top = point(p.post_top),
                         anchor = point(p.rope_anchor);
          // The brake at the anchor: the rope ends 'length' before it.
          const Tensor<1, 2> along  = (top - anchor) / (top - anchor).norm();
          const Point<2>     joint  = anchor + p.brake_length * along;
          const unsigned int n_net  = p.elements << level;
          const unsigned int n_rope = 1;
          make_line(net.triangulation, bottom, top, n_net);
          make_line(post.triangulation, base, top, 1);
          make_line(rope.triangulation, top, joint, n_rope);
          make_line(brake.triangulation, joint, anchor, 1);

          auto post_element = std::make_shared<Talus::Structure::Truss>();
          post_element->youngs_modulus        = p.post_EA;
          post_element->area                  = 1.;
          post_element->density               = p.post_mass;
          post_element->slack_stiffness_ratio = p.slack_ratio;
          post_element->strain_measure        = p.member_strain_measure;
          auto rope_element = std::make_shared<Talus::Structure::Cable>();
          rope_element->youngs_modulus        = p.rope_EA;
          rope_element->area                  = 1.;
          rope_element->density               = p.rope_mass;
          rope_element->prestress             = p.rope_pretension;
          rope_element->slack_stiffness_ratio = p.slack_ratio;
          rope_element->strain_measure        = p.member_strain_measure;

          s.gravity = p.gravity;
          net.add_to(s, "net", line_element());
          post.add_to(s, "post", post_element);
          rope.add_to(s, "rope", rope_element);
          brake.add_to(s, "brake", brake_element());
          s.setup_dofs();
          for (auto *string : {&net, &post, &rope, &brake})
            string->setup(s);
          net.fix(s, 0);
          post.fix(s, 0);
          brake.fix(s, 1);
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &) override
        {
          // Informative: the forces of the load path (not checked).
          const auto member = [&s](const std::string &name) {
            for (const auto &mesh : s.line_meshes)
              if (mesh->name == name)
                return mesh.get();
            AssertThrow(false, ExcInternalError());
            return s.line_meshes[0].get();
          };
          return {
            {"post axial force [N/m]", member("post")->force[0], 0., false},
            {"rope force [N/m]", member("rope")->force[0], 0., false},
            {"brake stroke [m]", member("brake")->state[0].plastic, 0., false},
            {"net bottom force [N/m]", net.reaction(s, 0).norm(), 0., false},
            {"anchor force [N/m]", brake.reaction(s, 1).norm(), 0., false}};
        }

        std::array<std::string, 3>
        support_parameter() const override
        {
          return {{structure_section + "/Plane barrier",
                   "post base",
                   "(and net bottom, rope anchor)"}};
        }

      private:
        Talus::Structure::PlaneString net, post, rope, brake;

        static Point<2>
        point(const Tensor<1, 3> &x)
        {
          return Point<2>(x[0], x[1]);
        }
      };
    } // namespace


    std::unique_ptr<Model>
    create_plane_barrier(const Parameters &p)
    {
      return std::make_unique<PlaneBarrier>(p);
    }
  } // namespace StructureModels
} // namespace Talus
