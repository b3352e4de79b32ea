#include <talus/base/input.h>
#include <talus/mpm/contact_time_integration.h>
#include <talus/mpm/mpm_solver.h>

#include <deal.II/lac/vector.h>

namespace Talus
{
  namespace MPM
  {
    void
    ContactTimeIntegration::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry(
        "contact force in time",
        "trapezoidal",
        dealii::Patterns::Selection("trapezoidal|end of step"),
        "How the penalty force of unilateral contact (conditions 'contact' "
        "and 'friction' of boundaries of boundary particles at rest, on "
        "either contact side) acts within a dynamic step. 'trapezoidal': "
        "like every other force, through Newmark's a_n and a_{n+1}; a "
        "contact that closes within a step then throws the point back with "
        "up to three times its impact speed (the energy the balance does "
        "not book at such an impact: 764 J of 1.5 kJ in "
        "tests/mpm/drop_contact_onset_points). 'end of step': with its end "
        "value over the whole step (the fully implicit contact force of "
        "Doyen, Ern and Piperno 2011): a contact that closes within the "
        "step stops or reflects the point but never speeds it up, and the "
        "contact's energy error k |dg|^2 / 2 is dissipation, booked as the "
        "boundary's. Needs 'start acceleration = from forces' (the "
        "acceleration of the other forces starts the step), so not with "
        "grid friction boundaries. Coupling interfaces follow 'interface "
        "force in time' in subsection Coupling. The other boundaries of "
        "boundary particles (moving ones, fixed, slip, Nitsche, Lagrange "
        "multipliers) keep the trapezoidal rule, and the nodes of their "
        "points the projected start acceleration. Lumped mass only; "
        "an input in which no boundary would use it is rejected. "
        "doc/theory.md, 'Contact force in time'.");
    }


    void
    ContactTimeIntegration::parse_parameters(dealii::ParameterHandler &prm)
    {
      end_of_step = prm.get("contact force in time") == "end of step";
    }


    template <int dim>
    void
    MPMSolver<dim>::end_contact_force(
      const dealii::TrilinosWrappers::MPI::Vector *du,
      dealii::TrilinosWrappers::MPI::Vector       &f) const
    {
      // f = sum_b N^T f_b(du_b) over the boundary points whose contact
      // force acts with its end value (BoundaryPoint::end_of_step), with
      // the constraints' distribution (hanging nodes to their masters)
      const auto        &fe            = grid.fe;
      const unsigned int dofs_per_cell = fe.dofs_per_cell;
      f.reinit(grid.locally_owned_dofs, grid.mpi_communicator);
      dealii::Vector<double> f_local(dofs_per_cell);
      for (const auto &c : boundary_cells)
        {
          bool any = false;
          for (unsigned int b = 0; b < c.n_boundary; ++b)
            any = any || boundary_points[c.first_boundary + b].end_of_step;
          if (!any)
            continue;
          f_local = 0.;
          for (unsigned int b = 0; b < c.n_boundary; ++b)
            {
              const BoundaryPoint &bp = boundary_points[c.first_boundary + b];
              if (!bp.end_of_step)
                continue;
              dealii::Tensor<1, dim> du_b;
              if (du != nullptr)
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    const auto ci = fe.system_to_component_index(i);
                    du_b[ci.first] +=
                      bp.N[ci.second] * conforming_value(*du, c.dofs[i]);
                  }
              const BoundaryForce bf = boundary_force(bp, du_b);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto ci = fe.system_to_component_index(i);
                  f_local[i] += bp.N[ci.second] * bf.force[ci.first];
                }
            }
          constraints.distribute_local_to_global(f_local, c.dofs, f);
        }
      f.compress(dealii::VectorOperation::add);
    }


    template <int dim>
    double
    MPMSolver<dim>::end_contact_factor() const
    {
      return quasi_static ? 1. : 1. / (2. * newmark.beta);
    }


    template <int dim>
    bool
    MPMSolver<dim>::end_of_step_contact(
      const Boundaries::BoundaryDescription<dim> &desc) const
    {
      using Boundaries::Condition;
      // (a moving boundary only as a coupling interface that asks for it:
      // the structure then takes the end value too)
      return uses_end_contact_force() &&
             (!desc.moving || desc.end_of_step_force) && !desc.augmented &&
             !desc.lagrange_multiplier && !desc.nitsche &&
             (desc.condition == Condition::contact ||
              desc.condition == Condition::friction);
    }


    template <int dim>
    bool
    MPMSolver<dim>::uses_end_contact_force() const
    {
      return boundary_particles != nullptr &&
             contact_time_integration.end_of_step && !quasi_static &&
             !consistent_mass;
    }


    template <int dim>
    void
    MPMSolver<dim>::check_contact_time_integration(
      const Boundaries::BoundaryParticles<dim> &boundaries) const
    {
      // a coupling interface asked for the end-of-step force
      // (Coupling/interface force in time) must get it: the structure
      // takes the end value whatever the MPM does
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &desc = boundaries.boundary(b);
          if (!desc.end_of_step_force || end_of_step_contact(desc))
            continue;
          if (!uses_end_contact_force())
            InputFile::reject(
              "Solver",
              "contact force in time",
              contact_time_integration.end_of_step ? "end of step" :
                                                     "trapezoidal",
              "'end of step' in a dynamic analysis with 'mass matrix = "
              "lumped' when 'interface force in time = end of step' in "
              "subsection Coupling (boundary '" +
                desc.name + "')");
          InputFile::reject(
            "Coupling",
            "interface force in time",
            "end of step",
            "'trapezoidal' for interface boundary '" + desc.name +
              "': 'end of step' needs 'condition = contact' or "
              "'friction' imposed by the penalty method (not Nitsche, the "
              "augmented Lagrangian or Lagrange multipliers)");
        }
      // 'end of step' that no boundary would use is an error, not a
      // silent trapezoidal rule
      if (contact_time_integration.end_of_step)
        {
          bool used = false;
          for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
            used = used || end_of_step_contact(boundaries.boundary(b));
          if (!used)
            InputFile::reject(
              "Solver",
              "contact force in time",
              "end of step",
              "'trapezoidal' here: 'end of step' acts on boundaries of "
              "boundary particles at rest (or coupling interfaces with "
              "'interface force in time = end of step') with 'condition "
              "= contact' or 'friction' and the penalty method, in a "
              "dynamic analysis with 'mass matrix = lumped'; this input "
              "has none (or is quasi-static, or uses the consistent "
              "mass)");
        }
      // (boundaries whose contact force acts with its end value are not
      // in the start acceleration: ContactTimeIntegration)
      if (!start_acceleration_from_forces)
        for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
          if (end_of_step_contact(boundaries.boundary(b)))
            InputFile::reject(
              "Solver",
              "contact force in time",
              "end of step",
              "'trapezoidal', or 'end of step' together with 'start "
              "acceleration = from forces' (boundary '" +
                boundaries.boundary(b).name +
                "'): the points' projected acceleration then misses the "
                "contact force that balances the other forces at a point in "
                "contact, and the difference does work (measured: 1.2 kJ of "
                "45 kJ released on a granular slide)");
      // Without end-of-step contact the start acceleration from the forces
      // would mix with the projected one at every boundary (the nodes of
      // boundary points keep it, newton.cc), which is less accurate than
      // either (doc/theory.md, "Contact force in time")
      if (!boundaries.empty() && start_acceleration_from_forces &&
          !contact_time_integration.end_of_step)
        InputFile::reject("Solver",
                          "start acceleration",
                          "from forces",
                          "'projected' with boundary particles, or 'from "
                          "forces' together with 'contact force in time = "
                          "end of step' (the nodes of boundaries that keep "
                          "the trapezoidal rule then keep the projected "
                          "acceleration)");
    }


#define TALUS_INSTANTIATE(dim)                                    \
  template void MPMSolver<dim>::end_contact_force(                \
    const dealii::TrilinosWrappers::MPI::Vector *du,              \
    dealii::TrilinosWrappers::MPI::Vector       &f) const;              \
  template double MPMSolver<dim>::end_contact_factor() const;     \
  template bool   MPMSolver<dim>::uses_end_contact_force() const; \
  template bool   MPMSolver<dim>::end_of_step_contact(            \
    const Boundaries::BoundaryDescription<dim> &desc) const;    \
  template void MPMSolver<dim>::check_contact_time_integration(   \
    const Boundaries::BoundaryParticles<dim> &boundaries) const;

    TALUS_INSTANTIATE(2)
    TALUS_INSTANTIATE(3)
#undef TALUS_INSTANTIATE
  } // namespace MPM
} // namespace Talus
