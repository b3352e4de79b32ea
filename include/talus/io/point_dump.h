#ifndef talus_io_point_dump_h
#define talus_io_point_dump_h

#include <talus/mpm/material_points.h>

#include <deal.II/base/mpi.h>

#include <string>

namespace Talus
{
  namespace IO
  {
    /**
     * Write every material point into the text file @p filename (rank 0):
     * one line per point, sorted by id, with the id, the position and all
     * properties in 17 digits. Collective. Used by the environment switch
     * TALUS_DEBUG_DUMP_POINTS (doc/debugging.md) for exact comparisons of
     * runs, e.g. by the checkpoint tests.
     */
    template <int dim>
    void
    write_points_text(const MPM::MaterialPoints<dim> &points,
                      const std::string              &filename,
                      const MPI_Comm                  communicator);
  } // namespace IO
} // namespace Talus

#endif
