#include <talus/base/input.h>
#include <talus/mpm/mpm_problem.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    MPMProblem<dim>::MPMProblem(const MPI_Comm       communicator,
                                const NewmarkBeta   &newmark,
                                dealii::TimerOutput &timer)
      : communicator(communicator)
      , newmark(newmark)
      , timer(timer)
    {}


    template <int dim>
    void
    MPMProblem<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                        const unsigned int        n_boundaries)
    {
      BackgroundGrid<dim>::declare_parameters(prm);
      MaterialPoints<dim>::declare_parameters(prm);
      InitialStress<dim>::declare_parameters(prm);
      Materials::declare_parameters(prm);
      MPMSolver<dim>::declare_parameters(prm);
      Boundaries::BoundaryParticles<dim>::declare_parameters(prm, n_boundaries);
    }


    template <int dim>
    void
    MPMProblem<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                      const unsigned int        refinement)
    {
      background_grid = std::make_unique<BackgroundGrid<dim>>(communicator);
      background_grid->parse_parameters_and_create(prm);
      if (refinement > 0)
        {
          auto &grid = *background_grid;
          grid.triangulation.refine_global(refinement);
          grid.cell_extent /= std::pow(2., refinement);
          grid.minimal_cell_diameter /= std::pow(2., refinement);
          grid.setup_dofs();
        }

      constitutive_model = Materials::create_model(prm);
      // the solver reads only the dim x dim x dim x dim block of dP/dF
      constitutive_model->set_tangent_dimension(dim);
      prm.enter_subsection("Material");
      material_density = get_positive(prm, "Material", "density");
      prm.leave_subsection();

      material_points = std::make_unique<MaterialPoints<dim>>(*background_grid);
      material_points->parse_parameters(prm);
      initial_stress_field.parse_parameters(prm);

      mpm_solver = std::make_unique<MPMSolver<dim>>(*background_grid,
                                                    *material_points,
                                                    *constitutive_model,
                                                    newmark,
                                                    timer);
      mpm_solver->parse_parameters(prm);

      boundary_particles =
        std::make_unique<Boundaries::BoundaryParticles<dim>>(*background_grid);
      boundary_particles->parse_parameters(prm);
    }


    template <int dim>
    void
    MPMProblem<dim>::setup()
    {
      Assert(mpm_solver, dealii::ExcMessage("parse_parameters() first"));
      const auto &model = *constitutive_model;
      // contact data (material-point contact) for every boundary
      material_points->set_contact_slots(boundary_particles->n_boundaries());
      material_points->generate(material_density,
                                model.n_history_variables(),
                                [&](const dealii::ArrayView<double> &h) {
                                  model.initialize_history(h);
                                });
      initial_stress_field.apply(*material_points,
                                 model,
                                 mpm_solver->gravity(),
                                 communicator,
                                 mpm_solver->load_ramp());
      mpm_solver->setup();
      boundary_particles->generate(model.p_wave_modulus());
      mpm_solver->attach_boundary_particles(*boundary_particles);
    }


    template <int dim>
    void
    MPMProblem<dim>::initialize(const double time)
    {
      mpm_solver->initialize_acceleration(time);
    }


    template <int dim>
    void
    MPMProblem<dim>::prepare_step(const double new_time, const double dt)
    {
      mpm_solver->prepare_step(new_time, dt);
    }


    template <int dim>
    NewtonResult
    MPMProblem<dim>::solve_step()
    {
      return mpm_solver->solve_step();
    }


    template <int dim>
    void
    MPMProblem<dim>::commit_step()
    {
      mpm_solver->commit_step();
    }


    template <int dim>
    StepLosses<dim>
    MPMProblem<dim>::take_losses()
    {
      StepLosses<dim> l;
      l.region             = material_points->take_lost_region();
      l.n_points           = material_points->take_lost_count();
      l.mass               = material_points->take_lost_mass();
      l.boundary_particles = boundary_particles->take_lost_per_boundary();
      return l;
    }


    template <int dim>
    void
    MPMProblem<dim>::save_state()
    {
      material_points->save_state();
      boundary_particles->save_state();
      mpm_solver->save_state();
    }


    template <int dim>
    void
    MPMProblem<dim>::restore_state()
    {
      material_points->restore_state();
      boundary_particles->restore_state();
      mpm_solver->restore_state();
    }


    template <int dim>
    void
    MPMProblem<dim>::print_summary(const dealii::ConditionalOStream &out) const
    {
      const auto &grid       = *background_grid;
      const auto &boundaries = *boundary_particles;
      out << "  background grid: " << grid.triangulation.n_global_active_cells()
          << " cells, " << grid.dof_handler.n_dofs() << " DoFs\n"
          << "  material points: " << material_points->n_global_points() << '\n'
          << "  material: " << constitutive_model->name() << ", density "
          << material_density << " kg/m^3\n";
      if (initial_stress_field.enabled())
        out << "  initial stress: " << initial_stress_field.description()
            << '\n';
      if (mpm_solver->ghost_penalty() > 0.)
        out << "  ghost penalty: factor " << mpm_solver->ghost_penalty()
            << " (gamma = factor * P-wave modulus), on the faces of cut "
               "cells\n";
      if (boundaries.empty())
        return;
      std::vector<unsigned int> count(boundaries.n_boundaries(), 0);
      for (const auto &p : boundaries.particle_handler())
        ++count[static_cast<unsigned int>(
          p.get_properties()
            [Boundaries::BoundaryParticleProperties<dim>::boundary])];
      MPI_Allreduce(MPI_IN_PLACE,
                    count.data(),
                    count.size(),
                    MPI_UNSIGNED,
                    MPI_SUM,
                    communicator);
      const auto number = [](const double x) {
        std::ostringstream o;
        o << x;
        return o.str();
      };
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &desc = boundaries.boundary(b);
          out << "  boundary " << desc.name << ": " << desc.geometry << ", "
              << count[b] << " boundary particles, "
              << (desc.condition == Boundaries::Condition::fixed ?
                    "fixed" :
                  desc.condition == Boundaries::Condition::slip ?
                    "slip" :
                  desc.condition == Boundaries::Condition::contact ?
                    "contact" :
                    "friction mu = " + number(desc.friction_coefficient))
              << (desc.augmented ?
                    ", augmented Lagrangian, penalty" :
                  desc.lagrange_multiplier ?
                    ", Lagrange multipliers, trial-force" :
                  desc.nitsche ?
                    ", Nitsche (theta = " + number(desc.nitsche_theta) +
                      "), stabilisation" :
                    ", penalty")
              << " beta = " << std::setprecision(4) << desc.beta << " Pa/m"
              << std::defaultfloat << '\n';
        }
    }


    template class MPMProblem<2>;
    template class MPMProblem<3>;
  } // namespace MPM
} // namespace Talus
