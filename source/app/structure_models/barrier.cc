// Structure verification model: standard flexible barrier (set problem =
// structure).

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
    namespace
    {
      using namespace dealii;

      /**
       * The standard barrier (BarrierBuilder) under pre-stress, gravity and
       * a field load F. Reference: global equilibrium. The reactions at all
       * supports must balance the total weight W = g (sum rho A L of posts,
       * cables and ropes + rho t A of the net), computed from the geometry,
       * and F. Active brakes must carry F_a + H s.
       */
      class Barrier : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "standard three-field barrier under pre-stress, gravity "
                 "and a field load";
        }

        void
        build(Structure &s, const unsigned int) override
        {
          builder            = p.barrier;
          builder.net        = *membrane();
          builder.brake_k    = p.brake_k;
          builder.brake_Fa   = p.brake_Fa;
          builder.brake_H    = p.brake_H;
          builder.brake_smax = p.brake_smax;
          builder.build(s);
          // The self weight acts from the start (the barrier is erected
          // under gravity): it is part of the form finding, and the load
          // factor scales the field load only.
          s.gravity       = p.gravity;
          s.scale_gravity = false;
          // Stage 1 of the form finding: post heads held, so that the net
          // and the support cables find their pre-stressed shape under
          // their weight first.
          for (const unsigned int n : builder.post_heads)
            for (unsigned int c = 0; c < 3; ++c)
              s.prescribe(n, c);
        }

        void
        before_load_steps(Structure                      &s,
                          Talus::Structure::StaticSolver &solver) override
        {
          // Stage 2: release the heads (posts and ropes take over) and find
          // the pre-stressed equilibrium of the whole barrier under its
          // weight. Without the weight this state is degenerate: the net
          // and the top cable pull the inner heads along the post axis,
          // which the post alone carries, and their retaining ropes are
          // left without force (and their rope-brake nodes without
          // stiffness).
          const Vector<double> u = solver.displacement;
          for (const unsigned int n : builder.post_heads)
            for (unsigned int c = 0; c < 3; ++c)
              s.release(n, c);
          s.setup_system();
          solver.setup();
          solver.displacement = u;
          const auto status   = solver.solve(0.);
          std::cout << "  stage 2 (post heads released, pre-stress and "
                       "gravity): "
                    << (status.converged ? "converged" : "FAILED") << " in "
                    << status.iterations << " Newton iterations\n";
          if (!status.converged)
            throw ExcSimulationFailed("the pre-stressed barrier with free "
                                      "post heads did not converge: " +
                                      status.failure);
        }

        bool
        prestress_step() const override
        {
          return true;
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        /** Damped motion ends with a static solve from the state reached
         * (dynamic relaxation); undamped motion is checked for its energy. */
        bool
        relax_to_equilibrium() const override
        {
          return p.mass_damping > 0. || p.stiffness_damping > 0.;
        }

        bool
        form_finding_before_dynamics() const override
        {
          return true;
        }

        std::vector<std::pair<std::string, double>>
        monitor(const Structure &s,
                const Vector<double> &,
                const double) override
        {
          // CSV: the force on each group of supports (sum of the reactions,
          // x, y, z) and the axial force of every post.
          std::vector<std::pair<std::string, double>> columns;
          const unsigned int n_posts = builder.n_fields + 1;
          const std::vector<
            std::pair<std::string, std::pair<unsigned, unsigned>>>
            groups = {{"post_bases", {0, n_posts}},
                      {"bottom_cable_anchors", {n_posts, n_posts + 2}},
                      {"top_cable_anchors", {n_posts + 2, n_posts + 4}},
                      {"lateral_anchors", {n_posts + 4, n_posts + 6}},
                      {"retaining_anchors",
                       {n_posts + 6,
                        static_cast<unsigned>(builder.supports.size())}}};
          for (const auto &[name, range] : groups)
            {
              Tensor<1, 3> R;
              for (unsigned int k = range.first; k < range.second; ++k)
                R += s.reaction(builder.supports[k]);
              for (unsigned int c = 0; c < 3; ++c)
                columns.emplace_back(name + "_R" + "xyz"[c], R[c]);
            }
          const auto &posts = s.line_meshes[builder.post_meshes[0]]->force;
          for (unsigned int i = 0; i < posts.size(); ++i)
            columns.emplace_back("post_" + std::to_string(i) + "_force",
                                 posts[i]);
          if (time == 0.)
            initial_energy = total_energy;
          max_kinetic = std::max(max_kinetic, kinetic_energy);
          max_drift =
            std::max(max_drift, std::abs(total_energy - initial_energy));
          columns.insert(columns.begin(),
                         {{"time", time},
                          {"total_energy", total_energy},
                          {"kinetic_energy", kinetic_energy}});
          return columns;
        }

        /**
         * The barrier engineer's time series of a coupled run: the
         * material's force on each field (nodal interface forces of the
         * field's net nodes, the nodes on an inner post shared half and
         * half, component along the net's downstream normal) [N]; per post
         * its axial force (tension positive) [N], its rotation about its
         * base line, downslope positive [degrees], and the force on its
         * base [N]; the force on every ground anchor (bottom, top and
         * lateral cable anchors, the retaining ropes' anchors, i.e. the
         * force in each rope's brake) [N]; every brake's stroke [m]; the
         * net's largest deflection along its downstream normal [m] and its
         * residual height (the lowest point of its top edge above the
         * ground plane z = 0) [m]; the number of the net's Gauss points
         * that are wrinkled and slack (wrinkling law) [-].
         */
        std::vector<std::pair<std::string, double>>
        impact_columns(const Structure      &s,
                       const Vector<double> &u,
                       const Vector<double> &interface_forces) const override
        {
          const auto        &b       = builder;
          const unsigned int n_posts = b.n_fields + 1;
          const double       theta   = b.inclination * numbers::PI / 180.;
          const Tensor<1, 3> normal({0., -std::cos(theta), -std::sin(theta)});
          const bool         loaded = interface_forces.size() == u.size();
          std::vector<std::pair<std::string, double>> columns;

          double deflection = 0., residual_height = b.height;
          for (unsigned int f = 0; f < b.n_fields; ++f)
            {
              const auto   nodes = b.field_nodes(s, f);
              const auto   nz    = b.cells_over_height + 1;
              double       force = 0.;
              unsigned int index = 0;
              for (unsigned int k = 0; k <= b.cells_per_field; ++k)
                for (unsigned int j = 0; j < nz; ++j, ++index)
                  {
                    const unsigned int n = nodes[index];
                    const bool         shared =
                      (k == 0 && f > 0) ||
                      (k == b.cells_per_field && f + 1 < b.n_fields);
                    if (loaded)
                      force +=
                        (shared ? 0.5 : 1.) *
                        (s.node_displacement(interface_forces, n) * normal);
                    const Tensor<1, 3> d = s.node_displacement(u, n);
                    deflection           = std::max(deflection, d * normal);
                    if (j + 1 == nz)
                      residual_height =
                        std::min(residual_height, s.node_position(n)[2] + d[2]);
                  }
              columns.emplace_back("field_" + std::to_string(f) + "_force",
                                   force);
            }
          const auto &posts = s.line_meshes[b.post_meshes[0]]->force;
          for (unsigned int i = 0; i < n_posts; ++i)
            {
              const unsigned int base = b.supports[i], head = b.post_heads[i];
              const Tensor<1, 3> a0 =
                s.node_position(head) - s.node_position(base);
              const Tensor<1, 3> a = a0 + s.node_displacement(u, head) -
                                     s.node_displacement(u, base);
              const std::string post = "post_" + std::to_string(i);
              if (i < posts.size())
                columns.emplace_back(post + "_force", posts[i]);
              columns.emplace_back(post + "_rotation",
                                   -(std::atan2(a[1], a[2]) -
                                     std::atan2(a0[1], a0[2])) *
                                     180. / numbers::PI);
              columns.emplace_back(post + "_base_force",
                                   s.reaction(base).norm());
            }
          const std::vector<std::string> anchors = {"bottom_cable_left",
                                                    "bottom_cable_right",
                                                    "top_cable_left",
                                                    "top_cable_right",
                                                    "lateral_rope_left",
                                                    "lateral_rope_right"};
          for (unsigned int k = 0; k < anchors.size(); ++k)
            columns.emplace_back("anchor_" + anchors[k] + "_force",
                                 s.reaction(b.supports[n_posts + k]).norm());
          const auto &brakes = s.line_meshes[b.brake_meshes[0]]->state;
          for (unsigned int i = 0; i < n_posts; ++i)
            for (unsigned int side = 0; side < 2; ++side)
              {
                const unsigned int k = 2 * i + side;
                const std::string  rope =
                  "rope_" + std::to_string(i) + (side == 0 ? "a" : "b");
                columns.emplace_back(
                  "anchor_" + rope + "_force",
                  s.reaction(b.supports[n_posts + anchors.size() + k]).norm());
                if (brakes.size() == 2 * n_posts)
                  columns.emplace_back("brake_" + rope.substr(5) + "_stroke",
                                       brakes[k].plastic);
              }
          columns.emplace_back("net_deflection", deflection);
          columns.emplace_back("net_residual_height", residual_height);
          // Gauss points of the net in each state of the wrinkling law.
          unsigned int n_wrinkled = 0, n_slack = 0;
          for (const auto &m : s.membrane_meshes)
            for (const auto &o : m->cell_output)
              {
                n_wrinkled += o.n_wrinkled;
                n_slack += o.n_slack;
              }
          columns.emplace_back("net_wrinkled_points", n_wrinkled);
          columns.emplace_back("net_slack_points", n_slack);
          return columns;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          // Weight from the geometry of the parameters (not from the
          // structure's lumped masses).
          const auto    &b     = builder;
          const double   Hs    = b.post_length();
          const double   L     = b.n_fields * b.field_width;
          const Point<3> head0 = b.net_point(0., Hs);
          const Point<3> top_left(-b.end_anchor_offset, head0[1], 0.);
          const Point<3> lateral_left(-b.lateral_anchor_offset,
                                      head0[1] - b.lateral_anchor_downslope,
                                      0.);
          double mass = (b.n_fields + 1) * b.post_density * b.post_A * Hs;
          mass += b.cable_density * b.cable_A *
                  (2. * top_left.distance(head0) + L + // top
                   L + 2. * b.end_anchor_offset +      // bottom
                   2. * Hs);                           // edges
          mass +=
            b.lateral_density * b.lateral_A * 2. * lateral_left.distance(head0);
          for (unsigned int i = 0; i <= b.n_fields; ++i)
            for (const double side : {-1., 1.})
              {
                const Point<3> head = b.net_point(i * b.field_width, Hs);
                const Point<3> anchor(i * b.field_width +
                                        side * b.anchor_spread,
                                      b.anchor_distance,
                                      0.);
                mass += b.rope_density * b.rope_A *
                        (head.distance(anchor) - b.brake_length);
              }
          mass += p.membrane_density * p.thickness * L * Hs;
          const Tensor<1, 3> W = mass * p.gravity;
          const Tensor<1, 3> F = b.field_load;
          Tensor<1, 3>       R;
          for (const unsigned int n : b.supports)
            R += s.reaction(n);
          // R: sum of reaction() = f_int - f_ext over the supports. The
          // residual vanishes at the free nodes and the internal forces of
          // every element sum to zero, so R = -(sum of all external forces)
          // = -(W + F) in equilibrium.
          const double scale = (W.norm() + F.norm());
          double       umax  = 0.;
          for (unsigned int k = 0; k < s.n_nodes(); ++k)
            umax = std::max(umax, s.node_displacement(u, k).norm());
          const auto max_force = [&](const std::vector<unsigned int> &meshes) {
            double f = 0.;
            for (const unsigned int mesh : meshes)
              for (const double x : s.line_meshes[mesh]->force)
                f = std::max(f, std::abs(x));
            return f;
          };
          const auto min_force = [&](const std::vector<unsigned int> &meshes) {
            double f = std::numeric_limits<double>::max();
            for (const unsigned int mesh : meshes)
              for (const double x : s.line_meshes[mesh]->force)
                f = std::min(f, x);
            return f;
          };
          double max_stroke = 0.;
          for (const auto &st : s.line_meshes[b.brake_meshes[0]]->state)
            max_stroke = std::max(max_stroke, st.plastic);
          // Active brakes (stroke > 0, not blocked) carry F_a + H s.
          double       brake_law_error = 0.;
          unsigned int n_active        = 0;
          {
            const auto &m = *s.line_meshes[b.brake_meshes[0]];
            for (unsigned int c = 0; c < m.state.size(); ++c)
              if (m.state[c].plastic > 0. &&
                  (b.brake_smax == 0. || m.state[c].plastic < b.brake_smax))
                {
                  ++n_active;
                  brake_law_error =
                    std::max(brake_law_error,
                             std::abs(
                               m.force[c] -
                               (b.brake_Fa + b.brake_H * m.state[c].plastic)) /
                               b.brake_Fa);
                }
          }
          unsigned int n_slack_ropes = 0;
          for (const double x : s.line_meshes[b.rope_meshes[0]]->force)
            n_slack_ropes += (x <= 0.);
          std::vector<Result> r = {
            {"|R + W + F| / (|W| + |F|)",
             (R + W + F).norm() / scale,
             0.,
             true,
             true},
            {"total weight [N]", W.norm(), 0., false},
            {"field load [N]", F.norm(), 0., false},
            {"sum of reactions y [N]", R[1], 0., false},
            {"sum of reactions z [N]", R[2], 0., false},
            {"largest displacement [m]", umax, 0., false},
            {"top cable tension [N]",
             max_force({b.support_cable_meshes[0]}),
             0.,
             false},
            {"bottom cable tension [N]",
             max_force({b.support_cable_meshes[1]}),
             0.,
             false},
            {"edge cable tension [N]",
             max_force({b.support_cable_meshes[2], b.support_cable_meshes[3]}),
             0.,
             false},
            {"lateral rope force [N]",
             max_force(b.lateral_rope_meshes),
             0.,
             false},
            {"largest retaining rope force [N]",
             max_force(b.rope_meshes),
             0.,
             false},
            {"smallest retaining rope force [N]",
             min_force(b.rope_meshes),
             0.,
             false},
            {"slack retaining ropes", double(n_slack_ropes), 0., false},
            {"largest brake force [N]", max_force(b.brake_meshes), 0., false},
            {"largest post compression [N]",
             -min_force(b.post_meshes),
             0.,
             false},
            {"largest brake stroke [m]", max_stroke, 0., false},
            {"active brakes", double(n_active), 0., false}};
          if (n_active > 0)
            r.push_back({"active brakes: max |N - (F_a + H s)| / F_a",
                         brake_law_error,
                         0.,
                         true,
                         true});
          if (p.dynamic && !relax_to_equilibrium() && max_kinetic > 0.)
            {
              // Undamped motion: energy (kinetic + strain + load potential)
              // against its initial value, relative to the largest kinetic
              // energy.
              r.push_back(
                {"largest kinetic energy [J]", max_kinetic, 0., false});
              r.push_back({"max |E(t) - E(0)| / max kinetic energy",
                           max_drift / max_kinetic,
                           0.,
                           true,
                           true});
              r[0].checked = false; // not in equilibrium while moving
            }
          // Post forces one by one.
          const auto &posts = s.line_meshes[b.post_meshes[0]]->force;
          for (unsigned int i = 0; i < posts.size(); ++i)
            r.push_back({"post " + std::to_string(i) + " axial force [N]",
                         posts[i],
                         0.,
                         false});
          return r;
        }

      private:
        Talus::Structure::BarrierBuilder builder;
        double initial_energy = 0., max_kinetic = 0., max_drift = 0.;
      };
    } // namespace


    std::unique_ptr<Model>
    create_barrier(const Parameters &p)
    {
      return std::make_unique<Barrier>(p);
    }


  } // namespace StructureModels
} // namespace Talus
