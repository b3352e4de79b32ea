#ifndef talus_io_probe_history_h
#define talus_io_probe_history_h

#include <talus/mpm/material_points.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace Talus
{
  namespace IO
  {
    /**
     * History of the mean displacement of the material points that start
     * in a box (subsection "Probe history"), e.g. the tip of a cantilever,
     * and its comparison with a reference history u_ref(t) (an independent
     * FE solution, contrib/reference/). The probe value after every step
     * is the mass-weighted mean
     *   u(t) = sum_p m_p (x_p(t) - X_p) / sum_p m_p
     * over the points whose initial position X_p lies in the box (points
     * of equal volume per cell fill it: the midpoint rule of the region's
     * mean int u dV0 / V0). It is written to probe_history.csv in the
     * output directory. Against the reference (linearly interpolated in
     * time, component 'component') at the end of the run:
     *  - relative L2-in-time error e = (int_0^T (u - u_ref)^2 dt /
     *    int_0^T u_ref^2 dt)^(1/2), trapezoidal rule over the steps;
     *  - the peak: the extreme value of u over the run and its time, with
     *    the relative error |u_peak - u_ref,peak| / |u_ref,peak|.
     */
    template <int dim>
    class ProbeHistory
    {
    public:
      explicit ProbeHistory(const MPI_Comm communicator);

      /** Declare subsection "Probe history". */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read it (and the reference file). */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** A box is given. */
      bool
      enabled() const
      {
        return active;
      }

      /** Open probe_history.csv in @p directory (after the output
       * directory exists). */
      void
      open(const std::string &directory);

      /** Record the probe at time @p t (collective). */
      void
      record(const double t, const MPM::MaterialPoints<dim> &points);

      /** Print the peak and the errors against the reference; returns
       * false if a tolerance is exceeded. */
      bool
      finalize(std::ostream &out);

    private:
      MPI_Comm                               communicator;
      bool                                   is_root = false;
      bool                                   active  = false;
      dealii::Point<dim>                     lower, upper;
      unsigned int                           component = dim - 1;
      std::string                            reference_file;
      std::vector<std::pair<double, double>> reference;
      double                                 tolerance      = 0.;
      double                                 peak_tolerance = 0.;
      std::vector<double>                    times;
      std::vector<dealii::Tensor<1, dim>>    values;
      unsigned int                           n_points = 0;
      std::ofstream                          file;
      inline static const std::string        section = "Probe history";
    };
  } // namespace IO
} // namespace Talus

#endif
