#include <talus/base/input.h>
#include <talus/io/time_series.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace Talus
{
  namespace IO
  {
    template <int dim>
    void
    TimeSeries<dim>::open(const std::string              &filename,
                          const MPI_Comm                  communicator,
                          const std::vector<std::string> &boundary_names,
                          const bool                      error_column,
                          const unsigned int              n_bodies,
                          const bool                      body_contact_columns)
    {
      with_error        = error_column;
      with_body_contact = body_contact_columns;
      is_root   = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
      file_name = filename;
      if (is_root)
        file.open(filename);
      const int ok =
        dealii::Utilities::MPI::min(is_root ? (file ? 1 : 0) : 1, communicator);
      if (!is_root && ok)
        return;
      if (!ok)
        throw ExcInvalidInput("Cannot write the time series file <" + filename +
                              ">: check 'output directory' in subsection "
                              "<Output>.");
      file
        << "step,time,dt,newton_iterations,linear_iterations,mass,"
           "momentum_x,momentum_y,momentum_z,kinetic_energy,strain_energy,"
           "gravitational_energy,total_energy,lost_mass,plastic_dissipation,"
           "friction_dissipation,energy_balance,contact_force_x,"
           "contact_force_y,contact_force_z,volume,grid_kinetic_energy,"
           "max_grid_speed,reset_dissipation,transfer_dissipation,spring_energy,"
           "integrator_dissipation";
      for (const auto &name : boundary_names)
        {
          for (unsigned int d = 0; d < dim; ++d)
            file << ',' << name << "_force_"
                 << "xyz"[d];
          file << ',' << name << "_normal_force," << name
               << "_tangential_force," << name << "_penetration," << name
               << "_friction_dissipation";
        }
      for (unsigned int b = 0; n_bodies > 1 && b < n_bodies; ++b)
        {
          const std::string body = "body" + std::to_string(b + 1);
          file << ',' << body << "_mass";
          for (unsigned int d = 0; d < dim; ++d)
            file << ',' << body << "_momentum_"
                 << "xyz"[d];
          file << ',' << body << "_kinetic_energy," << body << "_strain_energy";
        }
      if (with_body_contact)
        file << ",body_contact_dissipation,body_contact_nodes";
      if (with_error)
        file << ",error_estimate";
      file << '\n';
      file << std::setprecision(12);
    }


    template <int dim>
    void
    TimeSeries<dim>::copy_to(const std::string &target)
    {
      if (!is_root)
        return;
      file.flush();
      // (a failed copy leaves the file out of the checkpoint, which its
      // resume reports; no exception on one rank inside a collective write)
      std::error_code error;
      std::filesystem::copy_file(
        file_name,
        target,
        std::filesystem::copy_options::overwrite_existing,
        error);
      if (error)
        std::cerr << "Warning: cannot copy <" << file_name << "> to <" << target
                  << ">: " << error.message() << '\n';
    }


    template <int dim>
    void
    TimeSeries<dim>::resume(const std::string &filename,
                            const MPI_Comm     communicator,
                            const std::string &saved,
                            const bool         error_column,
                            const bool         body_contact_columns)
    {
      with_error        = error_column;
      with_body_contact = body_contact_columns;
      is_root   = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
      file_name = filename;
      int ok    = 1;
      if (is_root)
        {
          file.close();
          std::error_code error;
          std::filesystem::copy_file(
            saved,
            filename,
            std::filesystem::copy_options::overwrite_existing,
            error);
          if (!error)
            file.open(filename, std::ios::out | std::ios::app);
          ok = !error && file ? 1 : 0;
        }
      ok = dealii::Utilities::MPI::min(ok, communicator);
      if (!ok)
        throw ExcInvalidInput("Cannot write the time series file <" + filename +
                              "> (a copy of <" + saved +
                              ">): check 'output directory' in subsection "
                              "<Output>.");
      file << std::setprecision(12);
    }


    template <int dim>
    void
    TimeSeries<dim>::write(const unsigned int           step,
                           const double                 time,
                           const double                 dt,
                           const MPM::NewtonResult     &newton,
                           const MPM::Diagnostics<dim> &d,
                           const double                 lost_mass,
                           const double                 error)
    {
      if (!is_root)
        return;
      file << step << ',' << time << ',' << dt << ',' << newton.iterations
           << ',' << newton.linear_iterations << ',' << d.mass;
      for (unsigned int i = 0; i < 3; ++i)
        file << ',' << (i < dim ? d.momentum[i] : 0.);
      file << ',' << d.kinetic_energy << ',' << d.strain_energy << ','
           << d.gravitational_energy << ','
           << d.kinetic_energy + d.strain_energy + d.gravitational_energy << ','
           << lost_mass << ',' << d.plastic_dissipation << ','
           << d.friction_dissipation << ',' << d.energy_balance();
      for (unsigned int i = 0; i < 3; ++i)
        file << ',' << (i < dim ? d.contact_force[i] : 0.);
      file << ',' << d.volume << ',' << d.grid_kinetic_energy << ','
           << d.max_grid_speed << ',' << d.reset_dissipation << ','
           << d.transfer_dissipation << ',' << d.spring_energy() << ','
           << d.integrator_dissipation;
      for (unsigned int k = 0; k < d.boundaries.size(); ++k)
        {
          const auto &b = d.boundaries[k];
          for (unsigned int i = 0; i < dim; ++i)
            file << ',' << b.force[i];
          file << ',' << b.normal_force << ',' << b.tangential_force << ','
               << b.penetration << ','
               << (k < d.boundary_friction_dissipation.size() ?
                     d.boundary_friction_dissipation[k] :
                     0.);
        }
      for (unsigned int b = 0; d.body_mass.size() > 1 && b < d.body_mass.size();
           ++b)
        {
          file << ',' << d.body_mass[b];
          for (unsigned int i = 0; i < dim; ++i)
            file << ',' << d.body_momentum[b][i];
          file << ',' << d.body_kinetic_energy[b] << ','
               << d.body_strain_energy[b];
        }
      if (with_body_contact)
        file << ',' << d.body_contact_dissipation << ','
             << d.body_contact_nodes;
      if (with_error)
        file << ',' << error;
      file << '\n';
      file.flush();
    }


    template class TimeSeries<2>;
    template class TimeSeries<3>;
  } // namespace IO
} // namespace Talus
