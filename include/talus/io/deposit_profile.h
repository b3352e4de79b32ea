#ifndef talus_io_deposit_profile_h
#define talus_io_deposit_profile_h

#include <talus/mpm/material_points.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <fstream>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace Talus
{
  namespace IO
  {
    /**
     * Geometry of a granular deposit measured from the material points
     * (granular column collapse: Bui et al. 2008, Lube et al. 2005), and
     * its comparison with reference values. Subsection "Deposit profile".
     *
     * Coordinates: s is the distance from the wall along the horizontal
     * axis, s = sign (x_h - wall position) with sign = +1 for flow towards
     * increasing x_h; v = x_v - base level is the height above the base.
     * Each point stands for a square (cube) of edge d_p, its 'point size':
     * V0^(1/dim) of its initial volume unless given.
     *
     * Definitions (all ranks gathered on rank 0 and sorted by (s, v, m), so
     * the result does not depend on the number of ranks):
     *  - runout L: sort the points by s, largest first, and accumulate their
     *    mass; the front point is the first one for which the mass summed so
     *    far exceeds 'runout mass fraction' times the total mass AND more
     *    than 'ignored outermost points' points have been summed;
     *    L = s_front + d_p/2. A few stray points ahead of the front thus do
     *    not move it. At the start this is the initial length L0.
     *  - maximum height H = max (v + d_p/2) over all points (H0 at t = 0).
     *  - free surface h(x) = max (v + d_p/2) over the points with
     *    |s - x| <= 'bin width'/2; 0 if the bin holds no point.
     *  - failure line s_f(v) (optional, with a reference failure line): in
     *    horizontal bands of initial height of width 'bin width', the
     *    largest initial s0 + d_p/2 of the points whose displacement from
     *    their initial position is below 'failure line displacement': the
     *    edge of the material that did not move (Bui et al. 2008, Fig. 10;
     *    0 if every point of the band moved).
     *
     * The profile (h on stations every bin width from the wall to beyond
     * the front) is written to <output directory>/deposit_profile.csv at
     * the end; the runout and maximum height can also be written every N
     * steps to deposit_time_series.csv; deposit_summary.csv holds the final
     * numbers (contrib/granular/run_collapse_series.sh collects them).
     */
    template <int dim>
    class DepositProfile
    {
    public:
      using Properties = MPM::MaterialPointProperties<dim>;

      /** One measurement. */
      struct Measurement
      {
        double              runout     = 0.; ///< L [m] from the wall
        double              max_height = 0.; ///< H [m] above the base
        double              mass       = 0.; ///< total mass [kg]
        std::vector<double> station_heights; ///< h at stations() [m]
        std::vector<std::pair<double, double>> profile; ///< (x, h) [m]
        /// failure line (v, s_f) at the band centres of the reference
        /// failure line [m]; empty without one
        std::vector<std::pair<double, double>> failure_line;
      };

      /**
       * The final deposit against its references (finalize()), for a
       * refinement study (subsection "Convergence study"). Errors without a
       * reference are NaN.
       */
      struct Comparison
      {
        double runout     = 0.; ///< L [m]
        double max_height = 0.; ///< H [m]
        /// (L - L_ref)/L_ref with the 'reference runout' [-]
        double runout_error = std::numeric_limits<double>::quiet_NaN();
        /// largest |h - h_ref| over the reference profile's stations [m]
        double max_height_error = std::numeric_limits<double>::quiet_NaN();
        /// root mean square of h - h_ref over those stations [m]
        double rms_height_error = std::numeric_limits<double>::quiet_NaN();
        /// every comparison of the table within its tolerance
        bool passed = true;
      };

      explicit DepositProfile(const MPI_Comm communicator);

      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Parse subsection "Deposit profile" and read the reference profile
       * file (ExcInvalidInput on bad values, unreadable or malformed file).
       */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      bool
      enabled() const
      {
        return active;
      }

      /**
       * Measure the initial points: L0 and H0 (unless given) and check the
       * Lube et al. aspect ratio. Opens the CSV time series in
       * @p output_directory.
       */
      void
      initialize(const MPM::MaterialPoints<dim> &points,
                 const std::string              &output_directory);

      /** Append to the time series if it is due at @p step. */
      void
      step(const unsigned int              step,
           const double                    time,
           const MPM::MaterialPoints<dim> &points);

      /**
       * Final measurement: write the profile and summary files, print the
       * result (and the comparison table) to @p out on rank 0. Returns
       * false if a comparison failed.
       */
      bool
      finalize(const MPM::MaterialPoints<dim> &points,
               std::ostream                   &out,
               const bool                      test_mode);

      /** The result of the last finalize() (on every rank). */
      const Comparison &
      comparison() const
      {
        return last_comparison;
      }

      /**
       * Measure the current state (collective); the failure line only with
       * @p with_failure_line (at the end: the time series does not use it).
       */
      Measurement
      measure(const MPM::MaterialPoints<dim> &points,
              const bool                      with_failure_line = false) const;

      /** Lube et al. 2005 (2D): predicted (L - L0)/L0 for aspect ratio a. */
      static double
      lube_runout(const double a);

      /** Lube et al. 2005 (2D): predicted H/L0 for aspect ratio a. */
      static double
      lube_height(const double a);

    private:
      /** Stations: those of the reference file, then the listed ones. */
      std::vector<double>
      stations() const;

      /**
       * Heights v at which the failure line is measured: band centres every
       * bin width over the height range of the reference failure line.
       */
      std::vector<double>
      failure_line_heights() const;

      /**
       * Reference failure line at height @p v: linear interpolation of the
       * file's (x, h) pairs in h.
       */
      double
      reference_failure_position(const double v) const;

      MPI_Comm communicator;
      bool     is_root;

      bool                active = false;
      unsigned int        horizontal;
      unsigned int        vertical;
      double              direction;
      double              wall_position;
      double              base_level;
      double              point_size;
      double              mass_fraction;
      unsigned int        ignored_points;
      double              bin_width;
      std::vector<double> listed_stations;
      unsigned int        series_interval;

      double                                 given_H0;
      double                                 given_L0;
      std::string                            reference_file;
      std::vector<std::pair<double, double>> reference_profile;
      std::string                            failure_line_file;
      /// (h, x) of the reference failure line, sorted by h
      std::vector<std::pair<double, double>> reference_failure_line;
      double                                 failure_displacement;
      double                                 failure_line_tolerance;
      double                                 reference_runout;
      double                                 runout_tolerance;
      double                                 height_tolerance;
      bool                                   compare_lube;
      double                                 lube_tolerance;

      double        H0 = 0.;
      double        L0 = 0.;
      std::string   directory;
      std::ofstream series;
      Comparison    last_comparison;
    };
  } // namespace IO
} // namespace Talus

#endif
