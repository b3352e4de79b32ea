#include <talus/base/input.h>
#include <talus/mpm/body_contact.h>
#include <talus/mpm/mpm_solver.h>
#include <talus/mpm/point_tensors.h>

#include <deal.II/base/utilities.h>

#include <Epetra_Export.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace Talus
{
  void
  MPM::BodyContact::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.enter_subsection("Body contact");
    prm.declare_entry(
      "contact",
      "single velocity field",
      Patterns::Selection("single velocity field|multi-velocity field"),
      "How bodies (Body, Body 2, ...) meet. 'single velocity field': all "
      "share the grid's one velocity field (standard MPM): they stick where "
      "their points share a node, about a cell before they touch, and cannot "
      "separate while they do. 'multi-velocity field': each body has its own "
      "velocity field on the grid (Bardenhagen, Brackbill and Sulsky 2000); "
      "at nodes where two bodies carry mass a penalty pressure acts on the "
      "normal gap measured from the points' domains (Nairn 2013), so contact "
      "starts when the bodies touch, they separate freely, and Coulomb "
      "friction ('friction coefficient') acts between them. Needs 'number of "
      "bodies' >= 2, the lumped mass matrix, inertia (not quasi-static), no "
      "ghost penalty, and of the boundaries of boundary particles only "
      "those with 'contact side = material points' (each point meets the "
      "surface through its own body's field); works with every 'shape "
      "functions' and with grid friction boundaries (each body's field has "
      "its own friction nodes) (doc/theory.md, 'Contact between bodies').");
    prm.declare_entry(
      "friction coefficient",
      "0",
      Patterns::Anything(),
      "Coulomb friction coefficient mu between bodies [-], >= 0 "
      "(multi-velocity field): the tangential force at a contact node is "
      "that of a stick penalty with the normal stiffness, bounded by mu "
      "times the normal pressure (slip). With friction the tangent is not "
      "symmetric: 'linear solver' (subsection Solver) must be 'GMRES' or "
      "'direct'.");
    prm.declare_entry(
      "penalty factor",
      "100",
      Patterns::Anything(),
      "Factor of the contact stiffness k = factor * min(m_a, m_b) / (beta "
      "dt^2) at a node shared by bodies a and b [-], > 0 (multi-velocity "
      "field): the inertia stiffness of the lighter field, so that the "
      "penetration within a step is about 1/factor of the approach per step.");
    prm.declare_entry(
      "carry contact forces",
      "false",
      Patterns::Bool(),
      "Whether the penalty force of a node shared by two bodies (pressure "
      "and tangential stick force) is carried from one step into the next "
      "while the node stays in contact (multi-velocity field): the force "
      "then changes by k times the relative displacement of the step, so a "
      "body resting or sticking on another holds its place. 'false': the "
      "penalty starts unloaded in every step and such a body creeps, by "
      "F / k per step (about F beta dt / (factor m) per second). The energy "
      "the contact takes ('body contact dissipation') then includes what "
      "the carried springs store, F^2 / (2 k) per node.");
    prm.declare_entry(
      "normal margin",
      "0.05",
      Patterns::Anything(),
      "Preference of the contact normal of the larger volume gradient over "
      "the other candidates (the other body's normal, their mean), as a "
      "fraction of the smallest cell diameter [-], > 0 (multi-velocity "
      "field): another candidate is taken where it separates the bodies' "
      "point domains by this much more. The choice is continuous: "
      "candidates within a quarter of the margin of the best are blended, "
      "and where the two bodies' volume gradients are within 1 % of each "
      "other the preference is shared, so that mirrored nodes get mirrored "
      "normals "
      "(doc/theory.md, 'Contact between bodies').");
    prm.leave_subsection();
  }


  void
  MPM::BodyContact::parse_parameters(dealii::ParameterHandler &prm,
                                     const unsigned int        n_bodies)
  {
    const std::string sub = "Body contact";
    prm.enter_subsection(sub);
    multi_velocity_field = prm.get("contact") == "multi-velocity field";
    friction_coefficient = get_non_negative(prm, sub, "friction coefficient");
    penalty_factor       = get_positive(prm, sub, "penalty factor");
    carry_contact_forces = prm.get_bool("carry contact forces");
    normal_margin        = get_positive(prm, sub, "normal margin");
    prm.leave_subsection();
    if (!multi_velocity_field && carry_contact_forces)
      InputFile::reject(sub,
                        "carry contact forces",
                        "true",
                        "it applies to the forces between the bodies' "
                        "velocity fields, 'contact = multi-velocity field'; "
                        "with one velocity field there are none");
    if (multi_velocity_field && n_bodies < 2)
      InputFile::reject(sub,
                        "contact",
                        "multi-velocity field",
                        "it needs two or more bodies (subsection Body, "
                        "'number of bodies' is " +
                          std::to_string(n_bodies) +
                          "); use 'single velocity field'");
  }


  namespace MPM
  {
    namespace
    {
      /**
       * Max-reduction of a vector given on the locally relevant dofs
       * (@p local, this rank's values, -infinity where it has none) onto
       * the owners: the owned entries of the result are the maximum over
       * the ranks.
       */
      std::vector<double>
      max_to_owners(const dealii::IndexSet    &owned,
                    const dealii::IndexSet    &relevant,
                    const std::vector<double> &local,
                    const MPI_Comm             comm)
      {
        const Epetra_Map relevant_map = relevant.make_trilinos_map(comm, true);
        const Epetra_Map owned_map    = owned.make_trilinos_map(comm, false);
        Epetra_Vector    source(relevant_map), target(owned_map);
        for (unsigned int k = 0; k < local.size(); ++k)
          source[k] = local[k];
        target.PutScalar(-std::numeric_limits<double>::max());
        const Epetra_Export exporter(relevant_map, owned_map);
        target.Export(source, exporter, Epetra_Max);
        std::vector<double> result(owned.n_elements());
        for (unsigned int k = 0; k < result.size(); ++k)
          result[k] = target[k];
        return result;
      }
    } // namespace


    template <int dim>
    void
    MPMSolver<dim>::set_body_contact(const BodyContact &contact)
    {
      multi_field = contact.multi_velocity_field;
      if (!multi_field)
        return;
      body_friction      = contact.friction_coefficient;
      body_penalty       = contact.penalty_factor;
      body_carry         = contact.carry_contact_forces;
      body_normal_margin = contact.normal_margin;
      const auto reject  = [](const std::string &sub,
                             const std::string &entry,
                             const std::string &value,
                             const std::string &what) {
        InputFile::reject(sub,
                          entry,
                          value,
                          what +
                            " is not implemented with 'contact = "
                             "multi-velocity field' (subsection Body contact)");
      };
      if (consistent_mass)
        reject("Solver", "mass matrix", "consistent", "the consistent mass");
      if (quasi_static)
        reject("Solver",
               "quasi-static",
               "true",
               "a quasi-static analysis (the contact stiffness is that of "
               "the nodal inertia)");
      if (ghost_penalty_factor > 0.)
        reject("Solver",
               "ghost penalty factor",
               std::to_string(ghost_penalty_factor),
               "the ghost penalty");
      // The sliding tangent of the friction between bodies is not
      // symmetric (mu k t n; in 3D also mu p / |s| (P - t t)): CG, which
      // needs a symmetric positive definite matrix, stalls at 2000
      // iterations (tests/mpm/block_on_block_3d_mu02 from its third step,
      // tests/mpm/block_on_block_mu02 on the grid h/2 from its first).
      if (body_friction > 0. && linear_solver_type == "CG")
        InputFile::reject(
          "Solver",
          "linear solver",
          "CG",
          "CG needs a symmetric matrix, and the tangent of the friction "
          "between bodies (subsection Body contact, 'contact = "
          "multi-velocity field', 'friction coefficient' > 0) is not "
          "symmetric: use 'GMRES' or 'direct'");
    }


    template <int dim>
    void
    MPMSolver<dim>::prepare_body_contact()
    {
      contact_nodes.clear();
      if (!multi_field)
        return;
      // the forces committed at the end of the last step, by node and pair
      std::map<std::vector<double>, dealii::Tensor<1, dim>> carried;
      for (std::size_t i = 0; i + carried_entry_size <= carried_contact.size();
           i += carried_entry_size)
        {
          const std::vector<double> key(carried_contact.begin() + i,
                                        carried_contact.begin() + i + dim + 2);
          for (unsigned int d = 0; d < dim; ++d)
            carried[key][d] = carried_contact[i + dim + 2 + d];
        }
      using Properties            = MaterialPointProperties<dim>;
      const unsigned int n_nodes  = shape_stride;
      const unsigned int n_fields = grid.n_velocity_fields();
      const MPI_Comm     comm     = grid.mpi_communicator;
      const auto        &owned    = grid.locally_owned_dofs;
      const auto        &relevant = grid.locally_relevant_dofs;

      // the current volume V_0 det F of point k
      const auto point_volume = [this](const unsigned int k) {
        const auto             props = particles[k]->get_properties();
        dealii::Tensor<2, dim> F;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            F[i][j] = props[Properties::deformation + i * dim + j];
        return props[Properties::initial_volume] * dealii::determinant(F);
      };

      // volume gradients sum_p V_p grad N_I(x_p) at the nodes, on the dofs
      // of field b: they point out of body b (Bardenhagen et al. 2000;
      // volumes rather than masses, Nairn 2013: independent of density)
      dealii::TrilinosWrappers::MPI::Vector gradient(owned, comm);
      dealii::Vector<double>                g_local(dim * n_nodes);
      for (const auto &c : cells)
        {
          g_local.reinit(c.dofs.size());
          for (unsigned int q = 0; q < c.n; ++q)
            {
              const unsigned int k      = c.first + q;
              const double       volume = point_volume(k);
              for (unsigned int i = 0; i < c.dofs.size(); ++i)
                {
                  const auto ci = internal::component_and_node<dim>(i);
                  g_local[i] +=
                    volume * shape_gradients[k * n_nodes + ci.second][ci.first];
                }
            }
          gradient.add(c.dofs, g_local);
        }
      gradient.compress(dealii::VectorOperation::add);
      dealii::TrilinosWrappers::MPI::Vector grad(owned, relevant, comm);
      grad = gradient;

      // The nodes of a cache: its cell's vertices (linear shape functions)
      // or the patch nodes its points reach (uGIMP, cpGIMP, CPDI), each
      // with its index j in the cache's shape values, its position and
      // the dofs of every field (component d of field f at f dim + d).
      std::vector<dealii::types::global_dof_index> vertex_dofs(dim * n_fields);
      const auto for_each_node = [&](const CellCache &c, const auto &visit) {
        if (!gimp)
          for (const unsigned int v : c.cell->vertex_indices())
            {
              for (unsigned int i = 0; i < vertex_dofs.size(); ++i)
                vertex_dofs[i] = c.cell->vertex_dof_index(v, i);
              visit(v, c.cell->vertex(v), vertex_dofs);
            }
        else
          for (unsigned int j = 0; j < c.lattice_nodes.size(); ++j)
            {
              long long          key = c.lattice_nodes[j];
              dealii::Point<dim> x   = grid.lower_corner;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  x[d] += static_cast<double>(key % lattice_size[d]) *
                          grid.cell_extent[d];
                  key /= lattice_size[d];
                }
              visit(j, x, lattice_dofs.at(c.lattice_nodes[j]));
            }
      };
      // The pairs of bodies at the nodes of this rank's cells with points
      // (the same on every rank that sees the node): the key is the dof
      // of component 0 of field a; the normal from a to b.
      constexpr unsigned int n_candidates = 3;
      struct Pair
      {
        unsigned int                                     a, b;
        std::array<dealii::Tensor<1, dim>, n_candidates> normals;
        std::array<dealii::types::global_dof_index, dim> dofs_a, dofs_b;
        dealii::Point<dim>                               vertex;
        /**
         * The preference of candidate 0 (a's normal) over candidate 1
         * (b's), in [0, 1]: 1 where a's volume gradient is the larger by 1
         * % or more of their sum, 0 where b's is, linear in between.
         */
        double preference_a = 1.;
      };
      std::map<std::pair<dealii::types::global_dof_index, unsigned int>, Pair>
                                                pairs;
      std::set<dealii::types::global_dof_index> visited;
      for (const auto &c : cells)
        for_each_node(c,
                      [&](const unsigned int,
                          const dealii::Point<dim> &x,
                          const auto               &dofs) {
                        if (!visited.insert(dofs[0]).second)
                          return;
                        for (unsigned int a = 0; a < n_fields; ++a)
                          for (unsigned int b = a + 1; b < n_fields; ++b)
                            {
                              const double m_a = nodal_mass(dofs[a * dim]);
                              const double m_b = nodal_mass(dofs[b * dim]);
                              if (!(m_a > 0.) || !(m_b > 0.))
                                continue;
                              Pair p;
                              p.a      = a;
                              p.b      = b;
                              p.vertex = x;
                              // candidate normals: the outward normal of body
                              // a, minus that of body b, and their average
                              // (Nairn 2013's options); the one along which the
                              // bodies' domains are separated most is taken
                              // below. A body's gradient is exact inside a flat
                              // face but tilts at its corners and where its
                              // points cross cells; along a tilted normal the
                              // domains overlap.
                              dealii::Tensor<1, dim> g_a, g_b;
                              for (unsigned int d = 0; d < dim; ++d)
                                {
                                  p.dofs_a[d] = dofs[a * dim + d];
                                  p.dofs_b[d] = dofs[b * dim + d];
                                  g_a[d]      = grad(p.dofs_a[d]);
                                  g_b[d]      = grad(p.dofs_b[d]);
                                }
                              if (!(g_a.norm() > 0.) || !(g_b.norm() > 0.))
                                continue;
                              p.normals[0] = g_a / g_a.norm();
                              p.normals[1] = -g_b / g_b.norm();
                              p.normals[2] = p.normals[0] + p.normals[1];
                              if (!(p.normals[2].norm() > 1e-12))
                                p.normals[2] = p.normals[0];
                              p.normals[2] /= p.normals[2].norm();
                              p.preference_a =
                                std::clamp(0.5 + 50. *
                                                   (g_a.norm() - g_b.norm()) /
                                                   (g_a.norm() + g_b.norm()),
                                           0.,
                                           1.);
                              pairs[{p.dofs_a[0], b}] = p;
                            }
                      });

      // The extremes of the points' domains along each candidate normal,
      // per pair: on dof a_0 the largest x.n + l of body a, on dof b_0 the
      // largest -(x.n - l) of body b, over the points whose cell holds the
      // node (GIMP: that give it mass).
      const double lowest = -std::numeric_limits<double>::max();
      for (unsigned int a = 0; a < n_fields; ++a)
        for (unsigned int b = a + 1; b < n_fields; ++b)
          {
            std::vector<std::vector<double>> local(
              n_candidates, std::vector<double>(relevant.n_elements(), lowest));
            bool any = false;
            for (const auto &c : cells)
              {
                const unsigned int field = c.field;
                if (field != a && field != b)
                  continue;
                for_each_node(
                  c,
                  [&](const unsigned int j,
                      const dealii::Point<dim> &,
                      const auto &dofs) {
                    const auto it = pairs.find({dofs[a * dim], b});
                    if (it == pairs.end())
                      return;
                    any = true;
                    const auto slot =
                      relevant.index_within_set(dofs[field * dim]);
                    for (unsigned int q = 0; q < c.n; ++q)
                      {
                        const unsigned int k = c.first + q;
                        // (GIMP: not a point whose domain only touches the
                        // node's support, weight 0 up to round-off)
                        if (gimp && !(shape_values[k * n_nodes + j] > 1e-10))
                          continue;
                        const double volume = point_volume(k);
                        const double l =
                          0.5 * std::pow(std::max(volume, 0.), 1. / dim);
                        for (unsigned int i = 0; i < n_candidates; ++i)
                          {
                            const double xn = particles[k]->get_location() *
                                              it->second.normals[i];
                            const double value =
                              field == a ? xn + l : -(xn - l);
                            local[i][slot] = std::max(local[i][slot], value);
                          }
                      }
                  });
              }
            if (!dealii::Utilities::MPI::logical_or(any, comm))
              continue;
            std::vector<std::vector<double>> result(n_candidates);
            for (unsigned int i = 0; i < n_candidates; ++i)
              result[i] = max_to_owners(owned, relevant, local[i], comm);
            for (const auto &entry : pairs)
              {
                const Pair &p = entry.second;
                if (p.a != a || p.b != b || !owned.is_element(p.dofs_a[0]))
                  continue;
                // the normal of the larger volume gradient (Nairn 2013),
                // unless another candidate separates the domains by more
                // than the margin (the preferred one is tilted: its
                // domains overlap). The choice is made continuous, so that
                // mirrored nodes get mirrored normals (a hard switch
                // decided on rounding where the margin was nearly met):
                // the preference is shared between a's and b's normal
                // where their gradients are about equal, and the
                // candidates within tau of the best biased gap are
                // blended, with weights falling linearly from 1 (the best)
                // to 0 (tau behind)
                const auto gap = [&](const unsigned int i) {
                  const double top_a =
                    result[i][owned.index_within_set(p.dofs_a[0])];
                  const double top_b =
                    result[i][owned.index_within_set(p.dofs_b[0])];
                  return (top_a <= lowest || top_b <= lowest) ? lowest :
                                                                -top_b - top_a;
                };
                const double margin =
                  body_normal_margin * grid.minimal_cell_diameter;
                const double                           tau  = 0.25 * margin;
                const std::array<double, n_candidates> bias = {
                  {margin * p.preference_a,
                   margin * (1. - p.preference_a),
                   0.}};
                std::array<double, n_candidates> score;
                double                           top = lowest;
                for (unsigned int i = 0; i < n_candidates; ++i)
                  {
                    score[i] = gap(i) <= lowest ? lowest : gap(i) + bias[i];
                    top      = std::max(top, score[i]);
                  }
                if (top <= lowest)
                  continue;
                dealii::Tensor<1, dim> normal;
                double                 weights = 0., blended_gap = 0.;
                for (unsigned int i = 0; i < n_candidates; ++i)
                  if (score[i] > lowest)
                    {
                      const double w =
                        std::clamp(1. + (score[i] - top) / tau, 0., 1.);
                      normal += w * p.normals[i];
                      blended_gap += w * gap(i);
                      weights += w;
                    }
                if (!(normal.norm() > 1e-12 * weights))
                  continue;
                ContactNode node;
                node.gap    = blended_gap / weights;
                node.normal = normal / normal.norm();
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    node.dofs.push_back(p.dofs_a[d]);
                  }
                for (unsigned int d = 0; d < dim; ++d)
                  node.dofs.push_back(p.dofs_b[d]);
                node.stiffness =
                  body_penalty *
                  std::min(nodal_mass(p.dofs_a[0]), nodal_mass(p.dofs_b[0])) *
                  newmark.mass_factor(dt);
                node.key = carried_key(p.vertex, a, b);
                if (const auto it = carried.find(node.key); it != carried.end())
                  node.carried = it->second;
                contact_nodes.push_back(node);
              }
          }
    }


    template <int dim>
    typename MPMSolver<dim>::ContactForce
    MPMSolver<dim>::body_contact_force(
      const ContactNode                           &node,
      const dealii::TrilinosWrappers::MPI::Vector &du) const
    {
      // relative increment of b against a
      dealii::Tensor<1, dim> jump;
      for (unsigned int d = 0; d < dim; ++d)
        jump[d] = du(node.dofs[dim + d]) - du(node.dofs[d]);
      return body_contact_force(node, jump);
    }


    template <int dim>
    typename MPMSolver<dim>::ContactForce
    MPMSolver<dim>::body_contact_force(const ContactNode            &node,
                                       const dealii::Tensor<1, dim> &jump) const
    {
      ContactForce result;
      const auto  &n = node.normal;
      const double k = node.stiffness;
      // the pressure carried from the last step (carry contact forces),
      // which the approach of this step raises; else a gap the bodies may
      // close within the step, where a negative one (the domains overlap
      // at the start) is not pushed out: only the approach of this step
      // is resisted
      const double carried_pressure = node.carried * n;
      const double pressure         = carried_pressure > 0. ?
                                        carried_pressure - k * (jump * n) :
                                        -k * (std::max(node.gap, 0.) + jump * n);
      if (!(pressure > 0.))
        return result;
      result.active   = true;
      result.pressure = pressure;
      // force on b (on a: its negative): p n + t
      result.force                    = result.pressure * n;
      const dealii::Tensor<2, dim> nn = dealii::outer_product(n, n);
      result.dforce                   = -k * nn;
      if (body_friction > 0.)
        {
          // stick penalty on the tangential increment, from the carried
          // tangential force f_t (on the current tangent plane), bounded
          // by mu p: the trial force -k sigma with the slip sigma = s -
          // f_t / k of the spring
          const dealii::Tensor<1, dim> s = jump - (jump * n) * n;
          const dealii::Tensor<1, dim> sigma =
            s - (node.carried - carried_pressure * n) / k;
          const dealii::Tensor<1, dim> trial = -k * sigma;
          const double                 limit = body_friction * result.pressure;
          dealii::Tensor<2, dim>       tangential_projector =
            dealii::unit_symmetric_tensor<dim>() - nn;
          if (trial.norm() <= limit)
            {
              result.force += trial;
              result.dforce += -k * tangential_projector;
            }
          else
            {
              const double                 sigma_norm = sigma.norm();
              const dealii::Tensor<1, dim> t          = sigma / sigma_norm;
              result.force -= limit * t;
              result.slip = true;
              // d(-mu p t)/d jump = -mu (dp/djump) t - mu p dt/djump,
              // dp/djump = -k n, dt/djump = (P - t t)/|sigma| P
              result.dforce += body_friction * k * dealii::outer_product(t, n);
              result.dforce -=
                limit / sigma_norm *
                (tangential_projector - dealii::outer_product(t, t));
            }
        }
      return result;
    }


    template <int dim>
    void
    MPMSolver<dim>::assemble_body_contact(
      const dealii::TrilinosWrappers::MPI::Vector &du,
      const bool                                   with_matrix)
    {
      dealii::FullMatrix<double> k_local(2 * dim, 2 * dim);
      dealii::Vector<double>     r_local(2 * dim);
      for (const auto &node : contact_nodes)
        {
          const ContactForce f = body_contact_force(node, du);
          if (!f.active)
            continue;
          k_local = 0.;
          for (unsigned int d = 0; d < dim; ++d)
            {
              r_local[d]       = -f.force[d];
              r_local[dim + d] = f.force[d];
              // K = -dR/du: R_b = f(jump), R_a = -f(jump), jump = u_b - u_a
              for (unsigned int e = 0; e < dim; ++e)
                {
                  const double D            = f.dforce[d][e];
                  k_local(dim + d, dim + e) = -D;
                  k_local(dim + d, e)       = D;
                  k_local(d, dim + e)       = D;
                  k_local(d, e)             = -D;
                }
            }
          if (with_matrix)
            constraints.distribute_local_to_global(
              k_local, r_local, node.dofs, matrix, residual);
          else
            constraints.distribute_local_to_global(r_local,
                                                   node.dofs,
                                                   residual);
        }
    }


    template <int dim>
    void
    MPMSolver<dim>::commit_body_contact()
    {
      if (!multi_field)
        return;
      // The work of the contact forces on the bodies over the step, by the
      // trapezoidal rule of the time integrator, (f(0) + f(j)) . j / 2 with
      // the converged jump j = du_b - du_a: the grid's energy changes by
      // it (Newmark's energy identity). The penalty starts every step
      // unloaded (f(0) = 0 unless the friction pulls), so what the contact
      // takes is dissipated: the inelastic nodal impact of the fields and
      // the friction between the bodies.
      // With 'carry contact forces' it includes what the carried springs
      // store, which they give back when the bodies separate.
      double              work   = 0.;
      unsigned int        active = 0;
      std::vector<double> carried_local;
      for (const auto &node : contact_nodes)
        {
          dealii::Tensor<1, dim> jump;
          for (unsigned int d = 0; d < dim; ++d)
            jump[d] =
              displacement(node.dofs[dim + d]) - displacement(node.dofs[d]);
          const ContactForce end = body_contact_force(node, jump);
          if (end.active)
            {
              ++active;
              if (body_carry)
                {
                  carried_local.insert(carried_local.end(),
                                       node.key.begin(),
                                       node.key.end());
                  for (unsigned int d = 0; d < dim; ++d)
                    carried_local.push_back(end.force[d]);
                }
            }
          work += 0.5 *
                  (body_contact_force(node, dealii::Tensor<1, dim>()).force +
                   end.force) *
                  jump;
        }
      accounts.body_contact_dissipation -=
        dealii::Utilities::MPI::sum(work, grid.mpi_communicator);
      n_active_contact_nodes =
        dealii::Utilities::MPI::sum(active, grid.mpi_communicator);
      // the committed forces on every rank (a node's owner may change)
      carried_contact.clear();
      if (body_carry)
        for (const auto &from_rank :
             dealii::Utilities::MPI::all_gather(grid.mpi_communicator,
                                                carried_local))
          carried_contact.insert(carried_contact.end(),
                                 from_rank.begin(),
                                 from_rank.end());
    }


    template <int dim>
    std::vector<double>
    MPMSolver<dim>::carried_key(const dealii::Point<dim> &vertex,
                                const unsigned int        a,
                                const unsigned int        b)
    {
      std::vector<double> key(dim + 2);
      for (unsigned int d = 0; d < dim; ++d)
        key[d] = vertex[d];
      key[dim]     = a;
      key[dim + 1] = b;
      return key;
    }


    // Explicit instantiation of the members defined in this file.
#define TALUS_INSTANTIATE(dim)                                                            \
  template void MPMSolver<dim>::set_body_contact(const BodyContact &);                    \
  template void MPMSolver<dim>::prepare_body_contact();                                   \
  template typename MPMSolver<dim>::ContactForce                                          \
  MPMSolver<dim>::body_contact_force(                                                     \
    const ContactNode &, const dealii::TrilinosWrappers::MPI::Vector &) const;            \
  template typename MPMSolver<dim>::ContactForce                                          \
                MPMSolver<dim>::body_contact_force(const ContactNode &,                   \
                                     const dealii::Tensor<1, dim> &) const; \
  template void MPMSolver<dim>::assemble_body_contact(                                    \
    const dealii::TrilinosWrappers::MPI::Vector &, const bool);                           \
  template void                MPMSolver<dim>::commit_body_contact();                     \
  template std::vector<double> MPMSolver<dim>::carried_key(                               \
    const dealii::Point<dim> &, const unsigned int, const unsigned int);

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
