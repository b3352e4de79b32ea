#include <talus/mpm/diagnostics.h>
#include <talus/mpm/mpm_solver.h>
#include <talus/mpm/point_tensors.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace Talus
{
  namespace MPM
  {
    using internal::embed;
    using internal::read_tensor;


    template <int dim>
    Diagnostics<dim>
    MPMSolver<dim>::compute_diagnostics() const
    {
      using Properties = MaterialPointProperties<dim>;
      Diagnostics<dim> d;
      double           point_speed = 0.;
      // the history variable "plastic_dissipation" of each material
      const auto dissipation_of = [](const Materials::ConstitutiveModel &m) {
        int        index = -1;
        const auto names = m.history_names();
        for (unsigned int h = 0; h < names.size(); ++h)
          if (names[h] == "plastic_dissipation")
            index = h;
        return index;
      };
      const int        single_dissipation = dissipation_of(model);
      std::vector<int> material_dissipation(materials.size(), -1);
      for (unsigned int m = 0; m < materials.size(); ++m)
        if (materials[m] != nullptr)
          material_dissipation[m] = dissipation_of(*materials[m]);
      const unsigned int n_bodies = points.n_bodies();
      if (n_bodies > 1)
        {
          d.body_mass.assign(n_bodies, 0.);
          d.body_momentum.assign(n_bodies, dealii::Tensor<1, dim>());
          d.body_kinetic_energy.assign(n_bodies, 0.);
          d.body_strain_energy.assign(n_bodies, 0.);
        }
      for (const auto &p : points.particle_handler())
        {
          const int dissipation_index =
            materials.empty() ?
              single_dissipation :
              material_dissipation[points.material_of(p.get_properties())];
          if (dissipation_index >= 0)
            d.plastic_dissipation +=
              p.get_properties()[Properties::initial_volume] *
              p.get_properties()[Properties::history + dissipation_index];
          const auto   props = p.get_properties();
          const double m     = props[Properties::mass];
          d.mass += m;
          double v2 = 0.;
          for (unsigned int i = 0; i < dim; ++i)
            {
              const double v = props[Properties::velocity + i];
              d.momentum[i] += m * v;
              v2 += v * v;
              d.gravitational_energy -=
                m * gravity_vector[i] * p.get_location()[i];
            }
          d.kinetic_energy += 0.5 * m * v2;
          point_speed = std::max(point_speed, std::sqrt(v2));
          d.volume += props[Properties::initial_volume] *
                      dealii::determinant(
                        read_tensor<dim>(props, Properties::deformation));
          const auto  &point_model = model_of(props);
          const double point_strain_energy =
            props[Properties::initial_volume] *
            point_model.energy_density(
              embed<dim>(read_tensor<dim>(props, Properties::deformation)),
              dealii::ArrayView<const double>(
                props.data() + Properties::history,
                point_model.n_history_variables()));
          d.strain_energy += point_strain_energy;
          if (n_bodies > 1)
            {
              const unsigned int b = points.body_of(props);
              d.body_mass[b] += m;
              for (unsigned int i = 0; i < dim; ++i)
                d.body_momentum[b][i] += m * props[Properties::velocity + i];
              d.body_kinetic_energy[b] += 0.5 * m * v2;
              d.body_strain_energy[b] += point_strain_energy;
            }
        }
      for (unsigned int b = 0; b < d.body_mass.size(); ++b)
        {
          const MPI_Comm comm = grid.mpi_communicator;
          d.body_mass[b] = dealii::Utilities::MPI::sum(d.body_mass[b], comm);
          d.body_momentum[b] =
            dealii::Utilities::MPI::sum(d.body_momentum[b], comm);
          d.body_kinetic_energy[b] =
            dealii::Utilities::MPI::sum(d.body_kinetic_energy[b], comm);
          d.body_strain_energy[b] =
            dealii::Utilities::MPI::sum(d.body_strain_energy[b], comm);
        }
      const MPI_Comm comm = grid.mpi_communicator;
      d.mass              = dealii::Utilities::MPI::sum(d.mass, comm);
      d.momentum          = dealii::Utilities::MPI::sum(d.momentum, comm);
      d.kinetic_energy    = dealii::Utilities::MPI::sum(d.kinetic_energy, comm);
      d.strain_energy     = dealii::Utilities::MPI::sum(d.strain_energy, comm);
      d.gravitational_energy =
        dealii::Utilities::MPI::sum(d.gravitational_energy, comm);
      d.plastic_dissipation =
        dealii::Utilities::MPI::sum(d.plastic_dissipation, comm);
      d.volume                   = dealii::Utilities::MPI::sum(d.volume, comm);
      d.friction_dissipation     = accounts.friction_dissipation;
      d.reset_dissipation        = accounts.reset_dissipation;
      d.transfer_dissipation     = accounts.transfer_dissipation;
      d.integrator_dissipation   = accounts.integrator_dissipation;
      d.body_contact_dissipation = accounts.body_contact_dissipation;
      d.body_contact_nodes       = n_active_contact_nodes;
      d.boundary_friction_dissipation = accounts.boundary_friction_dissipation;
      d.contact_force                 = contact_force;
      if (grid_kinetic_energy >= 0.)
        {
          d.grid_kinetic_energy = grid_kinetic_energy;
          d.max_grid_speed      = max_grid_speed;
        }
      else
        {
          // no step yet: the points' velocities are the initial field
          d.grid_kinetic_energy = d.kinetic_energy;
          d.max_grid_speed = dealii::Utilities::MPI::max(point_speed, comm);
        }
      if (boundary_particles != nullptr)
        d.boundaries = boundary_particles->resultants();
      return d;
    }


    template Diagnostics<2>
    MPMSolver<2>::compute_diagnostics() const;
    template Diagnostics<3>
    MPMSolver<3>::compute_diagnostics() const;
  } // namespace MPM
} // namespace Talus
