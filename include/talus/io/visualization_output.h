#ifndef talus_io_visualization_output_h
#define talus_io_visualization_output_h

#include <talus/mpm/background_grid.h>
#include <talus/mpm/material_points.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <string>
#include <utility>
#include <vector>

namespace Talus
{
  namespace IO
  {
    /**
     * Writes the material points (all their properties) and the background
     * grid (with the number of points per cell) for ParaView: VTU pieces
     * per rank, a PVTU record per output and a PVD file indexing them by
     * time; optionally HDF5 + XDMF instead.
     *
     * Files: <directory>/particles.pvd, particles-NNNNN.pvtu,
     * grid.pvd, grid-NNNNN.pvtu (or particles.xdmf / grid.xdmf with .h5).
     */
    template <int dim>
    class VisualizationOutput
    {
    public:
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse the output entries of subsection "Output". */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Create the output directory (rank 0) on all ranks' behalf. */
      void
      initialize(const MPI_Comm communicator);

      /** Is an output due at @p time (the last output was before)? */
      bool
      due(const double time) const;

      /**
       * Write the material points and (with 'write grid') the background
       * grid with the number of points per cell, the subdomain and, when
       * @p grid_velocity is given and not empty, the nodal grid velocity
       * of the last step (MPM::MPMSolver::grid_velocity()).
       */
      void
      write(
        const double                                 time,
        const MPM::BackgroundGrid<dim>              &grid,
        const MPM::MaterialPoints<dim>              &points,
        const dealii::TrilinosWrappers::MPI::Vector *grid_velocity = nullptr);

      const std::string &
      directory() const
      {
        return output_directory;
      }

      /** Visualization files are written (format is not 'none'). */
      bool
      writes_files() const
      {
        return enabled;
      }

      /**
       * Read or write the record of the outputs so far with a boost
       * archive (checkpoints): the output counter, the time of the last
       * output and the entries of the PVD or XDMF index files.
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int /*version*/)
      {
        ar &counter &last_output_time &particle_records &grid_records
          &particle_xdmf &grid_xdmf;
      }

      /**
       * Rewrite the index files (particles.pvd and grid.pvd, or the .xdmf
       * files) from the records, e.g. after a resume: the outputs a killed
       * run wrote after its checkpoint are no longer listed (and are
       * overwritten by the resumed run). Collective.
       */
      void
      write_index(const MPI_Comm communicator) const;

      double output_interval = 0.;

    private:
      /**
       * Write one HDF5 file `name`-`number`.h5 of @p data_out with the ranks
       * that have data (@p has_data) and rewrite `name`.xdmf with the new
       * entry appended to @p entries (kept on every rank).
       */
      template <typename DataOutType>
      void
      write_hdf5(const DataOutType                        &data_out,
                 const dealii::DataOutBase::DataOutFilter &filter,
                 bool                                      has_data,
                 const std::string                        &name,
                 const std::string                        &number,
                 double                                    time,
                 MPI_Comm                                  comm,
                 std::vector<dealii::XDMFEntry>           &entries) const;

      std::string                                 output_directory;
      std::string                                 format;
      bool                                        write_grid       = true;
      bool                                        enabled          = true;
      unsigned int                                counter          = 0;
      double                                      last_output_time = -1e300;
      std::vector<std::pair<double, std::string>> particle_records;
      std::vector<std::pair<double, std::string>> grid_records;
      std::vector<dealii::XDMFEntry>              particle_xdmf;
      std::vector<dealii::XDMFEntry>              grid_xdmf;
    };
  } // namespace IO
} // namespace Talus

#endif
