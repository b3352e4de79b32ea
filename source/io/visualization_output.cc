#include <talus/base/input.h>
#include <talus/io/visualization_output.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <deal.II/particles/data_out.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace Talus
{
  namespace IO
  {
    template <int dim>
    void
    VisualizationOutput<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Output");
      {
        prm.declare_entry("output directory",
                          "output",
                          Patterns::DirectoryName(),
                          "Directory for all output files (created if "
                          "missing).");
        prm.declare_entry("output interval",
                          "0",
                          Patterns::Double(0),
                          "Simulated time between two visualization outputs "
                          "and progress lines [s], >= 0; 0: every step.");
        prm.declare_entry("format",
                          "vtu",
                          Patterns::Selection("vtu|hdf5|none"),
                          "'vtu': VTU pieces + PVTU + PVD (ParaView); 'hdf5': "
                          "one HDF5 file per output + an XDMF index, "
                          "written in parallel by the ranks that own material "
                          "points (grid cells); "
                          "'none': no visualization files (the CSV time "
                          "series is always written).");
        prm.declare_entry("write grid",
                          "true",
                          Patterns::Bool(),
                          "Also write the background grid with the number of "
                          "material points per cell, the subdomain and the "
                          "nodal grid velocity of the last step (the "
                          "velocity the points moved with).");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    VisualizationOutput<dim>::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      output_directory = prm.get("output directory");
      output_interval  = prm.get_double("output interval");
      format           = prm.get("format");
      write_grid       = prm.get_bool("write grid");
      enabled          = format != "none";
      prm.leave_subsection();
    }


    template <int dim>
    void
    VisualizationOutput<dim>::initialize(const MPI_Comm communicator)
    {
      int ok = 1;
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::error_code error;
          std::filesystem::create_directories(output_directory, error);
          ok = error ? 0 : 1;
        }
      ok = dealii::Utilities::MPI::min(ok, communicator);
      if (!ok)
        InputFile::reject("Output",
                          "output directory",
                          output_directory,
                          "the directory cannot be created");
    }


    template <int dim>
    bool
    VisualizationOutput<dim>::due(const double time) const
    {
      return time >= last_output_time + output_interval * (1. - 1e-9);
    }


    template <int dim>
    void
    VisualizationOutput<dim>::write(
      const double                                 time,
      const MPM::BackgroundGrid<dim>              &grid,
      const MPM::MaterialPoints<dim>              &points,
      const dealii::TrilinosWrappers::MPI::Vector *grid_velocity)
    {
      last_output_time = time;
      if (!enabled)
        return;
      const MPI_Comm comm = grid.mpi_communicator;
      using Properties    = MPM::MaterialPointProperties<dim>;
      const auto &handler = points.particle_handler();

      dealii::Particles::DataOut<dim> particle_out;
      particle_out.build_patches(
        handler,
        Properties::names(points.n_history(),
                          points.n_contact_slots(),
                          points.has_body_property()),
        Properties::interpretation(points.n_history(),
                                   points.n_contact_slots(),
                                   points.has_body_property()));

      dealii::DataOut<dim>  grid_out;
      dealii::Vector<float> n_points(grid.triangulation.n_active_cells());
      dealii::Vector<float> subdomain(grid.triangulation.n_active_cells());
      if (write_grid)
        {
          for (const auto &cell : grid.triangulation.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                n_points(cell->active_cell_index()) =
                  handler.n_particles_in_cell(cell);
                subdomain(cell->active_cell_index()) = cell->subdomain_id();
              }
          grid_out.attach_dof_handler(grid.dof_handler);
          grid_out.add_data_vector(n_points,
                                   "material_points",
                                   dealii::DataOut<dim>::type_cell_data);
          grid_out.add_data_vector(subdomain,
                                   "subdomain",
                                   dealii::DataOut<dim>::type_cell_data);
          if (grid_velocity != nullptr && grid_velocity->size() > 0)
            {
              // one vector per velocity field (multi-velocity-field
              // contact: grid_velocity_1, _2, ... per body)
              const unsigned int       n_fields = grid.n_velocity_fields();
              std::vector<std::string> names;
              for (unsigned int f = 0; f < n_fields; ++f)
                for (unsigned int d = 0; d < dim; ++d)
                  names.push_back(n_fields == 1 ?
                                    std::string("grid_velocity") :
                                    "grid_velocity_" + std::to_string(f + 1));
              grid_out.add_data_vector(
                *grid_velocity,
                names,
                dealii::DataOut<dim>::type_dof_data,
                std::vector<dealii::DataComponentInterpretation::
                              DataComponentInterpretation>(
                  dim * n_fields,
                  dealii::DataComponentInterpretation::
                    component_is_part_of_vector));
            }
          grid_out.build_patches();
        }

      const std::string dir = output_directory + "/";
      if (format == "vtu")
        {
          // zlib's fastest level (as deal.II's step-37 and step-64 write):
          // deal.II's default, the best compression, took 4 % of the Bui
          // collapse's run time (doc/performance.md); the files grow by
          // about 4 %
          dealii::DataOutBase::VtkFlags flags;
          flags.compression_level = dealii::DataOutBase::VtkFlags::best_speed;
          particle_out.set_flags(flags);
          grid_out.set_flags(flags);
          const std::string pname = particle_out.write_vtu_with_pvtu_record(
            dir, "particles", counter, comm, 5);
          particle_records.emplace_back(time, pname);
          if (write_grid)
            {
              const std::string gname = grid_out.write_vtu_with_pvtu_record(
                dir, "grid", counter, comm, 5);
              grid_records.emplace_back(time, gname);
            }
          write_index(comm);
        }
      else
        {
          const std::string number =
            dealii::Utilities::int_to_string(counter, 5);
          {
            dealii::DataOutBase::DataOutFilter filter(
              dealii::DataOutBase::DataOutFilterFlags(false, true));
            particle_out.write_filtered_data(filter);
            write_hdf5(particle_out,
                       filter,
                       handler.n_locally_owned_particles() > 0,
                       "particles",
                       number,
                       time,
                       comm,
                       particle_xdmf);
          }
          if (write_grid)
            {
              dealii::DataOutBase::DataOutFilter filter(
                dealii::DataOutBase::DataOutFilterFlags(true, true));
              grid_out.write_filtered_data(filter);
              write_hdf5(grid_out,
                         filter,
                         grid.triangulation.n_locally_owned_active_cells() > 0,
                         "grid",
                         number,
                         time,
                         comm,
                         grid_xdmf);
            }
        }
      ++counter;
    }


    template <int dim>
    void
    VisualizationOutput<dim>::write_index(const MPI_Comm communicator) const
    {
      if (!enabled)
        return;
      const std::string dir = output_directory + "/";
      if (format == "vtu")
        {
          if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
            {
              std::ofstream pvd(dir + "particles.pvd");
              dealii::DataOutBase::write_pvd_record(pvd, particle_records);
              if (write_grid)
                {
                  std::ofstream gpvd(dir + "grid.pvd");
                  dealii::DataOutBase::write_pvd_record(gpvd, grid_records);
                }
            }
        }
      else
        {
          dealii::DataOut<dim> index;
          index.write_xdmf_file(particle_xdmf,
                                dir + "particles.xdmf",
                                communicator);
          if (write_grid)
            index.write_xdmf_file(grid_xdmf, dir + "grid.xdmf", communicator);
        }
    }


    template <int dim>
    template <typename DataOutType>
    void
    VisualizationOutput<dim>::write_hdf5(
      const DataOutType                        &data_out,
      const dealii::DataOutBase::DataOutFilter &filter,
      const bool                                has_data,
      const std::string                        &name,
      const std::string                        &number,
      const double                              time,
      const MPI_Comm                            comm,
      std::vector<dealii::XDMFEntry>           &entries) const
    {
      // deal.II 9.4's parallel HDF5 writer hangs when a rank of its
      // communicator has no patches (its collective calls no longer match:
      // measured with 2 ranks and all material points on one). Write with
      // the sub-communicator of the ranks that have data, and hand the
      // XDMF entry from the first of them to every rank, so that rank 0
      // writes the index whether or not it has data itself.
      const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
      const unsigned int first_with_data = dealii::Utilities::MPI::min(
        has_data ? rank : dealii::numbers::invalid_unsigned_int, comm);
      if (first_with_data == dealii::numbers::invalid_unsigned_int)
        return; // nothing to write on any rank (e.g. every point lost)
      MPI_Comm  writers;
      const int ierr = MPI_Comm_split(comm,
                                      has_data ? 0 : MPI_UNDEFINED,
                                      static_cast<int>(rank),
                                      &writers);
      AssertThrowMPI(ierr);
      const std::string h5 = name + "-" + number + ".h5";
      dealii::XDMFEntry entry;
      if (has_data)
        {
          data_out.write_hdf5_parallel(filter,
                                       output_directory + "/" + h5,
                                       writers);
          entry = data_out.create_xdmf_entry(filter, h5, time, writers);
          MPI_Comm_free(&writers);
        }
      entries.push_back(
        dealii::Utilities::MPI::broadcast(comm, entry, first_with_data));
      data_out.write_xdmf_file(entries,
                               output_directory + "/" + name + ".xdmf",
                               comm);
    }


    template class VisualizationOutput<2>;
    template class VisualizationOutput<3>;
  } // namespace IO
} // namespace Talus
