#ifndef talus_io_structure_time_series_h
#define talus_io_structure_time_series_h

#include <talus/structure/structure.h>

#include <deal.II/lac/vector.h>

#include <fstream>
#include <string>
#include <vector>

namespace Talus
{
  namespace IO
  {
    /**
     * The barrier's time series, what an engineer reads off a coupled run:
     * `structure.csv`, one row per step (rank 0): time; for every line
     * mesh (net cables, posts, ropes, brakes) the axial force of largest
     * magnitude, signed (tension positive) [N]; for every brake mesh also
     * the largest stroke [m]; the energy the structure has dissipated
     * (brakes, truss plasticity, Rayleigh damping;
     * Structure::StructureProblem::dissipated_energy()) [J]; the largest
     * nodal displacement [m]; then the model's own columns
     * (StructureModels::Model::impact_columns()). In a 2D problem forces are
     * per metre of width. The forces are those of the structure's last
     * assembly: call write() after Structure::assemble() at the committed
     * state.
     */
    class StructureTimeSeries
    {
    public:
      /** Open @p filename and write the header (only if @p root), with
       * the model's own columns @p extra_names after the standard ones. */
      void
      open(const std::string                 &filename,
           const Talus::Structure::Structure &structure,
           const bool                         root,
           const std::vector<std::string>    &extra_names = {});

      /**
       * Continue the series of a resumed run (doc/checkpoint.md): replace
       * @p filename (only if @p root) by a copy of the file @p saved, the
       * header and the rows up to the checkpoint (the checkpoint's copy of
       * the file), and append the next rows to it. @p n_extra_columns: the
       * model's own columns, as in open().
       */
      void
      resume(const std::string &filename,
             const std::string &saved,
             const bool         root,
             const std::size_t  n_extra_columns);

      /** One row. */
      void
      write(const double                       time,
            const Talus::Structure::Structure &structure,
            const dealii::Vector<double>      &displacement,
            const double                       dissipated_energy,
            const std::vector<double>         &extra_values = {});

    private:
      std::ofstream file;
      std::size_t   n_extra = 0; ///< model columns in the header
    };
  } // namespace IO
} // namespace Talus

#endif
